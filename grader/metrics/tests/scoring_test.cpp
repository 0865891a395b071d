// Verdicts on one image: images smaller than SSIM's window are judged by the other metrics, the
// high-dynamic-range comparison sees errors above 1 that the display comparison clamps away, the
// RGBE rounding it uses is stable and matches the .hdr files, and reasons never print two equal
// numbers as "below".
#include "grader/metrics/scoring.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>

#include "test_images.h"

namespace grader {
namespace {

// Regression: a graded target smaller than 11 px never passed (SSIM was reported as 0).
TEST(Scoring, SmallImagesAreJudgedWithoutSsim) {
    const Image a = test::patternImage(8, 8);
    const ImageVerdict same = judgeImage(a, {}, a, {}, Thresholds{});
    EXPECT_TRUE(same.passed);
    EXPECT_FALSE(same.covered.ssim_defined);
    EXPECT_EQ(same.checks_total, 3);
    const ImageVerdict other = judgeImage(a, {}, test::greyImage(8, 8, 0.0f), {}, Thresholds{});
    EXPECT_FALSE(other.passed);
    EXPECT_FALSE(other.reasons.empty());
    for (const std::string& r : other.reasons) EXPECT_EQ(r.find("SSIM"), std::string::npos) << r;
}

// Regression: values above 1 in float targets were clamped before grading, so errors in an
// intermediate HDR pass (a bloom's bright pass) were invisible.
TEST(Scoring, HdrRangeSeesErrorsAboveOne) {
    const Image reference = test::greyImage(32, 32, 4.0f);
    Image wrong = reference;
    for (int y = 8; y < 24; ++y)
        for (int x = 8; x < 24; ++x)
            for (int c = 0; c < 3; ++c) wrong.at(x, y, c) = 2.0f;
    EXPECT_TRUE(judgeImage(reference, {}, wrong, {}, Thresholds{}, ImageRange::Display).passed);
    const ImageVerdict hdr = judgeImage(reference, {}, wrong, {}, Thresholds{}, ImageRange::Hdr);
    EXPECT_FALSE(hdr.passed);
    EXPECT_DOUBLE_EQ(hdr.hdr_scale, 4.0);
    EXPECT_TRUE(judgeImage(reference, {}, reference, {}, Thresholds{}, ImageRange::Hdr).passed);
    // Within 0..1 the HDR comparison agrees with the display one on what passes.
    const Image ldr = test::patternImage(32, 32);
    EXPECT_TRUE(judgeImage(ldr, {}, ldr, {}, Thresholds{}, ImageRange::Hdr).passed);
    EXPECT_FALSE(
        judgeImage(ldr, {}, test::greyImage(32, 32, 0.5f), {}, Thresholds{}, ImageRange::Hdr).passed);
}

TEST(Scoring, RgbeRoundingIsStableAndMatchesHdrFiles) {
    Image img(4, 2, 4);
    const float values[8] = {0.0f, 1e-3f, 0.5f, 1.0f, 3.14159f, 100.0f, 65504.0f, -2.0f};
    for (int i = 0; i < 8; ++i)
        for (int c = 0; c < 3; ++c) img.at(i % 4, i / 4, c) = values[i] * (1.0f + 0.1f * c);
    const Image once = rgbeRoundTrip(img);
    EXPECT_EQ(rgbeRoundTrip(once).pixels, once.pixels);
    for (int i = 0; i < 7; ++i) {
        const float v = values[i] * 1.2f;  // the largest channel keeps 8 significant bits
        EXPECT_NEAR(once.at(i % 4, i / 4, 2), v, v / 128.0f) << v;
    }
    EXPECT_EQ(once.at(3, 1, 0), 0.0f);  // negative values count as 0
    const std::filesystem::path file =
        std::filesystem::temp_directory_path() / ("scoring_rgbe_" + std::to_string(::getpid()) + ".hdr");
    std::string err;
    ASSERT_TRUE(writeHdr(img, file.string(), &err)) << err;
    Image back;
    ASSERT_TRUE(readHdr(file.string(), &back, &err)) << err;
    std::filesystem::remove(file);
    ASSERT_EQ(back.width, 4);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 4; ++x)
            for (int c = 0; c < 3; ++c)
                EXPECT_EQ(back.at(x, y, c), once.at(x, y, c)) << x << "," << y << "," << c;
}

// "0.950 is below 0.950" must not happen: as many decimals as it takes to tell them apart.
TEST(Scoring, ReasonsTellTheNumberFromTheThreshold) {
    const Image a = test::patternImage(32, 32);
    Image b = a;
    b.at(5, 5, 0) = 1.0f - b.at(5, 5, 0);
    const ImageVerdict v = judgeImage(a, {}, b, {}, Thresholds{});
    Thresholds t;
    t.ssim_min = static_cast<float>(v.covered.ssim + 1e-5);  // just above what it measures
    t.psnr_min_db = 0.0f;
    const ImageVerdict tight = judgeImage(a, {}, b, {}, t);
    ASSERT_FALSE(tight.passed);
    bool found = false;
    for (const std::string& r : tight.reasons) {
        if (r.rfind("SSIM ", 0) != 0) continue;
        found = true;
        const std::string value = r.substr(5, r.find(' ', 5) - 5);
        const std::string limit = r.substr(r.rfind(' ') + 1);
        EXPECT_NE(value, limit) << r;
    }
    EXPECT_TRUE(found);
}

TEST(Scoring, FormatDistinctAddsDecimalsOnlyWhenNeeded) {
    EXPECT_EQ(formatDistinct(27.34, 30.0, 1), std::make_pair(std::string("27.3"), std::string("30.0")));
    EXPECT_EQ(formatDistinct(0.9499, 0.95, 3), std::make_pair(std::string("0.9499"), std::string("0.9500")));
    EXPECT_EQ(formatDistinct(29.96, 30.0, 1), std::make_pair(std::string("29.96"), std::string("30.00")));
    // Equal numbers stay equal (at most 6 decimals).
    EXPECT_EQ(formatDistinct(0.95, 0.95, 3),
              std::make_pair(std::string("0.950000"), std::string("0.950000")));
    // The graded pixels are the verdict's mask.
    const Image a = test::patternImage(16, 16);
    EXPECT_EQ(judgeImage(a, {}, a, {}, Thresholds{}).graded.count(), 256u);
}

}  // namespace
}  // namespace grader
