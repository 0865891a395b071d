// PNG round trip through writePng / readPng: 8-bit quantisation error at most half a step,
// clamping and NaN handling on write, errors reported for missing files.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>

#include "grader/image.h"
#include "test_images.h"

namespace grader {
namespace {

std::string temporaryPng(const std::string& name) {
    return (std::filesystem::temp_directory_path() / ("grader_test_" + name + ".png")).string();
}

TEST(ImageIo, RoundTripQuantisesToHalfAStep) {
    for (int channels : {1, 3, 4}) {
        Image original(23, 17, channels);
        test::Lcg random(channels);
        for (float& v : original.pixels) v = random.next();
        const std::string path = temporaryPng("round_trip_" + std::to_string(channels));
        std::string error;
        ASSERT_TRUE(writePng(original, path, &error)) << error;
        Image loaded;
        ASSERT_TRUE(readPng(path, &loaded, &error)) << error;
        std::filesystem::remove(path);
        ASSERT_EQ(loaded.width, 23);
        ASSERT_EQ(loaded.height, 17);
        ASSERT_EQ(loaded.channels, channels);
        float worst = 0.0f;
        for (std::size_t i = 0; i < original.pixels.size(); ++i) {
            worst = std::max(worst, std::abs(loaded.pixels[i] - original.pixels[i]));
        }
        EXPECT_LE(worst, 0.5f / 255.0f + 1e-6f) << channels << " channels";
        EXPECT_GT(worst, 0.0f);  // random floats do not all sit on the 8-bit grid
    }
}

TEST(ImageIo, WriteClampsAndZeroesNaN) {
    Image image(4, 1, 1);
    image.pixels = {-0.5f, 1.7f, std::numeric_limits<float>::quiet_NaN(), 0.5f};
    const std::string path = temporaryPng("clamp");
    std::string error;
    ASSERT_TRUE(writePng(image, path, &error)) << error;
    Image loaded;
    ASSERT_TRUE(readPng(path, &loaded, &error)) << error;
    std::filesystem::remove(path);
    EXPECT_EQ(loaded.pixels[0], 0.0f);
    EXPECT_EQ(loaded.pixels[1], 1.0f);
    EXPECT_EQ(loaded.pixels[2], 0.0f);
    EXPECT_EQ(loaded.pixels[3], 128.0f / 255.0f);  // 0.5 * 255 = 127.5 rounds up
}

TEST(ImageIo, ReportsUnreadableAndUnwritablePaths) {
    Image loaded;
    std::string error;
    EXPECT_FALSE(readPng("/nonexistent/grader/none.png", &loaded, &error));
    EXPECT_NE(error.find("none.png"), std::string::npos);
    EXPECT_FALSE(writePng(test::greyImage(2, 2, 0.5f), "/nonexistent/folder/out.png", &error));
    Image inconsistent(2, 2, 3);
    inconsistent.pixels.pop_back();
    EXPECT_FALSE(writePng(inconsistent, temporaryPng("inconsistent"), &error));
}

}  // namespace
}  // namespace grader
