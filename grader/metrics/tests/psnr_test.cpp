// PSNR: values derived by hand from the definition, masks, channel handling, input checks.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "grader/metrics/metrics.h"
#include "test_images.h"

namespace grader {
namespace {

using test::constantImage;
using test::greyImage;

TEST(Psnr, ConstantOffsetIsMinusTwentyLogOffset) {
    // Every channel off by d: MSE = d^2, PSNR = 10 log10(1 / d^2) = -20 log10(d).
    for (float d : {0.1f, 0.02f, 0.25f}) {
        const Image reference = greyImage(20, 10, 0.3f);
        const Image test = greyImage(20, 10, 0.3f + d);
        const PsnrResult result = computePsnr(reference, test);
        ASSERT_TRUE(result.ok) << result.error;
        const double actual_d = static_cast<double>(0.3f + d) - 0.3f;  // the offset as stored in float
        EXPECT_NEAR(result.mse, actual_d * actual_d, 1e-12);
        EXPECT_NEAR(result.psnr_db, -20.0 * std::log10(actual_d), 1e-9);
        EXPECT_EQ(result.pixel_count, 200u);
    }
}

TEST(Psnr, OffsetInOneChannelCountsAsOneThirdOfTheMse) {
    // Only red off by 0.3: MSE = 0.09 / 3 = 0.03.
    const Image reference = constantImage(8, 8, 0.2f, 0.4f, 0.6f);
    const Image test = constantImage(8, 8, 0.5f, 0.4f, 0.6f);
    const PsnrResult result = computePsnr(reference, test);
    ASSERT_TRUE(result.ok);
    const double d = static_cast<double>(0.5f) - 0.2f;
    EXPECT_NEAR(result.mse, d * d / 3.0, 1e-12);
}

TEST(Psnr, IdenticalImagesGiveInfinity) {
    const Image image = test::patternImage(33, 17);
    const PsnrResult result = computePsnr(image, image);
    ASSERT_TRUE(result.ok);
    EXPECT_EQ(result.mse, 0.0);
    EXPECT_EQ(result.psnr_db, std::numeric_limits<double>::infinity());
}

TEST(Psnr, AlphaIsIgnored) {
    const Image reference = constantImage(4, 4, 0.1f, 0.2f, 0.3f, 4, 1.0f);
    const Image test = constantImage(4, 4, 0.1f, 0.2f, 0.3f, 4, 0.0f);
    EXPECT_EQ(computePsnr(reference, test).psnr_db, std::numeric_limits<double>::infinity());
}

TEST(Psnr, GreyImageComparesAsEqualRgb) {
    const Image grey = greyImage(5, 5, 0.5f, 1);
    const Image rgb = greyImage(5, 5, 0.5f, 3);
    EXPECT_EQ(computePsnr(grey, rgb).psnr_db, std::numeric_limits<double>::infinity());
    const Image brighter = greyImage(5, 5, 0.6f, 4);
    const double d = static_cast<double>(0.6f) - 0.5f;
    EXPECT_NEAR(computePsnr(grey, brighter).mse, d * d, 1e-12);
}

TEST(Psnr, MaskRestrictsThePixelsThatCount) {
    // Left half identical, right half off by 0.5; the mask selects the left half plus one
    // right-hand pixel, so MSE = 0.25 / (count).
    Image reference = greyImage(10, 4, 0.25f);
    Image test = reference;
    for (int y = 0; y < 4; ++y) {
        for (int x = 5; x < 10; ++x) {
            for (int c = 0; c < 3; ++c) test.at(x, y, c) = 0.75f;
        }
    }
    Mask mask(10, 4, 0);
    for (int y = 0; y < 4; ++y) {
        for (int x = 0; x < 5; ++x) mask.at(x, y) = 1;
    }
    PsnrConfig config;
    config.mask = &mask;
    PsnrResult result = computePsnr(reference, test, config);
    ASSERT_TRUE(result.ok);
    EXPECT_EQ(result.pixel_count, 20u);
    EXPECT_EQ(result.psnr_db, std::numeric_limits<double>::infinity());

    mask.at(7, 2) = 1;
    result = computePsnr(reference, test, config);
    EXPECT_EQ(result.pixel_count, 21u);
    EXPECT_NEAR(result.mse, 0.25 / 21.0, 1e-12);
}

TEST(Psnr, NaNPropagates) {
    Image reference = greyImage(4, 4, 0.5f);
    Image test = reference;
    test.at(1, 1, 2) = std::numeric_limits<float>::quiet_NaN();
    const PsnrResult result = computePsnr(reference, test);
    ASSERT_TRUE(result.ok);
    EXPECT_TRUE(std::isnan(result.psnr_db));
}

TEST(Psnr, RejectsMismatchedInputs) {
    const Image a = greyImage(4, 4, 0.5f);
    const Image b = greyImage(4, 5, 0.5f);
    PsnrResult result = computePsnr(a, b);
    EXPECT_FALSE(result.ok);
    EXPECT_NE(result.error.find("sizes must match"), std::string::npos) << result.error;

    Mask wrong(3, 3, 1);
    PsnrConfig config;
    config.mask = &wrong;
    result = computePsnr(a, a, config);
    EXPECT_FALSE(result.ok);
    EXPECT_NE(result.error.find("mask"), std::string::npos);

    Mask empty(4, 4, 0);
    config.mask = &empty;
    result = computePsnr(a, a, config);
    EXPECT_FALSE(result.ok);

    EXPECT_FALSE(computePsnr(Image(), Image()).ok);
    Image two_channels(4, 4, 2);
    EXPECT_FALSE(computePsnr(two_channels, two_channels).ok);
}

}  // namespace
}  // namespace grader
