// Times the grader's metrics on a 512x512 RGB pair, one thread: PSNR, SSIM and FLIP alone and
// all three together (the requirement: all three under 20 ms on one core), plus the
// shift-tolerant comparison for information. It does not check results; the tests do that.
//
// Inputs: a smooth colour gradient with deterministic noise (own LCG, so the pixels are the
// same on every platform and standard library), and the same gradient with different noise,
// shifted by a fraction of a pixel: a realistic "almost right" student image.
//
//   cmake --build build --target bench_metrics && ./build/bench/bench_metrics
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>

#include "grader/compare.h"
#include "grader/image.h"
#include "grader/metrics.h"

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

grader::Image gradientWithNoise(std::uint32_t seed, float shift, float noise) {
    grader::Image image(kSize, kSize, 3);
    Lcg random(seed);
    for (int y = 0; y < kSize; ++y) {
        for (int x = 0; x < kSize; ++x) {
            const float u = (x + shift) / kSize;
            const float v = static_cast<float>(y) / kSize;
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

}  // namespace

BENCHMARK(BM_Psnr)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Ssim)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Flip)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AllThree)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ShiftTolerantCompare)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
