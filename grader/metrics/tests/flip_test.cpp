// LDR-FLIP: a value derived by hand (black against white), zero for identical images,
// symmetry, monotonicity, locality of the filters, pooling against its definition, masks, and
// agreement with an independent double-precision implementation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "grader/metrics/metrics.h"
#include "test_images.h"

namespace grader {
namespace {

using test::greyImage;

// ---- the hand derivation for flat black against flat white ------------------------------
// On flat images the filters change nothing (they sum to 1) and every edge and point detector
// gives 0, so the feature error is 0 and the FLIP error is the colour error itself:
//   HyAB(Hunt(Lab(black)), Hunt(Lab(white)))^0.7, redistributed with cmax, pc = 0.4, pt = 0.95.
struct Lab {
    double l, a, b;
};

// sRGB linear -> XYZ (the sRGB primaries, D65), divided by the white point, -> CIELab, then
// Hunt: a and b scaled by 0.01 L.
Lab huntLab(double r, double g, double b) {
    const double m[3][3] = {{10135552.0 / 24577794, 8788810.0 / 24577794, 4435075.0 / 24577794},
                            {2613072.0 / 12288897, 8788810.0 / 12288897, 887015.0 / 12288897},
                            {1425312.0 / 73733382, 8788810.0 / 73733382, 70074185.0 / 73733382}};
    const double white[3] = {0.950428545, 1.0, 1.088900371};
    double f[3];
    for (int i = 0; i < 3; ++i) {
        const double t = (m[i][0] * r + m[i][1] * g + m[i][2] * b) / white[i];
        const double delta = 6.0 / 29.0;
        f[i] = t > delta * delta * delta ? std::cbrt(t) : t / (3 * delta * delta) + 4.0 / 29.0;
    }
    const double l = 116 * f[1] - 16;
    return {l, 0.01 * l * 500 * (f[0] - f[1]), 0.01 * l * 200 * (f[1] - f[2])};
}

double hyab(const Lab& p, const Lab& q) { return std::abs(p.l - q.l) + std::hypot(p.a - q.a, p.b - q.b); }

double flatColourError(double distance) {
    const double cmax = std::pow(hyab(huntLab(0, 1, 0), huntLab(0, 0, 1)), 0.7);  // green against blue
    const double pccmax = 0.4 * cmax;
    const double compressed = std::pow(distance, 0.7);
    return compressed < pccmax ? compressed * 0.95 / pccmax
                               : 0.95 + (compressed - pccmax) / (cmax - pccmax) * 0.05;
}

TEST(Flip, BlackAgainstWhiteMatchesTheHandDerivation) {
    // White is L = 100, a = b = 0; black L = 0 (f(0) = 4/29): HyAB = 100, 100^0.7 = 25.119;
    // cmax = 41.276, pc * cmax = 16.510, so the error is 0.95 + (25.119 - 16.510) / (41.276 -
    // 16.510) * 0.05 = 0.96738.
    const Lab white = huntLab(1, 1, 1), black = huntLab(0, 0, 0);
    EXPECT_NEAR(white.l, 100.0, 1e-6);
    EXPECT_NEAR(black.l, 0.0, 1e-9);
    const double expected = flatColourError(hyab(white, black));
    EXPECT_NEAR(expected, 0.96738, 1e-5);

    const FlipResult result = computeFlip(greyImage(24, 16, 0.0f), greyImage(24, 16, 1.0f));
    ASSERT_TRUE(result.ok) << result.error;
    EXPECT_NEAR(result.mean, expected, 1e-4);
    // Flat everywhere, so every pixel has that error, and so do the percentiles.
    for (float e : result.error_map) EXPECT_NEAR(e, expected, 1e-4);
    EXPECT_NEAR(result.weighted_median, expected, 1e-4);
    EXPECT_NEAR(result.weighted_p25, expected, 1e-4);
    EXPECT_NEAR(result.max_error, expected, 1e-4);
}

TEST(Flip, FlatColourPairsMatchTheHandDerivation) {
    // The same reasoning for flat colours: only the colour pipeline matters.
    struct Case {
        float a[3], b[3];
    };
    const auto linear = [](float v) {
        return v <= 0.04045f ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
    };
    for (const Case& c : {Case{{0.2f, 0.4f, 0.6f}, {0.25f, 0.4f, 0.6f}}, Case{{1, 0, 0}, {0, 1, 0}},
                          Case{{0.5f, 0.5f, 0.5f}, {0.6f, 0.5f, 0.5f}}}) {
        const Lab p = huntLab(linear(c.a[0]), linear(c.a[1]), linear(c.a[2]));
        const Lab q = huntLab(linear(c.b[0]), linear(c.b[1]), linear(c.b[2]));
        const FlipResult result = computeFlip(test::constantImage(20, 20, c.a[0], c.a[1], c.a[2]),
                                              test::constantImage(20, 20, c.b[0], c.b[1], c.b[2]));
        ASSERT_TRUE(result.ok);
        EXPECT_NEAR(result.mean, flatColourError(hyab(p, q)), 1e-4);
    }
}

TEST(Flip, IdenticalImagesGiveZero) {
    const Image image = test::patternImage(37, 29);
    const FlipResult result = computeFlip(image, image);
    ASSERT_TRUE(result.ok);
    EXPECT_EQ(result.mean, 0.0);
    EXPECT_EQ(result.max_error, 0.0f);
    EXPECT_EQ(result.weighted_median, 0.0);
    EXPECT_EQ(result.error_map.size(), 37u * 29u);
}

TEST(Flip, IsSymmetric) {
    // HyAB and the feature difference are both symmetric, so swapping the images changes
    // nothing but rounding.
    const Image a = test::patternImage(50, 40);
    const Image b = test::withNoise(test::patternImage(50, 40, 0.5), 0.1f, 3);
    const FlipResult ab = computeFlip(a, b), ba = computeFlip(b, a);
    EXPECT_GT(ab.mean, 0.05);
    EXPECT_NEAR(ab.mean, ba.mean, 1e-6);
}

TEST(Flip, GrowsWithAGreyStep) {
    double previous = 0.0;
    for (int step = 1; step <= 8; ++step) {
        const double value =
            computeFlip(greyImage(16, 16, 0.5f), greyImage(16, 16, 0.5f + 0.05f * step)).mean;
        EXPECT_GT(value, previous) << "step " << step;
        previous = value;
    }
}

TEST(Flip, OnePixelChangeStaysWithinTheFilterRadius) {
    // The colour filters reach 10 pixels at 67 ppd and the feature filters 9: beyond 10 pixels
    // both images filter to the same values and the error is exactly 0.
    const Image reference = greyImage(64, 64, 0.4f);
    Image test_image = reference;
    for (int c = 0; c < 3; ++c) test_image.at(32, 30, c) = 0.9f;
    const FlipResult result = computeFlip(reference, test_image);
    ASSERT_TRUE(result.ok);
    for (int y = 0; y < 64; ++y) {
        for (int x = 0; x < 64; ++x) {
            const float e = result.error_map[static_cast<std::size_t>(y) * 64 + x];
            if (std::abs(x - 32) > 10 || std::abs(y - 30) > 10) {
                ASSERT_EQ(e, 0.0f) << "at " << x << "," << y;
            }
        }
    }
    EXPECT_GT(result.error_map[30 * 64 + 32], 0.1f);
    EXPECT_EQ(result.max_error, result.error_map[30 * 64 + 32]);
}

TEST(Flip, EdgesAddFeatureError) {
    // A one-pixel shift of a sharp vertical edge: the error sits on the edge, where the feature
    // detectors disagree, and is far larger there than anywhere else.
    Image reference = greyImage(48, 16, 0.1f), shifted = greyImage(48, 16, 0.1f);
    for (int y = 0; y < 16; ++y) {
        for (int x = 0; x < 48; ++x) {
            for (int c = 0; c < 3; ++c) {
                reference.at(x, y, c) = x >= 24 ? 0.9f : 0.1f;
                shifted.at(x, y, c) = x >= 25 ? 0.9f : 0.1f;
            }
        }
    }
    const FlipResult result = computeFlip(reference, shifted);
    ASSERT_TRUE(result.ok);
    const float at_edge = result.error_map[8 * 48 + 24];
    const float far_away = result.error_map[8 * 48 + 2];
    EXPECT_GT(at_edge, 0.3f);
    EXPECT_EQ(far_away, 0.0f);
}

TEST(Flip, WeightedPercentilesFollowTheFlipToolDefinition) {
    // The tool's weighted percentile: sort the errors; the first one whose running sum exceeds
    // p times the total. Recomputed here from the returned map by sorting it all.
    const Image a = test::patternImage(61, 47);
    const Image b = test::withNoise(test::patternImage(61, 47, 0.8), 0.15f, 11);
    const FlipResult result = computeFlip(a, b);
    ASSERT_TRUE(result.ok);
    std::vector<float> sorted = result.error_map;
    std::sort(sorted.begin(), sorted.end());
    double total = 0.0;
    for (float e : sorted) total += e;
    auto percentile = [&](double p) {
        double running = 0.0;
        for (float e : sorted) {
            running += e;
            if (running > p * total) return static_cast<double>(e);
        }
        return static_cast<double>(sorted.back());
    };
    EXPECT_NEAR(result.weighted_p25, percentile(0.25), 1e-7);
    EXPECT_NEAR(result.weighted_median, percentile(0.5), 1e-7);
    EXPECT_NEAR(result.weighted_p75, percentile(0.75), 1e-7);
    EXPECT_NEAR(result.mean, total / sorted.size(), 1e-7);  // rows are summed in float lanes
    EXPECT_LE(result.weighted_p25, result.weighted_median);
    EXPECT_LE(result.weighted_median, result.weighted_p75);
}

TEST(Flip, WeightedMedianLeansTowardsLargeErrors) {
    // Left half black against white (error ~0.967), right half identical (error 0 away from
    // the seam). The plain median would sit at the seam; the weighted one, weighting each error
    // by its value, lies among the large errors.
    Image reference = greyImage(64, 16, 0.0f), test_image = greyImage(64, 16, 0.0f);
    for (int y = 0; y < 16; ++y) {
        for (int x = 0; x < 32; ++x) {
            for (int c = 0; c < 3; ++c) test_image.at(x, y, c) = 1.0f;
        }
    }
    const FlipResult result = computeFlip(reference, test_image);
    EXPECT_NEAR(result.mean, 0.5, 0.05);
    EXPECT_GT(result.weighted_median, 0.95);
}

TEST(Flip, MaskSelectsThePixelsThatArePooled) {
    const Image a = test::patternImage(40, 40);
    const Image b = test::withNoise(a, 0.1f, 21);
    Mask mask(40, 40, 0);
    for (int y = 10; y < 30; ++y) {
        for (int x = 5; x < 20; ++x) mask.at(x, y) = 1;
    }
    FlipConfig config;
    config.mask = &mask;
    const FlipResult masked = computeFlip(a, b, config);
    const FlipResult whole = computeFlip(a, b);
    ASSERT_TRUE(masked.ok);
    EXPECT_EQ(masked.pixel_count, 300u);
    // The map is the whole frame's either way (filters see everything).
    ASSERT_EQ(masked.error_map, whole.error_map);
    double sum = 0.0;
    for (int y = 10; y < 30; ++y) {
        for (int x = 5; x < 20; ++x) sum += whole.error_map[static_cast<std::size_t>(y) * 40 + x];
    }
    EXPECT_NEAR(masked.mean, sum / 300.0, 1e-9);

    // Without the map, the statistics are the same, masked or not.
    FlipConfig unmasked_no_map;
    unmasked_no_map.want_map = false;
    const FlipResult whole_no_map = computeFlip(a, b, unmasked_no_map);
    EXPECT_EQ(whole_no_map.mean, whole.mean);
    EXPECT_EQ(whole_no_map.weighted_p75, whole.weighted_p75);
    config.want_map = false;
    const FlipResult no_map = computeFlip(a, b, config);
    EXPECT_TRUE(no_map.error_map.empty());
    EXPECT_EQ(no_map.mean, masked.mean);
    EXPECT_EQ(no_map.weighted_median, masked.weighted_median);
}

TEST(Flip, NaNAndOutOfRangeInputsAreClampedFirst) {
    // As in the reference implementation, inputs are clamped to [0, 1] and NaN becomes 0.
    Image a = test::patternImage(30, 30), clamped = a;
    a.at(3, 4, 0) = std::numeric_limits<float>::quiet_NaN();
    clamped.at(3, 4, 0) = 0.0f;
    a.at(10, 10, 1) = 7.0f;
    clamped.at(10, 10, 1) = 1.0f;
    a.at(20, 5, 2) = -3.0f;
    clamped.at(20, 5, 2) = 0.0f;
    const Image b = test::patternImage(30, 30, 0.2);
    const FlipResult raw = computeFlip(a, b), expected = computeFlip(clamped, b);
    EXPECT_EQ(raw.error_map, expected.error_map);
    EXPECT_FALSE(std::isnan(raw.mean));
}

TEST(Flip, AgreesWithAnIndependentDoublePrecisionImplementation) {
    // grader/metrics/tests/reference/flip_reference.py (numpy/scipy, whole 2D filters in double) on
    // this pair prints mean 0.40585714, weighted quartiles 0.37827508 0.44111566 0.50255458.
    const Image reference = test::patternImage(64, 48);
    const Image test_image = test::withNoise(test::patternImage(64, 48, 0.4), 0.05f, 1234);
    const FlipResult result = computeFlip(reference, test_image);
    ASSERT_TRUE(result.ok);
    EXPECT_NEAR(result.mean, 0.40585714, 1e-5);
    EXPECT_NEAR(result.weighted_p25, 0.37827508, 1e-4);
    EXPECT_NEAR(result.weighted_median, 0.44111566, 1e-4);
    EXPECT_NEAR(result.weighted_p75, 0.50255458, 1e-4);
}

TEST(Flip, TinyAndOddSizedImagesWork) {
    for (const auto& size : {std::pair<int, int>{1, 1}, {1, 20}, {3, 5}, {17, 2}, {33, 9}}) {
        const Image a = test::withNoise(greyImage(size.first, size.second, 0.5f), 0.3f, 1);
        const Image b = test::withNoise(greyImage(size.first, size.second, 0.5f), 0.3f, 2);
        const FlipResult result = computeFlip(a, b);
        ASSERT_TRUE(result.ok) << size.first << "x" << size.second;
        EXPECT_GT(result.mean, 0.0);
        EXPECT_LE(result.max_error, 1.0f);
        EXPECT_EQ(result.error_map.size(), static_cast<std::size_t>(size.first) * size.second);
    }
}

TEST(Flip, PixelsPerDegree) {
    // The FLIP default: a 0.7 m wide, 3840-pixel monitor seen from 0.7 m: 3840 pi / 180.
    EXPECT_NEAR(flipPixelsPerDegree(0.7, 3840, 0.7), 67.0206432, 1e-6);
    EXPECT_NEAR(FlipConfig{}.pixels_per_degree, 67.0206432, 1e-5);
    FlipConfig bad;
    bad.pixels_per_degree = 0.0f;
    EXPECT_FALSE(computeFlip(greyImage(4, 4, 0.5f), greyImage(4, 4, 0.5f), bad).ok);
}

TEST(Flip, RejectsMismatchedSizesAndEmptyMasks) {
    EXPECT_FALSE(computeFlip(greyImage(4, 4, 0.5f), greyImage(5, 4, 0.5f)).ok);
    Mask empty(4, 4, 0);
    FlipConfig config;
    config.mask = &empty;
    EXPECT_FALSE(computeFlip(greyImage(4, 4, 0.5f), greyImage(4, 4, 0.5f), config).ok);
}

}  // namespace
}  // namespace grader
