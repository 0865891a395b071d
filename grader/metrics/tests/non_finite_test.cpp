// NaN / Inf scan: counts per pixel, positions in row-major order, bounding box.
#include <gtest/gtest.h>

#include <limits>

#include "grader/metrics/metrics.h"
#include "test_images.h"

namespace grader {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

TEST(NonFinite, CleanImageHasNone) {
    const NonFiniteResult result = scanNonFinite(test::patternImage(20, 10));
    EXPECT_FALSE(result.any());
    EXPECT_EQ(result.nan_pixels, 0u);
    EXPECT_EQ(result.inf_pixels, 0u);
    EXPECT_TRUE(result.first_positions.empty());
    EXPECT_TRUE(result.bounding_box.empty());
}

TEST(NonFinite, CountsPixelsAndLocatesThem) {
    Image image = test::constantImage(10, 8, 0.5f, 0.5f, 0.5f, 4);
    image.at(3, 2, 1) = kNaN;   // NaN in green
    image.at(7, 5, 3) = kInf;   // +Inf in alpha: alpha is scanned too
    image.at(1, 1, 0) = -kInf;  // one pixel with both
    image.at(1, 1, 2) = kNaN;
    image.at(3, 2, 2) = kNaN;  // a second NaN in the same pixel counts once
    const NonFiniteResult result = scanNonFinite(image);
    EXPECT_TRUE(result.any());
    EXPECT_EQ(result.nan_pixels, 2u);         // (1,1) and (3,2)
    EXPECT_EQ(result.inf_pixels, 2u);         // (1,1) and (7,5)
    EXPECT_EQ(result.non_finite_pixels, 3u);  // (1,1), (3,2), (7,5)
    ASSERT_EQ(result.first_positions.size(), 3u);
    EXPECT_EQ(result.first_positions[0].x, 1);  // row-major order
    EXPECT_EQ(result.first_positions[0].y, 1);
    EXPECT_EQ(result.first_positions[1].x, 3);
    EXPECT_EQ(result.first_positions[1].y, 2);
    EXPECT_EQ(result.first_positions[2].x, 7);
    EXPECT_EQ(result.first_positions[2].y, 5);
    EXPECT_EQ(result.bounding_box.x0, 1);
    EXPECT_EQ(result.bounding_box.y0, 1);
    EXPECT_EQ(result.bounding_box.x1, 7);
    EXPECT_EQ(result.bounding_box.y1, 5);
}

TEST(NonFinite, KeepsOnlyTheFirstPositionsButCountsAll) {
    Image image = test::greyImage(50, 50, 0.1f, 1);
    for (int i = 0; i < 50; ++i) image.at(i, i, 0) = kNaN;  // the diagonal
    NonFiniteConfig config;
    config.max_positions = 4;
    const NonFiniteResult result = scanNonFinite(image, config);
    EXPECT_EQ(result.nan_pixels, 50u);
    ASSERT_EQ(result.first_positions.size(), 4u);
    EXPECT_EQ(result.first_positions[3].x, 3);
    EXPECT_EQ(result.bounding_box.width(), 50);
    EXPECT_EQ(result.bounding_box.height(), 50);
}

TEST(NonFinite, InconsistentImageIsReportedAsClean) {
    Image broken(4, 4, 3);
    broken.pixels.resize(5);
    EXPECT_FALSE(scanNonFinite(broken).any());
    EXPECT_FALSE(scanNonFinite(Image()).any());
}

}  // namespace
}  // namespace grader
