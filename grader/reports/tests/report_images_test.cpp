// The report's pictures: signed difference colours and scale, NaN/Inf in magenta, windows,
// nearest-neighbour zoom, side-by-side strips, downsampling, and the known-mistake comparison.
#include "grader/reports/report_images.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "grader/metrics/scoring.h"
#include "test_images.h"

namespace grader {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

TEST(SignedDifference, BrighterOrangeDarkerBlueEqualGhost) {
    Image reference = test::greyImage(3, 1, 0.5f);
    Image student = reference;
    for (int c = 0; c < 3; ++c) {
        student.at(0, 0, c) = 1.0f;  // +0.5: brighter, beyond the full scale
        student.at(1, 0, c) = 0.0f;  // -0.5: darker
    }
    const SignedDifferenceConfig config;
    const Image d = signedDifference(reference, student, config);
    ASSERT_EQ(d.width, 3);
    ASSERT_EQ(d.channels, 3);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(d.at(0, 0, c), config.brighter_color[c], 1e-6f);
        EXPECT_NEAR(d.at(1, 0, c), config.darker_color[c], 1e-6f);
        // Equal: the grey ghost of the reference's luminance, no tint.
        EXPECT_NEAR(d.at(2, 0, c), 0.78f + 0.18f * 0.5f, 1e-6f);
    }
}

TEST(SignedDifference, TintGrowsLinearlyUpToTheFullScale) {
    const Image reference = test::greyImage(1, 1, 0.0f);
    SignedDifferenceConfig config;
    config.full_scale = 0.5f;
    const Image quarter = signedDifference(reference, test::greyImage(1, 1, 0.125f), config);
    // Luminance difference 0.125 of 0.5: a quarter of the way from the ghost (0.78) to orange.
    EXPECT_NEAR(quarter.at(0, 0, 0), 0.78f + 0.25f * (config.brighter_color[0] - 0.78f), 1e-5f);
    EXPECT_NEAR(quarter.at(0, 0, 2), 0.78f + 0.25f * (config.brighter_color[2] - 0.78f), 1e-5f);
}

TEST(SignedDifference, HueChangeAtEqualLuminanceIsNeutralAndNonFiniteIsMagenta) {
    // Pure luminance: a colour shift that keeps it shows no tint (the FLIP map shows that one).
    Image reference(2, 1, 3, 0.0f), student(2, 1, 3, 0.0f);
    reference.at(0, 0, 0) = 0.7152f;  // red of luminance 0.152...
    student.at(0, 0, 1) = 0.2126f;    // green of the same luminance
    student.at(1, 0, 2) = kNaN;
    const Image d = signedDifference(reference, student);
    EXPECT_NEAR(d.at(0, 0, 0), d.at(0, 0, 2), 1e-5f);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(d.at(1, 0, c), kNonFiniteColor[c]);
    EXPECT_TRUE(signedDifference(reference, test::greyImage(3, 1, 0.0f)).empty());
}

TEST(MarkNonFinite, PaintsNaNAndInfKeepsTheRestClamped) {
    Image image(3, 1, 4, 0.25f);
    image.at(0, 0, 1) = kNaN;
    image.at(1, 0, 2) = -kInf;
    image.at(2, 0, 0) = 3.0f;  // only out of range: clamped, not painted
    std::size_t painted = 0;
    const Image marked = markNonFinite(image, &painted);
    EXPECT_EQ(painted, 2u);
    ASSERT_EQ(marked.channels, 4);
    for (int x = 0; x < 2; ++x) {
        for (int c = 0; c < 3; ++c) EXPECT_EQ(marked.at(x, 0, c), kNonFiniteColor[c]);
        EXPECT_EQ(marked.at(x, 0, 3), 1.0f);
    }
    EXPECT_EQ(marked.at(2, 0, 0), 1.0f);
    EXPECT_EQ(marked.at(2, 0, 1), 0.25f);
}

TEST(WindowAround, CentredThenMovedInside) {
    const PixelBox centre = windowAround(50, 40, 16, 256, 256);
    EXPECT_EQ(centre.x0, 42);
    EXPECT_EQ(centre.y0, 32);
    EXPECT_EQ(centre.width(), 16);
    const PixelBox corner = windowAround(255, 0, 16, 256, 256);
    EXPECT_EQ(corner.x1, 255);
    EXPECT_EQ(corner.y0, 0);
    const PixelBox small = windowAround(3, 3, 16, 8, 4);  // smaller than the window
    EXPECT_EQ(small.x0, 0);
    EXPECT_EQ(small.width(), 8);
    EXPECT_EQ(small.height(), 4);
}

