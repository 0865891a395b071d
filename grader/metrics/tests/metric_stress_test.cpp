// Every metric under inputs that break naive formulas: constant, black and white images (zero
// variance: SSIM's and PSNR's divisions), denormal values, NaN and Inf, HDR values up to the
// half-float limit, the smallest images SSIM accepts, grey and RGBA layouts. A metric must
// answer a defined input with a number (never NaN), and the fast path for bit-identical images
// must agree with the full computation on images one rounding step apart.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "grader/metrics/compare.h"
#include "grader/metrics/metrics.h"
#include "grader/metrics/scoring.h"
#include "test_images.h"

namespace grader {
namespace {

using test::constantImage;
using test::greyImage;

constexpr float kDenormal = 1e-40f;   // below FLT_MIN (1.18e-38): a subnormal float
constexpr float kHalfMax = 65504.0f;  // the largest finite half float (rgba16f targets)

Image noiseImage(int w, int h, int channels, std::uint32_t seed, float scale = 1.0f) {
    Image image(w, h, channels);
    test::Lcg random(seed);
    for (float& v : image.pixels) v = scale * random.next();
    return image;
}

struct Pair {
    std::string name;
    Image reference, test;
};

std::vector<Pair> definedPairs() {
    std::vector<Pair> pairs;
    auto add = [&](std::string name, Image a, Image b) { pairs.push_back({std::move(name), a, b}); };
    add("black_black", greyImage(32, 32, 0.0f), greyImage(32, 32, 0.0f));
    add("white_white", greyImage(32, 32, 1.0f), greyImage(32, 32, 1.0f));
    add("black_white", greyImage(32, 32, 0.0f), greyImage(32, 32, 1.0f));
    add("white_black", greyImage(32, 32, 1.0f), greyImage(32, 32, 0.0f));
    add("grey_constants", greyImage(32, 32, 0.25f), greyImage(32, 32, 0.75f));
    add("constant_noise", greyImage(32, 32, 0.5f), noiseImage(32, 32, 3, 7));
    add("denormal_black", greyImage(32, 32, kDenormal), greyImage(32, 32, 0.0f));
    add("denormal_noise", noiseImage(32, 32, 3, 3, kDenormal), noiseImage(32, 32, 3, 4, kDenormal));
    add("smallest_ssim_window", noiseImage(11, 11, 3, 1), noiseImage(11, 11, 3, 2));
    add("below_ssim_window", noiseImage(4, 4, 3, 1), noiseImage(4, 4, 3, 2));
    add("one_pixel", greyImage(1, 1, 0.2f), greyImage(1, 1, 0.9f));
    add("grey_layout", noiseImage(24, 24, 1, 5), noiseImage(24, 24, 1, 6));
    add("rgba_layout", noiseImage(24, 24, 4, 5), noiseImage(24, 24, 4, 6));
    add("wide_strip", noiseImage(300, 11, 3, 8), noiseImage(300, 11, 3, 9));
    return pairs;
}

class DefinedInputs : public ::testing::TestWithParam<Pair> {};

TEST_P(DefinedInputs, EveryMetricAnswersWithANumber) {
    const Pair& p = GetParam();
    const PsnrResult psnr = computePsnr(p.reference, p.test);
    ASSERT_TRUE(psnr.ok) << psnr.error;
    EXPECT_FALSE(std::isnan(psnr.psnr_db));
    EXPECT_FALSE(std::isnan(psnr.mse));
    EXPECT_GE(psnr.mse, 0.0);

    const SsimResult ssim = computeSsim(p.reference, p.test);
    if (p.reference.width >= 11 && p.reference.height >= 11) {
        ASSERT_TRUE(ssim.ok) << ssim.error;
        EXPECT_TRUE(std::isfinite(ssim.ssim)) << ssim.ssim;
        EXPECT_LE(ssim.ssim, 1.0 + 1e-9);
        EXPECT_GE(ssim.ssim, -1.0 - 1e-9);
    } else {
        EXPECT_FALSE(ssim.ok);  // undefined, said so, not a NaN
        EXPECT_FALSE(ssim.error.empty());
    }

    const FlipResult flip = computeFlip(p.reference, p.test);
    ASSERT_TRUE(flip.ok) << flip.error;
    EXPECT_TRUE(std::isfinite(flip.mean));
    EXPECT_GE(flip.mean, 0.0);
    EXPECT_LE(flip.mean, 1.0);
    EXPECT_TRUE(std::isfinite(flip.weighted_median));
    for (float e : flip.error_map) ASSERT_TRUE(std::isfinite(e) && e >= 0.0f && e <= 1.0f) << e;

    const ToleranceCompareResult cmp = compareShiftTolerant(p.reference, p.test);
    ASSERT_TRUE(cmp.ok) << cmp.error;
    EXPECT_TRUE(std::isfinite(cmp.mismatch_fraction));

    for (ImageRange range : {ImageRange::Display, ImageRange::Hdr}) {
        const ImageVerdict v = judgeImage(p.reference, {}, p.test, {}, Thresholds{}, range);
        for (const MetricSet* m : {&v.covered, &v.frame}) {
            EXPECT_FALSE(std::isnan(m->psnr_db));
            EXPECT_TRUE(std::isfinite(m->ssim));
            EXPECT_TRUE(std::isfinite(m->flip_mean));
            EXPECT_TRUE(std::isfinite(m->mismatch_fraction));
        }
        EXPECT_TRUE(std::isfinite(v.hdr_scale));
    }
}

INSTANTIATE_TEST_SUITE_P(Stress, DefinedInputs, ::testing::ValuesIn(definedPairs()),
                         [](const ::testing::TestParamInfo<Pair>& param_info) {
                             return param_info.param.name;
                         });

TEST(MetricStress, DenormalDifferencesReadAsEqualForEveryVerdict) {
    // 1e-40 against 0 is far below an 8-bit step: the grade must not see it.
    const Image a = greyImage(32, 32, kDenormal), b = greyImage(32, 32, 0.0f);
    const ImageVerdict v = judgeImage(a, {}, b, {}, Thresholds{});
    EXPECT_TRUE(v.passed);
    EXPECT_TRUE(std::isinf(v.covered.psnr_db));
}

TEST(MetricStress, NanAndInfInTheTestImageFailWithFiniteMetrics) {
    for (float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
                      -std::numeric_limits<float>::infinity()}) {
        const Image reference = greyImage(32, 32, 0.5f);
        Image broken = reference;
        broken.at(3, 4, 1) = bad;
        broken.at(20, 21, 0) = bad;
        for (ImageRange range : {ImageRange::Display, ImageRange::Hdr}) {
            const ImageVerdict v = judgeImage(reference, {}, broken, {}, Thresholds{}, range);
            EXPECT_FALSE(v.passed) << bad;
            EXPECT_EQ(v.nan_count + v.inf_count, 2u) << bad;
            EXPECT_FALSE(std::isnan(v.covered.psnr_db));
            EXPECT_TRUE(std::isfinite(v.covered.ssim));
            EXPECT_TRUE(std::isfinite(v.covered.flip_mean));
            EXPECT_TRUE(std::isfinite(v.hdr_scale));
        }
    }
}

TEST(MetricStress, HdrUpToTheHalfFloatLimitStaysFinite) {
    Image reference(32, 32, 4, 1.0f), test(32, 32, 4, 1.0f);
    test::Lcg random(11);
    for (int y = 0; y < 32; ++y) {
        for (int x = 0; x < 32; ++x) {
            for (int c = 0; c < 3; ++c) {
                const float v = kHalfMax * random.next();
                reference.at(x, y, c) = v;
                test.at(x, y, c) = v * 0.999f;
            }
        }
    }
    reference.at(0, 0, 0) = kHalfMax;
    const ImageVerdict same = judgeImage(reference, {}, reference, {}, Thresholds{}, ImageRange::Hdr);
    EXPECT_TRUE(same.passed);
    EXPECT_NEAR(same.hdr_scale, kHalfMax, kHalfMax * 0.01);
    const ImageVerdict close = judgeImage(reference, {}, test, {}, Thresholds{}, ImageRange::Hdr);
    EXPECT_TRUE(close.passed) << (close.reasons.empty() ? "" : close.reasons[0]);
    EXPECT_TRUE(std::isfinite(close.covered.psnr_db));
    EXPECT_TRUE(std::isfinite(close.covered.flip_mean));
    // Overflowing the half range (what a float target holds beyond it) is still a number.
    test.at(1, 1, 0) = 1e30f;
    const ImageVerdict over = judgeImage(reference, {}, test, {}, Thresholds{}, ImageRange::Hdr);
    EXPECT_TRUE(std::isfinite(over.covered.flip_mean));
    EXPECT_FALSE(std::isnan(over.covered.psnr_db));
}

// quantise8 against the formula it implements, round(clamp(v, 0, 1) * 255) / 255, over every
// 251st float in [0, 1] (all the values one rounding step either side of each level included by
// the explicit list) and the values outside.
TEST(MetricStress, QuantiseMatchesRoundOfTheClampedValue) {
    std::vector<float> values = {-1.0f,
                                 -0.0f,
                                 0.0f,
                                 1.0f,
                                 2.0f,
                                 1e30f,
                                 -1e30f,
                                 kDenormal,
                                 std::numeric_limits<float>::infinity(),
                                 -std::numeric_limits<float>::infinity(),
                                 std::numeric_limits<float>::quiet_NaN()};
    for (int level = 0; level < 256; ++level) {
        const float half = (level + 0.5f) / 255.0f;
        values.push_back(half);
        values.push_back(std::nextafter(half, 0.0f));
        values.push_back(std::nextafter(half, 1.0f));
    }
    for (std::uint32_t bits = 0; bits <= 0x3f800000u; bits += 251) {
        float f;
        std::memcpy(&f, &bits, sizeof f);
        values.push_back(f);
    }
    Image image(static_cast<int>(values.size()), 1, 1);
    image.pixels = values;
    const Image q = quantise8(image);
    for (std::size_t i = 0; i < values.size(); ++i) {
        const float v = values[i];
        const float c = std::isnan(v) ? 0.0f : std::fmin(std::fmax(v, 0.0f), 1.0f);
        const float expected = std::round(c * 255.0f) / 255.0f;
        ASSERT_EQ(q.pixels[i], expected) << "value " << v;
    }
}

// The identical-image fast path against the full computation one float step away.
TEST(MetricStress, IdenticalFastPathAgreesWithTheFullComputation) {
    const Image a = noiseImage(64, 48, 3, 21);
    Image nearly = a;
    nearly.at(30, 20, 1) = std::nextafter(nearly.at(30, 20, 1), 2.0f);  // defeats the fast path
    Mask mask(64, 48, 0);
    for (int y = 10; y < 40; ++y)
        for (int x = 5; x < 50; ++x) mask.at(x, y) = 1;
    for (const Mask* m : {static_cast<const Mask*>(nullptr), static_cast<const Mask*>(&mask)}) {
        SsimConfig sc;
        sc.mask = m;
        sc.want_map = true;
        const SsimResult fast_ssim = computeSsim(a, a, sc), full_ssim = computeSsim(a, nearly, sc);
        ASSERT_TRUE(fast_ssim.ok && full_ssim.ok);
        EXPECT_EQ(fast_ssim.ssim, 1.0);
        EXPECT_NEAR(full_ssim.ssim, 1.0, 1e-5);
        EXPECT_EQ(fast_ssim.pixel_count, full_ssim.pixel_count);
        EXPECT_EQ(fast_ssim.channel_count, full_ssim.channel_count);
        ASSERT_EQ(fast_ssim.map.size(), full_ssim.map.size());
        for (std::size_t i = 0; i < fast_ssim.map.size(); ++i)
            ASSERT_NEAR(fast_ssim.map[i], full_ssim.map[i], 1e-4);

        FlipConfig fc;
        fc.mask = m;
        const FlipResult fast_flip = computeFlip(a, a, fc), full_flip = computeFlip(a, nearly, fc);
        ASSERT_TRUE(fast_flip.ok && full_flip.ok);
        EXPECT_EQ(fast_flip.mean, 0.0);
        EXPECT_NEAR(full_flip.mean, 0.0, 1e-6);
        EXPECT_EQ(fast_flip.pixel_count, full_flip.pixel_count);
        EXPECT_EQ(fast_flip.width, full_flip.width);
        ASSERT_EQ(fast_flip.error_map.size(), full_flip.error_map.size());

        ToleranceCompareConfig cc;
        cc.mask = m;
        const ToleranceCompareResult fast_cmp = compareShiftTolerant(a, a, cc),
                                     full_cmp = compareShiftTolerant(a, nearly, cc);
        ASSERT_TRUE(fast_cmp.ok && full_cmp.ok);
        EXPECT_EQ(fast_cmp.compared_count, full_cmp.compared_count);
        EXPECT_EQ(fast_cmp.mismatch_count, 0u);
        EXPECT_EQ(full_cmp.mismatch_count, 0u);
        EXPECT_EQ(fast_cmp.mismatches.values, full_cmp.mismatches.values);
        EXPECT_TRUE(fast_cmp.worst.tile.empty());
    }
    // An empty mask is an error on both paths.
    const Mask none(64, 48, 0);
    FlipConfig fc;
    fc.mask = &none;
    EXPECT_FALSE(computeFlip(a, a, fc).ok);
    EXPECT_FALSE(computeFlip(a, nearly, fc).ok);
}

// The identity test the metrics start with scans in blocks of 256 values: a difference, a NaN
// or a negative zero anywhere (first block, a middle one, the tail after the last whole block)
// is seen, and the image takes the full path; an equal one gets FLIP exactly 0.
TEST(MetricStress, IdentityTestSeesEveryValue) {
    const Image a = noiseImage(37, 29, 3, 5);  // 3219 values: 12 blocks and a tail of 147
    ASSERT_EQ(computeFlip(a, a).mean, 0.0);
    for (const std::size_t at : {std::size_t(0), std::size_t(255), std::size_t(1500), a.pixels.size() - 1}) {
        Image b = a;
        b.pixels[at] = b.pixels[at] > 0.5f ? 0.0f : 1.0f;
        EXPECT_GT(computeFlip(a, b).mean, 0.0) << "one value changed at " << at;
        EXPECT_LT(computeSsim(a, b).ssim, 1.0) << "one value changed at " << at;
        Image n = a;
        n.pixels[at] = std::numeric_limits<float>::quiet_NaN();
        // A NaN is never identical to itself: the full path, whose result the NaN reaches.
        EXPECT_FALSE(computeSsim(n, n).ssim == 1.0) << "NaN at " << at;
    }
    // -0 equals +0 under float ==: the fast path, and the same answer as the full one.
    Image zero = greyImage(20, 20, 0.0f), negative = zero;
    for (float& v : negative.pixels) v = -0.0f;
    EXPECT_EQ(computeSsim(zero, negative).ssim, 1.0);
}

// Images that quantise to the same levels skip the metrics' copies in judgeImage; what they get
// must be what measuring the quantised pair gives, field for field: with and without coverage,
// coverage only in SSIM's border, none at all, images smaller than SSIM's window, values beyond
// 0..1 and a NaN that quantises to the reference's 0.
TEST(MetricStress, QuantisedEqualImagesGetWhatTheMetricsGive) {
    struct Case {
        int w, h;
        int coverage;  // 0: none given, 1: a block, 2: a ring inside SSIM's border only, 3: all zero
        bool nan;
    };
    for (const Case c :
         {Case{64, 48, 0, false}, Case{64, 48, 1, false}, Case{64, 48, 2, false}, Case{64, 48, 3, false},
          Case{8, 6, 1, false}, Case{20, 9, 0, false}, Case{33, 17, 1, true}}) {
        SCOPED_TRACE(std::to_string(c.w) + "x" + std::to_string(c.h) + " coverage " +
                     std::to_string(c.coverage) + (c.nan ? " with NaN" : ""));
        Image reference = quantise8(noiseImage(c.w, c.h, 4, 31));
        Image test = reference;
        std::uint32_t state = 7;
        for (float& v : test.pixels) {  // within 0.4 of a level of the reference's, either way
            state = state * 1664525u + 1013904223u;
            v += ((state >> 8) % 2 ? 0.4f : -0.4f) / 255.0f;
        }
        reference.pixels[0] = 0.0f, test.pixels[0] = c.nan ? std::numeric_limits<float>::quiet_NaN() : -3.0f;
        reference.pixels[5] = 1.0f, test.pixels[5] = 7.0f;
        const std::size_t n = static_cast<std::size_t>(c.w) * c.h;
        std::vector<std::uint8_t> cov;
        if (c.coverage != 0) {
            cov.assign(n, 0);
            for (int y = 0; y < c.h; ++y)
                for (int x = 0; x < c.w; ++x) {
                    const bool block = x > c.w / 4 && x < c.w / 2 && y > c.h / 4 && y < c.h / 2;
                    const bool ring = x < 3 || y < 3;
                    cov[static_cast<std::size_t>(y) * c.w + x] = c.coverage == 1   ? block
                                                                 : c.coverage == 2 ? ring
                                                                                   : 0;
                }
        }
        const Thresholds t;
        const ImageVerdict v = judgeImage(reference, cov, test, cov, t);

        // What measuring the quantised pair gives (scoring.cpp's measure, spelled out).
        const Image r8 = quantise8(reference), t8 = quantise8(test);
        Mask covered(c.w, c.h, 1);
        if (c.coverage != 0 && c.coverage != 3)
            for (std::size_t i = 0; i < n; ++i) covered.values[i] = cov[i];
        const auto expect = [&](const MetricSet& got, const Mask* mask) {
            PsnrConfig pc;
            pc.mask = mask;
            const PsnrResult psnr = computePsnr(r8, t8, pc);
            EXPECT_EQ(got.psnr_db, psnr.psnr_db);
            EXPECT_EQ(got.pixel_count, psnr.pixel_count);
            SsimConfig sc;
            sc.mask = mask;
            SsimResult ssim = computeSsim(r8, t8, sc);
            if (!ssim.ok && mask) ssim = computeSsim(r8, t8, SsimConfig{});
            EXPECT_EQ(got.ssim_defined, ssim.ok);
            EXPECT_EQ(got.ssim, ssim.ok ? ssim.ssim : 0.0);
            FlipConfig fc;
            fc.mask = mask;
            const FlipResult flip = computeFlip(r8, t8, fc);
            EXPECT_EQ(got.flip_mean, flip.mean);
            EXPECT_EQ(got.flip_weighted_median, flip.weighted_median);
            ToleranceCompareConfig cc;
            cc.mask = mask;
            cc.tolerance = t.pixel_tolerance;
            EXPECT_EQ(got.mismatch_fraction, compareShiftTolerant(r8, t8, cc).mismatch_fraction);
        };
        expect(v.covered, &covered);
        expect(v.frame, nullptr);
        FlipConfig fc;
        fc.mask = &covered;
        fc.want_map = true;
        EXPECT_EQ(v.flip_map, computeFlip(r8, t8, fc).error_map);
        ToleranceCompareConfig cc;
        cc.mask = &covered;
        cc.tolerance = t.pixel_tolerance;
        const ToleranceCompareResult cmp = compareShiftTolerant(r8, t8, cc);
        EXPECT_EQ(v.mismatches.values, cmp.mismatches.values);
        EXPECT_TRUE(v.worst.tile.empty());
        EXPECT_EQ(v.worst.mismatch_count, cmp.worst.mismatch_count);
        EXPECT_EQ(v.graded.values, covered.values);
        EXPECT_EQ(v.passed, !c.nan);
        EXPECT_EQ(v.nan_count, c.nan ? 1u : 0u);
    }
}

}  // namespace
}  // namespace grader
