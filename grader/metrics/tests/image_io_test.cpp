// PNG round trip through writePng / readPng: 8-bit quantisation error at most half a step,
// clamping and NaN handling on write, errors reported for missing files.
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "grader/metrics/image.h"
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

// CRC-32 as PNG chunks use it (ISO 3309; PNG specification, section 5.5), bitwise.
std::uint32_t pngCrc(const std::string& bytes) {
    std::uint32_t crc = 0xFFFFFFFFu;
    for (unsigned char byte : bytes) {
        crc ^= byte;
        for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
    return crc ^ 0xFFFFFFFFu;
}

std::string bigEndian(std::uint32_t v) {
    return {static_cast<char>(v >> 24), static_cast<char>(v >> 16), static_cast<char>(v >> 8),
            static_cast<char>(v)};
}

long peakResidentKiB() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return usage.ru_maxrss;
}

// A few dozen bytes that claim 16000x16000 pixels: refused from the header, before any pixel
// memory is allocated (decoding it would need about 1 GB of 8-bit and 4 GB of float pixels).
TEST(ImageIo, RefusesAHeaderThatClaimsTooManyPixels) {
    const std::string ihdr = "IHDR" + bigEndian(16000) + bigEndian(16000) + std::string("\x08\x06\0\0\0", 5);
    const std::string iend = "IEND";
    std::string png = "\x89PNG\r\n\x1a\n";
    png += bigEndian(13) + ihdr + bigEndian(pngCrc(ihdr));
    png += bigEndian(0) + iend + bigEndian(pngCrc(iend));
    const std::string path = temporaryPng("header_bomb");
    std::ofstream(path, std::ios::binary) << png;

    const long before = peakResidentKiB();
    Image loaded;
    std::string error;
    EXPECT_FALSE(readPng(path, &loaded, &error));
    const long grown_mib = (peakResidentKiB() - before) / 1024;
    std::filesystem::remove(path);
    EXPECT_NE(error.find("16000x16000"), std::string::npos) << error;
    EXPECT_NE(error.find("limit"), std::string::npos) << error;
    EXPECT_TRUE(loaded.pixels.empty());
    EXPECT_LT(grown_mib, 16) << "the peak resident size grew while refusing the image";
}

}  // namespace
}  // namespace grader
