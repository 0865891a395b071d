// Internal: the input checks and colour-channel access every metric shares, so that all of
// them treat channel counts, sizes and masks the same way.
#pragma once

#include <cstddef>
#include <string>

#include "grader/metrics/image.h"
#include "grader/metrics/mask.h"

namespace grader::detail {

inline bool supportedChannelCount(int channels) { return channels == 1 || channels == 3 || channels == 4; }

// Interleaved offset of colour channel c (0 = R, 1 = G, 2 = B) within a pixel: grey images
// answer every colour channel from their single channel; alpha is never a colour channel.
inline int colourChannel(const Image& image, int c) { return image.channels >= 3 ? c : 0; }

inline std::string describeSize(const Image& image) {
    return std::to_string(image.width) + "x" + std::to_string(image.height) + "x" +
           std::to_string(image.channels);
}

// Empty when the image is usable on its own; otherwise what is wrong with it.
inline std::string checkImage(const Image& image, const char* role) {
    if (image.width <= 0 || image.height <= 0) {
        return std::string(role) + " image is empty (" + describeSize(image) + ")";
    }
    if (!supportedChannelCount(image.channels)) {
        return std::string(role) + " image has " + std::to_string(image.channels) +
               " channels; expected 1, 3 or 4";
    }
    if (image.pixels.size() != static_cast<std::size_t>(image.width) * image.height * image.channels) {
        return std::string(role) + " image holds " + std::to_string(image.pixels.size()) +
               " values, not width * height * channels for " + describeSize(image);
    }
    return {};
}

// Empty when reference, test and the optional mask fit together; otherwise why not.
inline std::string checkPair(const Image& reference, const Image& test, const Mask* mask) {
    std::string error = checkImage(reference, "reference");
    if (error.empty()) error = checkImage(test, "test");
    if (!error.empty()) return error;
    if (reference.width != test.width || reference.height != test.height) {
        return "reference is " + describeSize(reference) + " but test is " + describeSize(test) +
               "; the sizes must match";
    }
    if (mask != nullptr) {
        if (mask->width != reference.width || mask->height != reference.height ||
            mask->values.size() != static_cast<std::size_t>(mask->width) * mask->height) {
            return "mask is " + std::to_string(mask->width) + "x" + std::to_string(mask->height) +
                   " but the images are " + std::to_string(reference.width) + "x" +
                   std::to_string(reference.height);
        }
    }
    return {};
}

// True when both images hold the same values, channel for channel (float ==, so a NaN is never
// identical and such images take the full path). Metrics use it to skip their filters: equal
// inputs have known results (PSNR infinite, SSIM 1, FLIP 0, no mismatch).
// The level of 0..255 that quantise8 (scoring.h) puts `v` on: round(clamp(v, 0, 1) * 255), NaN
// as 0. Written so that loops over it vectorise (scoring.cpp and non_finite.cpp are built with
// -ftree-vectorize): for 0 <= x <= 255, k = trunc(x) and x - k are exact in float, so
// k + (x - k >= 0.5) is round-half-up of x, as floor(x + 0.5) in double is.
inline int level8(float v) {
    const float positive = v > 0.0f ? v : 0.0f;  // NaN fails v > 0: 0
    const float x = (positive < 1.0f ? positive : 1.0f) * 255.0f;
    const int k = static_cast<int>(x);
    return k + (x - static_cast<float>(k) >= 0.5f ? 1 : 0);
}

// Defined in non_finite.cpp, which is built to vectorise its scans.
bool identicalPixels(const Image& a, const Image& b);
// True when quantise8 (scoring.h) would turn both images into the same one: the same size and
// channels, and every value on the same of the 256 levels (NaN counts as 0). No copy is made.
bool quantisedPixelsEqual(const Image& a, const Image& b);

inline bool counts(const Mask* mask, std::size_t pixel) {
    return mask == nullptr || mask->values[pixel] != 0;
}

}  // namespace grader::detail
