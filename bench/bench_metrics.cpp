// Times the grader's metrics on a 512x512 RGB pair, one thread: PSNR, SSIM and FLIP alone and
// all three together (the target: all three at most 10 ms on one core), the shift-tolerant
// comparison, what grading one image costs (judgeImage: all of them on 8-bit quantised copies),
// the same for two bit-identical images (the metrics' fast path), and all three over image sizes
// 64..1024 for the size curve in docs/performance.md. It does not check results; the tests do.
//
// Inputs: a smooth colour gradient with deterministic noise (own LCG, so the pixels are the
// same on every platform and standard library), and the same gradient with different noise,
// shifted by a fraction of a pixel: a realistic "almost right" student image.
//
//   cmake --build build --target bench_metrics && ./build/bench/bench_metrics
#include <cstdlib>  // defines __GLIBC__ on glibc
#if defined(__GLIBC__)
#include <malloc.h>
#endif
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>

#include "grader/metrics/compare.h"
#include "grader/metrics/image.h"
#include "grader/metrics/metrics.h"
#include "grader/metrics/scoring.h"

namespace {

constexpr int kSize = 512;

class Lcg {
  public:
    explicit Lcg(std::uint32_t seed) : state_(seed) {}
    float uniform() {  // [0, 1)
        state_ = state_ * 1664525u + 1013904223u;
        return static_cast<float>(state_ >> 8) / 16777216.0f;
    }

  private:
    std::uint32_t state_;
};

grader::Image gradientWithNoise(std::uint32_t seed, float shift, float noise, int size = kSize) {
    grader::Image image(size, size, 3);
    Lcg random(seed);
    for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
            const float u = (x + shift) / size;
            const float v = static_cast<float>(y) / size;
            const float base[3] = {u, v, 0.5f + 0.5f * std::sin(6.0f * (u + v))};
            for (int c = 0; c < 3; ++c) {
                const float value = base[c] + noise * (random.uniform() - 0.5f);
                image.at(x, y, c) = value < 0.0f ? 0.0f : (value > 1.0f ? 1.0f : value);
            }
        }
    }
    return image;
}

struct Pair {
    grader::Image reference = gradientWithNoise(1, 0.0f, 0.04f);
    grader::Image test = gradientWithNoise(2, 0.3f, 0.04f);
};

const Pair& pair() {
    static const Pair images;
    return images;
}

void BM_Psnr(benchmark::State& state) {
    const Pair& p = pair();
    for (auto _ : state) benchmark::DoNotOptimize(grader::computePsnr(p.reference, p.test).psnr_db);
}

void BM_Ssim(benchmark::State& state) {
    const Pair& p = pair();
    for (auto _ : state) benchmark::DoNotOptimize(grader::computeSsim(p.reference, p.test).ssim);
}

void BM_Flip(benchmark::State& state) {
    const Pair& p = pair();
    for (auto _ : state) benchmark::DoNotOptimize(grader::computeFlip(p.reference, p.test).mean);
}

// What grading one image costs: the three metrics, FLIP keeping its error map for the heat map.
void BM_AllThree(benchmark::State& state) {
    const Pair& p = pair();
    for (auto _ : state) {
        benchmark::DoNotOptimize(grader::computePsnr(p.reference, p.test).psnr_db);
        benchmark::DoNotOptimize(grader::computeSsim(p.reference, p.test).ssim);
        benchmark::DoNotOptimize(grader::computeFlip(p.reference, p.test).mean);
    }
}

void BM_ShiftTolerantCompare(benchmark::State& state) {
    const Pair& p = pair();
    for (auto _ : state) {
        benchmark::DoNotOptimize(grader::compareShiftTolerant(p.reference, p.test).mismatch_count);
    }
}

// grader::judgeImage: 8-bit quantisation, then every metric (with FLIP's map) over the frame.
void BM_JudgeImage(benchmark::State& state) {
    const Pair& p = pair();
    for (auto _ : state)
        benchmark::DoNotOptimize(
            grader::judgeImage(p.reference, {}, p.test, {}, grader::Thresholds{}).passed);
}

// The same for a student image bit-identical to the reference (a correct solution on the
// reference's machine): the metrics see equal inputs and skip their filters.
void BM_JudgeImageIdentical(benchmark::State& state) {
    const Pair& p = pair();
    for (auto _ : state)
        benchmark::DoNotOptimize(
            grader::judgeImage(p.reference, {}, p.reference, {}, grader::Thresholds{}).passed);
}

// The "before" of the fast path: the reference against itself with one value one float step
// off, so every metric runs in full on what is, to the eye and the verdict, the same image.
void BM_JudgeImageNearlyIdentical(benchmark::State& state) {
    const Pair& p = pair();
    grader::Image nearly = p.reference;
    nearly.pixels[12345] = 0.5f;  // quantised to 8 bits differently from the reference's value
    if (nearly.pixels[12345] == p.reference.pixels[12345]) nearly.pixels[12345] = 0.25f;
    for (auto _ : state)
        benchmark::DoNotOptimize(
            grader::judgeImage(p.reference, {}, nearly, {}, grader::Thresholds{}).passed);
}

// PSNR + SSIM + FLIP at state.range(0) x state.range(0).
void BM_AllThreeBySize(benchmark::State& state) {
    const int size = static_cast<int>(state.range(0));
    const grader::Image a = gradientWithNoise(1, 0.0f, 0.04f, size),
                        b = gradientWithNoise(2, 0.3f, 0.04f, size);
    for (auto _ : state) {
        benchmark::DoNotOptimize(grader::computePsnr(a, b).psnr_db);
        benchmark::DoNotOptimize(grader::computeSsim(a, b).ssim);
        benchmark::DoNotOptimize(grader::computeFlip(a, b).mean);
    }
    state.counters["pixels"] = static_cast<double>(size) * size;
}

// SSIM alone at state.range(0) x state.range(0), for the size table's comparison with
// scikit-image's structural_similarity (timed by bench/run_bench.py where it is installed).
void BM_SsimBySize(benchmark::State& state) {
    const int size = static_cast<int>(state.range(0));
    const grader::Image a = gradientWithNoise(1, 0.0f, 0.04f, size),
                        b = gradientWithNoise(2, 0.3f, 0.04f, size);
    for (auto _ : state) benchmark::DoNotOptimize(grader::computeSsim(a, b).ssim);
    state.counters["pixels"] = static_cast<double>(size) * size;
}

}  // namespace

BENCHMARK(BM_JudgeImage)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_JudgeImageIdentical)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_JudgeImageNearlyIdentical)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AllThreeBySize)->RangeMultiplier(2)->Range(64, 1024)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SsimBySize)->RangeMultiplier(2)->Range(64, 1024)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Psnr)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Ssim)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Flip)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AllThree)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ShiftTolerantCompare)->Unit(benchmark::kMillisecond);

// The allocator as the shaderlab program sets it (framework/cli/main.cpp): large blocks kept in
// the heap, so that each call does not pay the kernel's page faults for its images again.
int main(int argc, char** argv) {
#if defined(__GLIBC__)
    mallopt(M_MMAP_THRESHOLD, 64 << 20);
    mallopt(M_TRIM_THRESHOLD, 256 << 20);
#endif
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