TEST(CropZoom, RepeatsPixelsNearestNeighbour) {
    Image image(4, 4, 3, 0.0f);
    image.at(2, 1, 0) = 1.0f;  // one red pixel
    PixelBox box;
    box.x0 = 1;
    box.y0 = 1;
    box.x1 = 2;
    box.y1 = 2;
    const Image zoom = cropZoom(image, box, 3);
    ASSERT_EQ(zoom.width, 6);
    ASSERT_EQ(zoom.height, 6);
    // The red pixel is the top-right 3x3 block, sharp-edged.
    for (int y = 0; y < 6; ++y)
        for (int x = 0; x < 6; ++x)
            EXPECT_EQ(zoom.at(x, y, 0), (x >= 3 && y < 3) ? 1.0f : 0.0f) << x << "," << y;
    // A box reaching outside is clipped; one outside entirely gives nothing.
    box.x1 = 10;
    EXPECT_EQ(cropZoom(image, box, 2).width, 6);
    box.x0 = 7;
    EXPECT_TRUE(cropZoom(image, box, 2).empty());
    EXPECT_TRUE(cropZoom(image, PixelBox{}, 2).empty());
}

TEST(SideBySide, GapsAndHeights) {
    const Image a = test::greyImage(2, 3, 1.0f);
    const Image b = test::greyImage(3, 1, 0.0f);
    const Image strip = sideBySide({a, b}, 2, 0.5f);
    ASSERT_EQ(strip.width, 7);
    ASSERT_EQ(strip.height, 3);
    EXPECT_EQ(strip.at(1, 2, 0), 1.0f);
    EXPECT_EQ(strip.at(2, 0, 0), 0.5f);  // gap
    EXPECT_EQ(strip.at(4, 0, 0), 0.0f);  // b
    EXPECT_EQ(strip.at(4, 2, 0), 0.5f);  // below the shorter image
    EXPECT_TRUE(sideBySide({}).empty());
}

TEST(Downsample, AveragesBlocksAndPartialEdges) {
    Image image(3, 2, 1, 0.0f);
    image.at(0, 0) = 1.0f;
    image.at(1, 1) = 1.0f;
    image.at(2, 0) = kNaN;  // counts as 0
    image.at(2, 1) = 0.5f;
    const Image half = downsample(image, 2);
    ASSERT_EQ(half.width, 2);
    ASSERT_EQ(half.height, 1);
    EXPECT_FLOAT_EQ(half.at(0, 0), 0.5f);
    EXPECT_FLOAT_EQ(half.at(1, 0), 0.25f);  // the partial column: (NaN->0 + 0.5) / 2
    Mask mask(3, 2, 0);
    mask.at(2, 1) = 1;
    const Mask small = downsample(mask, 2);
    EXPECT_EQ(small.at(0, 0), 0);
    EXPECT_EQ(small.at(1, 0), 1);
}

TEST(CompareWithHint, MatchesTheMistakeNotTheReference) {
    const float white[3] = {1, 1, 1}, black[3] = {0, 0, 0}, grey[3] = {0.5f, 0.5f, 0.5f};
    const Image reference = test::discImage(32, 32, 16, 16, 8, white, black);
    const Image mistake = test::discImage(32, 32, 16, 16, 8, grey, black);  // a darker disc
    const Image hint = quantise8(downsample(mistake, 2));
    const Mask all(32, 32, 1);

    const HintComparison same = compareWithHint(mistake, reference, hint, all, 2);
    ASSERT_TRUE(same.comparable);
    EXPECT_TRUE(std::isinf(same.psnr_to_hint_db));
    EXPECT_TRUE(same.matches);

    // The right answer is far from the mistake: no match.
    EXPECT_FALSE(compareWithHint(reference, reference, hint, all, 2).matches);

    // Close to the mistake but only within 40 dB? Slightly brighter disc: ~0.04 off.
    const float near_grey[3] = {0.54f, 0.54f, 0.54f};
    const Image close = test::discImage(32, 32, 16, 16, 8, near_grey, black);
    const HintComparison near = compareWithHint(close, reference, hint, all, 2);
    EXPECT_GT(near.psnr_to_hint_db, 30.0);
    EXPECT_LT(near.psnr_to_hint_db, 40.0);
    EXPECT_FALSE(near.matches);
    EXPECT_TRUE(compareWithHint(close, reference, hint, all, 2, 30.0).matches);

    // Sizes that do not fit the factor: not comparable.
    EXPECT_FALSE(compareWithHint(mistake, reference, hint, all, 4).comparable);
}

}  // namespace
}  // namespace grader
