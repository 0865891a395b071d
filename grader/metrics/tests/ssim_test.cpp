// SSIM: values derived by hand from the formula (flat images, where the variances vanish),
// symmetry, monotonicity in noise, masks, and agreement with scikit-image.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "grader/metrics/metrics.h"
#include "test_images.h"

namespace grader {
namespace {

using test::greyImage;

constexpr double kC1 = 0.01 * 0.01;  // (K1 L)^2, L = 1

// Flat images: every window has zero variance and covariance, so SSIM is the luminance term
// alone, (2 mu_x mu_y + C1) / (mu_x^2 + mu_y^2 + C1), at every pixel.
double flatSsim(double a, double b) { return (2 * a * b + kC1) / (a * a + b * b + kC1); }

TEST(Ssim, IdenticalImagesGiveOne) {
    const Image image = test::patternImage(40, 30);
    const SsimResult result = computeSsim(image, image);
    ASSERT_TRUE(result.ok) << result.error;
    EXPECT_NEAR(result.ssim, 1.0, 1e-12);
    EXPECT_EQ(result.channel_count, 3);
    EXPECT_EQ(result.pixel_count,
              static_cast<std::size_t>((40 - 10) * (30 - 10)));  // 5-pixel border left out
}

TEST(Ssim, FlatImagesGiveTheLuminanceTerm) {
    for (const auto& pair :
         {std::pair<float, float>{0.2f, 0.7f}, {0.5f, 0.5f}, {1.0f, 0.2f}, {0.0f, 1.0f}, {0.999f, 0.998f}}) {
        const SsimResult result = computeSsim(greyImage(16, 16, pair.first), greyImage(16, 16, pair.second));
        ASSERT_TRUE(result.ok);
        // Tight: a variance computed in float as E[x^2] - E[x]^2 would be off by ~1e-7, which
        // the 1 / C2 sensitivity of flat regions turns into ~1e-4 here.
        EXPECT_NEAR(result.ssim, flatSsim(pair.first, pair.second), 1e-7)
            << pair.first << " vs " << pair.second;
    }
}

TEST(Ssim, ChannelsAreAveraged) {
    // Per channel the flat formula; the result is the mean of the three.
    const Image a = test::constantImage(12, 12, 0.1f, 0.5f, 0.9f);
    const Image b = test::constantImage(12, 12, 0.3f, 0.5f, 0.4f);
    const SsimResult result = computeSsim(a, b);
    ASSERT_TRUE(result.ok);
    const double expected[3] = {flatSsim(0.1f, 0.3f), 1.0, flatSsim(0.9f, 0.4f)};
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(result.channel_ssim[c], expected[c], 1e-7);
    EXPECT_NEAR(result.ssim, (expected[0] + expected[1] + expected[2]) / 3.0, 1e-7);
}

TEST(Ssim, GreyImagesUseOneChannel) {
    const SsimResult result = computeSsim(greyImage(11, 11, 0.25f, 1), greyImage(11, 11, 0.75f, 1));
    ASSERT_TRUE(result.ok);
    EXPECT_EQ(result.channel_count, 1);
    EXPECT_EQ(result.pixel_count, 1u);  // an 11x11 image has one pixel inside the border
    EXPECT_NEAR(result.ssim, flatSsim(0.25, 0.75), 1e-7);
}

TEST(Ssim, IsSymmetric) {
    const Image a = test::patternImage(48, 40);
    const Image b = test::withNoise(test::patternImage(48, 40, 0.3), 0.1f, 7);
    const double ab = computeSsim(a, b).ssim;
    const double ba = computeSsim(b, a).ssim;
    EXPECT_LT(ab, 0.99);
    EXPECT_NEAR(ab, ba, 1e-9);
}

TEST(Ssim, DecreasesAsNoiseGrows) {
    const Image clean = test::patternImage(64, 64);
    double previous = 1.0;
    for (float amplitude : {0.01f, 0.03f, 0.1f, 0.3f}) {
        const double value = computeSsim(clean, test::withNoise(clean, amplitude, 99)).ssim;
        EXPECT_LT(value, previous) << "noise amplitude " << amplitude;
        previous = value;
    }
    EXPECT_LT(previous, 0.7);
}

TEST(Ssim, AgreesWithScikitImage) {
    // grader/metrics/tests/reference/ssim_reference.py: scikit-image 0.19.3's
    // structural_similarity(gaussian_weights=True, sigma=1.5, use_sample_covariance=False,
    // data_range=1, channel_axis=-1) on this pair prints 0.8871646471.
    const Image reference = test::patternImage(64, 48);
    const Image test_image = test::withNoise(test::patternImage(64, 48, 0.4), 0.05f, 1234);
    const SsimResult result = computeSsim(reference, test_image);
    ASSERT_TRUE(result.ok);
    EXPECT_NEAR(result.ssim, 0.8871646471, 1e-6);
}

// SSIM per pixel and channel straight from the definition, in double: the 11x11 Gaussian
// window's weights (sigma 1.5, as computeSsim's) applied to the five moments of x and y, with
// scipy's "reflect" border (a b c | c b a). The map is averaged over the channels like
// SsimResult::map.
std::vector<double> directSsimMap(const Image& a, const Image& b) {
    constexpr int kRadius = 5;
    double weights[2 * kRadius + 1], total = 0.0;
    for (int k = -kRadius; k <= kRadius; ++k)
        total += weights[k + kRadius] = std::exp(-k * k / (2 * 1.5 * 1.5));
    for (double& w : weights) w /= total;
    auto reflect = [](int i, int n) { return i < 0 ? -i - 1 : (i >= n ? 2 * n - i - 1 : i); };
    const double c2 = 0.03 * 0.03;
    std::vector<double> map(static_cast<std::size_t>(a.width) * a.height, 0.0);
    for (int c = 0; c < 3; ++c) {
        for (int y = 0; y < a.height; ++y) {
            for (int x = 0; x < a.width; ++x) {
                double mx = 0, my = 0, mxx = 0, myy = 0, mxy = 0;
                for (int j = -kRadius; j <= kRadius; ++j) {
                    for (int i = -kRadius; i <= kRadius; ++i) {
                        const double w = weights[i + kRadius] * weights[j + kRadius];
                        const int sx = reflect(x + i, a.width), sy = reflect(y + j, a.height);
                        const double u = a.at(sx, sy, c), v = b.at(sx, sy, c);
                        mx += w * u;
                        my += w * v;
                        mxx += w * u * u;
                        myy += w * v * v;
                        mxy += w * u * v;
                    }
                }
                const double vx = mxx - mx * mx, vy = myy - my * my, cov = mxy - mx * my;
                map[static_cast<std::size_t>(y) * a.width + x] +=
                    (2 * mx * my + kC1) * (2 * cov + c2) / ((mx * mx + my * my + kC1) * (vx + vy + c2)) / 3.0;
            }
        }
    }
    return map;
}

TEST(Ssim, SmallDifferencesInFloatStayWithinTheirBound) {
    // computeSsim takes the moments of d = x - y in float where every |d| in a window is at most
    // 1/16 (ssim.cpp). The worst case is a flat offset just below that, where both variances
    // vanish and the 1 / C2 sensitivity is largest; then noise; then images whose rows alternate
    // in bands between small and large differences, so that windows mix float and double rows.
    const Image pattern = test::patternImage(48, 40);
    Image offset = pattern, banded = pattern;
    for (int y = 0; y < pattern.height; ++y) {
        for (int x = 0; x < pattern.width; ++x) {
            for (int c = 0; c < 3; ++c) {
                offset.at(x, y, c) = pattern.at(x, y, c) * 0.01f + 0.3f;
                banded.at(x, y, c) = (y / 7) % 2 ? 1.0f - pattern.at(x, y, c) : pattern.at(x, y, c) + 0.03f;
            }
        }
    }
    Image offset_by_a_sixteenth = offset, offset_by_a_quarter = offset;
    for (float& v : offset_by_a_sixteenth.pixels) v += 0.0624f;
    for (float& v : offset_by_a_quarter.pixels) v += 0.25f;
    const struct {
        const char* name;
        Image a, b;
    } cases[] = {{"flat offset of 0.0624", offset, offset_by_a_sixteenth},
                 {"flat offset of 0.25 (in double)", offset, offset_by_a_quarter},
                 {"noise", pattern, test::withNoise(pattern, 0.03f, 77)},
                 {"bands", pattern, banded}};
    for (const auto& c : cases) {
        SsimConfig config;
        config.want_map = true;
        const SsimResult result = computeSsim(c.a, c.b, config);
        ASSERT_TRUE(result.ok) << result.error;
        const std::vector<double> direct = directSsimMap(c.a, c.b);
        double worst = 0.0;
        for (std::size_t i = 0; i < direct.size(); ++i)
            worst = std::max(worst, std::abs(result.map[i] - direct[i]));
        // The map is stored in float (its rounding ~6e-8 is part of what is measured). Measured:
        // 1.2e-6 for the offset of 0.0624 (1.3e-7 with everything in double), 1.9e-7 or less
        // for the others; float moments for the offset of 0.25 would be off by ~2e-5.
        EXPECT_LT(worst, 2e-6) << c.name;
        RecordProperty(std::string(c.name) + ": largest difference per pixel",
                       std::to_string(worst * 1e9) + "e-9");
    }
}

TEST(Ssim, MaskedMeanIsTheMeanOfTheMapOverMaskedInteriorPixels) {
    const Image a = test::patternImage(40, 32);
    const Image b = test::withNoise(a, 0.2f, 5);
    Mask mask(40, 32, 0);
    for (int y = 0; y < 32; ++y) {
        for (int x = 0; x < 40; ++x) mask.at(x, y) = (x + 2 * y) % 7 < 3 ? 1 : 0;
    }
    SsimConfig config;
    config.mask = &mask;
    config.want_map = true;
    const SsimResult result = computeSsim(a, b, config);
    ASSERT_TRUE(result.ok);
    ASSERT_EQ(result.map.size(), 40u * 32u);
    double sum = 0.0;
    std::size_t count = 0;
    for (int y = 5; y < 32 - 5; ++y) {
        for (int x = 5; x < 40 - 5; ++x) {
            if (!mask.at(x, y)) continue;
            sum += result.map[static_cast<std::size_t>(y) * 40 + x];
            ++count;
        }
    }
    EXPECT_EQ(result.pixel_count, count);
    EXPECT_NEAR(result.ssim, sum / count, 1e-6);
    // Unmasked, the mean differs (the mask is not a random subset of equal value).
    EXPECT_NE(computeSsim(a, b).ssim, result.ssim);
}

TEST(Ssim, StructureChangeWithEqualMeansLowersIt) {
    // Same mean everywhere, different structure: a checkerboard against flat grey.
    Image checker = greyImage(32, 32, 0.0f);
    for (int y = 0; y < 32; ++y) {
        for (int x = 0; x < 32; ++x) {
            for (int c = 0; c < 3; ++c) checker.at(x, y, c) = ((x + y) % 2) ? 0.7f : 0.3f;
        }
    }
    const SsimResult result = computeSsim(checker, greyImage(32, 32, 0.5f));
    ASSERT_TRUE(result.ok);
    EXPECT_LT(result.ssim, 0.1);
}

TEST(Ssim, RejectsImagesSmallerThanTheWindow) {
    const SsimResult result = computeSsim(greyImage(10, 20, 0.5f), greyImage(10, 20, 0.5f));
    EXPECT_FALSE(result.ok);
    EXPECT_NE(result.error.find("11x11"), std::string::npos) << result.error;
}

TEST(Ssim, RejectsAMaskWithNothingInsideTheBorder) {
    Mask mask(20, 20, 0);
    mask.at(0, 0) = 1;  // only a border pixel
    SsimConfig config;
    config.mask = &mask;
    EXPECT_FALSE(computeSsim(greyImage(20, 20, 0.5f), greyImage(20, 20, 0.5f), config).ok);
}

}  // namespace
}  // namespace grader
