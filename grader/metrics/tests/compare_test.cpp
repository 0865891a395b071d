// Shift-tolerant comparison: a one-pixel shift passes, a two-pixel shift or a colour change is
// reported at the right place, both directions are checked, masks and tolerance behave; plus
// the coverage masks.
#include "grader/metrics/compare.h"

#include <gtest/gtest.h>

#include <limits>

#include "test_images.h"

namespace grader {
namespace {

const float kWhite[3] = {1.0f, 1.0f, 1.0f};
const float kBlack[3] = {0.0f, 0.0f, 0.0f};

Image disc(float cx, float cy) { return test::discImage(64, 64, cx, cy, 12.0f, kWhite, kBlack); }

TEST(Compare, IdenticalImagesMatch) {
    const Image image = test::patternImage(30, 20);
    const ToleranceCompareResult result = compareShiftTolerant(image, image);
    ASSERT_TRUE(result.ok) << result.error;
    EXPECT_EQ(result.compared_count, 600u);
    EXPECT_EQ(result.mismatch_count, 0u);
    EXPECT_EQ(result.mismatch_fraction, 0.0);
    EXPECT_TRUE(result.mismatch_bounds.empty());
    EXPECT_TRUE(result.worst.tile.empty());
}

TEST(Compare, OnePixelShiftedSilhouetteMatches) {
    for (const auto& shift : {std::pair<float, float>{1, 0}, {0, 1}, {-1, 0}, {1, 1}, {-1, 1}}) {
        const ToleranceCompareResult result =
            compareShiftTolerant(disc(32, 32), disc(32 + shift.first, 32 + shift.second));
        ASSERT_TRUE(result.ok);
        EXPECT_EQ(result.mismatch_count, 0u) << "shift " << shift.first << "," << shift.second;
    }
}

TEST(Compare, TwoPixelShiftIsReportedOnTheEdges) {
    // Shifted right by 2: pixels within 1 of the left and right edges find no match.
    const ToleranceCompareResult result = compareShiftTolerant(disc(32, 32), disc(34, 32));
    ASSERT_TRUE(result.ok);
    EXPECT_GT(result.mismatch_count, 0u);
    // Every mismatch lies in the band the two discs' edges sweep: x in [32-12-1, 34+12+1].
    EXPECT_GE(result.mismatch_bounds.x0, 32 - 12 - 1);
    EXPECT_LE(result.mismatch_bounds.x1, 34 + 12 + 1);
    for (int y = 0; y < 64; ++y) {
        for (int x = 0; x < 64; ++x) {
            if (!result.mismatches.at(x, y)) continue;
            const float left = x + 0.5f - 32, right = x + 0.5f - 34, dy = y + 0.5f - 32;
            const float d_reference = std::sqrt(left * left + dy * dy);
            const float d_test = std::sqrt(right * right + dy * dy);
            EXPECT_TRUE(std::abs(d_reference - 12) < 2.5f || std::abs(d_test - 12) < 2.5f) << x << "," << y;
        }
    }
    // The disc's centre is not touched.
    EXPECT_EQ(result.mismatches.at(33, 32), 0);
    // The worst window holds mismatches and sits on the edge band.
    EXPECT_GT(result.worst.mismatch_count, 0u);
    EXPECT_FALSE(result.worst.mismatch_bounds.empty());
}

TEST(Compare, ColourChangeIsReportedExactly) {
    // An 8x8 block at (40, 20) brighter by 0.2 in the test image: exactly those 64 pixels
    // mismatch (their neighbours in the reference all have the old colour).
    const Image reference = test::greyImage(64, 48, 0.3f);
    Image test_image = reference;
    for (int y = 20; y < 28; ++y) {
        for (int x = 40; x < 48; ++x) {
            for (int c = 0; c < 3; ++c) test_image.at(x, y, c) = 0.5f;
        }
    }
    const ToleranceCompareResult result = compareShiftTolerant(reference, test_image);
    ASSERT_TRUE(result.ok);
    EXPECT_EQ(result.mismatch_count, 64u);
    EXPECT_NEAR(result.mismatch_fraction, 64.0 / (64 * 48), 1e-12);
    EXPECT_EQ(result.mismatch_bounds.x0, 40);
    EXPECT_EQ(result.mismatch_bounds.y0, 20);
    EXPECT_EQ(result.mismatch_bounds.x1, 47);
    EXPECT_EQ(result.mismatch_bounds.y1, 27);
    // The worst 16x16 window holds all 64 and is centred on the block.
    EXPECT_EQ(result.worst.mismatch_count, 64u);
    EXPECT_EQ(result.worst.tile.width(), 16);
    EXPECT_EQ(result.worst.tile.height(), 16);
    EXPECT_EQ(result.worst.centre.x, 44);
    EXPECT_EQ(result.worst.centre.y, 24);
    EXPECT_EQ(result.worst.mismatch_bounds.x0, 40);
    EXPECT_EQ(result.worst.mismatch_bounds.y1, 27);
}

TEST(Compare, WorstRegionPicksTheDensestCluster) {
    // A 2x2 change at (5, 5) and a 4x4 change at (50, 30): the worst window is the latter.
    const Image reference = test::greyImage(64, 48, 0.3f);
    Image test_image = reference;
    auto paint = [&](int x0, int y0, int size) {
        for (int y = y0; y < y0 + size; ++y) {
            for (int x = x0; x < x0 + size; ++x) test_image.at(x, y, 1) = 0.9f;
        }
    };
    paint(5, 5, 2);
    paint(50, 30, 4);
    ToleranceCompareConfig config;
    config.tile_size = 8;
    const ToleranceCompareResult result = compareShiftTolerant(reference, test_image, config);
    EXPECT_EQ(result.mismatch_count, 20u);
    EXPECT_EQ(result.worst.mismatch_count, 16u);
    EXPECT_EQ(result.worst.centre.x, 52);
    EXPECT_EQ(result.worst.centre.y, 32);
    EXPECT_EQ(result.worst.tile.x0, 48);
    EXPECT_EQ(result.worst.tile.x1, 55);
}

TEST(Compare, BothDirectionsAreChecked) {
    // A one-pixel line present in only one image. Extra in the test image: the test's line
    // pixels have no match in the reference. Missing from the test image: the reference's line
    // pixels have no match in the test. Each direction alone would miss one of the two cases.
    const Image plain = test::greyImage(32, 32, 0.2f);
    Image lined = plain;
    for (int y = 4; y < 28; ++y) {
        for (int c = 0; c < 3; ++c) lined.at(16, y, c) = 0.8f;
    }
    const ToleranceCompareResult extra = compareShiftTolerant(plain, lined);
    const ToleranceCompareResult missing = compareShiftTolerant(lined, plain);
    EXPECT_EQ(extra.mismatch_count, 24u);
    EXPECT_EQ(missing.mismatch_count, 24u);
    EXPECT_EQ(extra.mismatch_bounds.x0, 16);
    EXPECT_EQ(missing.mismatch_bounds.x1, 16);
}

TEST(Compare, ToleranceIsPerChannelAndInclusive) {
    const Image reference = test::constantImage(10, 10, 0.5f, 0.5f, 0.5f);
    ToleranceCompareConfig config;
    config.tolerance = 0.05f;
    EXPECT_EQ(compareShiftTolerant(reference, test::constantImage(10, 10, 0.54f, 0.46f, 0.5f), config)
                  .mismatch_count,
              0u);
    EXPECT_EQ(compareShiftTolerant(reference, test::constantImage(10, 10, 0.5f, 0.5f, 0.56f), config)
                  .mismatch_count,
              100u);
    config.tolerance = 0.0f;
    EXPECT_EQ(compareShiftTolerant(reference, reference, config).mismatch_count, 0u);
    // Alpha never matters.
    EXPECT_EQ(compareShiftTolerant(test::constantImage(4, 4, 0.5f, 0.5f, 0.5f, 4, 0.0f),
                                   test::constantImage(4, 4, 0.5f, 0.5f, 0.5f, 4, 1.0f))
                  .mismatch_count,
              0u);
}

TEST(Compare, SearchRadiusZeroIsAPlainComparison) {
    ToleranceCompareConfig config;
    config.search_radius = 0;
    EXPECT_GT(compareShiftTolerant(disc(32, 32), disc(33, 32), config).mismatch_count, 0u);
    config.search_radius = 2;
    EXPECT_EQ(compareShiftTolerant(disc(32, 32), disc(34, 32), config).mismatch_count, 0u);
}

TEST(Compare, MaskLimitsCountingButNotTheSearch) {
    const Image reference = test::greyImage(20, 20, 0.3f);
    Image test_image = reference;
    for (int c = 0; c < 3; ++c) {
        test_image.at(2, 2, c) = 0.9f;    // outside the mask
        test_image.at(10, 10, c) = 0.9f;  // inside
    }
    Mask mask(20, 20, 0);
    for (int y = 5; y < 15; ++y) {
        for (int x = 5; x < 15; ++x) mask.at(x, y) = 1;
    }
    ToleranceCompareConfig config;
    config.mask = &mask;
    const ToleranceCompareResult result = compareShiftTolerant(reference, test_image, config);
    EXPECT_EQ(result.compared_count, 100u);
    EXPECT_EQ(result.mismatch_count, 1u);
    EXPECT_NEAR(result.mismatch_fraction, 0.01, 1e-12);
    EXPECT_EQ(result.mismatches.at(2, 2), 0);
    EXPECT_EQ(result.mismatches.at(10, 10), 1);

    // A disc edge on the mask boundary, shifted by one pixel outwards, still matches: the
    // neighbour that matches lies outside the mask.
    Mask inside(64, 64, 0);
    for (int y = 0; y < 64; ++y) {
        for (int x = 0; x < 64; ++x) inside.at(x, y) = disc(32, 32).at(x, y, 0) > 0.5f ? 1 : 0;
    }
    config.mask = &inside;
    EXPECT_EQ(compareShiftTolerant(disc(32, 32), disc(33, 32), config).mismatch_count, 0u);
}

TEST(Compare, NaNNeverMatches) {
    const Image reference = test::greyImage(8, 8, 0.5f);
    Image test_image = reference;
    test_image.at(4, 4, 0) = std::numeric_limits<float>::quiet_NaN();
    const ToleranceCompareResult result = compareShiftTolerant(reference, test_image);
    EXPECT_EQ(result.mismatch_count, 1u);
    EXPECT_EQ(result.mismatches.at(4, 4), 1);
}

TEST(Compare, RejectsBadInput) {
    EXPECT_FALSE(compareShiftTolerant(test::greyImage(4, 4, 0.5f), test::greyImage(4, 5, 0.5f)).ok);
    ToleranceCompareConfig config;
    config.tolerance = -1.0f;
    EXPECT_FALSE(compareShiftTolerant(test::greyImage(4, 4, 0.5f), test::greyImage(4, 4, 0.5f), config).ok);
}

TEST(Coverage, FromAlphaInEitherImage) {
    Image reference = test::constantImage(4, 1, 0, 0, 0, 4, 0.0f);
    Image test_image = reference;
    reference.at(1, 0, 3) = 1.0f;                                      // the reference draws pixel 1
    test_image.at(2, 0, 3) = 0.5f;                                     // the student draws pixel 2
    test_image.at(3, 0, 3) = std::numeric_limits<float>::quiet_NaN();  // broken: graded
    const Mask mask = coverageFromAlpha(reference, test_image);
    ASSERT_EQ(mask.values.size(), 4u);
    EXPECT_EQ(mask.at(0, 0), 0);
    EXPECT_EQ(mask.at(1, 0), 1);
    EXPECT_EQ(mask.at(2, 0), 1);
    EXPECT_EQ(mask.at(3, 0), 1);
    EXPECT_EQ(coverageFromAlpha(reference, test_image, 0.6f).at(2, 0), 0);
    // Without alpha everything is covered.
    EXPECT_EQ(coverageFromAlpha(test::greyImage(3, 3, 0.0f), test::greyImage(3, 3, 0.0f)).count(), 9u);
    EXPECT_TRUE(coverageFromAlpha(test::greyImage(3, 3, 0.0f), test::greyImage(4, 3, 0.0f)).empty());
}

TEST(Coverage, FromCoverageImagesIgnoresAlpha) {
    Image reference = test::constantImage(3, 1, 0, 0, 0, 4, 1.0f);  // opaque black: nothing drawn
    Image test_image = reference;
    reference.at(0, 0, 2) = 1.0f;
    test_image.at(1, 0, 0) = 0.25f;
    const Mask mask = coverageFromImages(reference, test_image);
    EXPECT_EQ(mask.at(0, 0), 1);
    EXPECT_EQ(mask.at(1, 0), 1);
    EXPECT_EQ(mask.at(2, 0), 0);
}

}  // namespace
}  // namespace grader
