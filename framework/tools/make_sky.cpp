// shaderlab_make_sky <out_dir>: writes the course's sky cube map (analytic_sky.h) as PNG faces:
// sky_{px,nx,py,ny,pz,nz}.png at 64x64 and sky_small_*.png at 16x16 (each small texel the mean of
// the 4x4 large texels it covers, for convolutions that visit every texel). Deterministic: the
// same bytes on every run. Run it through scripts/regenerate_scenes.sh; tests/sky_test.cpp fails
// when the committed faces are stale.
#include <cstdio>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include "analytic_sky.h"
#include "grader/metrics/image.h"

namespace fs = std::filesystem;

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: shaderlab_make_sky <out_dir>\n");
        return 2;
    }
    const fs::path dir = argv[1];
    std::error_code ec;
    fs::create_directories(dir, ec);
    const char* names[6] = {"px", "nx", "py", "ny", "pz", "nz"};
    constexpr int kLarge = 64, kSmall = 16, kRatio = kLarge / kSmall;
    for (int f = 0; f < 6; ++f) {
        std::vector<glm::dvec3> large(static_cast<std::size_t>(kLarge * kLarge));
        grader::Image big(kLarge, kLarge, 3);
        for (int j = 0; j < kLarge; ++j)
            for (int i = 0; i < kLarge; ++i) {
                const glm::dvec3 c = shaderlab::sky::texel(f, i, j, kLarge);
                large[static_cast<std::size_t>(j * kLarge + i)] = c;
                for (int k = 0; k < 3; ++k) big.at(i, j, k) = static_cast<float>(c[k]);
            }
        grader::Image small(kSmall, kSmall, 3);
        for (int j = 0; j < kSmall; ++j)
            for (int i = 0; i < kSmall; ++i) {
                glm::dvec3 sum(0.0);
                for (int b = 0; b < kRatio; ++b)
                    for (int a = 0; a < kRatio; ++a)
                        sum += large[static_cast<std::size_t>((j * kRatio + b) * kLarge + i * kRatio + a)];
                for (int k = 0; k < 3; ++k)
                    small.at(i, j, k) = static_cast<float>(sum[k] / (kRatio * kRatio));
            }
        std::string err;
        if (!grader::writePng(big, (dir / (std::string("sky_") + names[f] + ".png")).string(), &err) ||
            !grader::writePng(small, (dir / (std::string("sky_small_") + names[f] + ".png")).string(),
                              &err)) {
            std::fprintf(stderr, "shaderlab_make_sky: %s\n", err.c_str());
            return 1;
        }
    }
    return 0;
}
