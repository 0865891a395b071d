// NaN / Inf scan of one image, every channel including alpha (see grader/metrics.h), and the
// identity test the metrics start with (image_access.h): the two scans over every value of an
// image, built with -ftree-vectorize (CMakeLists.txt).
#include <cmath>
#include <cstdint>
#include <cstring>

#include "grader/metrics/metrics.h"
#include "image_access.h"

namespace grader {

NonFiniteResult scanNonFinite(const Image& image, const NonFiniteConfig& config) {
    NonFiniteResult result;
    const int channels = image.channels;
    if (image.width <= 0 || image.height <= 0 || channels <= 0 ||
        image.pixels.size() < static_cast<std::size_t>(image.width) * image.height * channels) {
        return result;  // nothing (consistent) to scan
    }
    // Most images hold no NaN or Inf: one branch-free pass over the bits says so (exponent all
    // ones), vectorised (-ftree-vectorize, see CMakeLists.txt); only an image that has one is
    // scanned pixel by pixel for where.
    const std::size_t n = static_cast<std::size_t>(image.width) * image.height * channels;
    std::uint32_t any = 0;
    for (std::size_t i = 0; i < n; ++i) {
        std::uint32_t bits;
        std::memcpy(&bits, &image.pixels[i], sizeof bits);
        any |= (bits & 0x7f800000u) == 0x7f800000u ? 1u : 0u;
    }
    if (any == 0) return result;
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            const float* p = &image.pixels[image.index(x, y)];
            bool has_nan = false;
            bool has_inf = false;
            for (int c = 0; c < channels; ++c) {
                has_nan = has_nan || std::isnan(p[c]);
                has_inf = has_inf || std::isinf(p[c]);
            }
            if (!has_nan && !has_inf) continue;
            result.nan_pixels += has_nan;
            result.inf_pixels += has_inf;
            ++result.non_finite_pixels;
            result.bounding_box.include(x, y);
            if (static_cast<int>(result.first_positions.size()) < config.max_positions) {
                result.first_positions.push_back({x, y});
            }
        }
    }
    return result;
}

namespace detail {

bool identicalPixels(const Image& a, const Image& b) {
    if (a.channels != b.channels || a.pixels.size() != b.pixels.size()) return false;
    const float* p = a.pixels.data();
    const float* q = b.pixels.data();
    const std::size_t n = a.pixels.size();
    // Blocks of a fixed length without an exit inside, so that the compiler vectorises them; the
    // first differing block ends the scan. float ==: a NaN is never identical, -0 equals +0.
    constexpr std::size_t kBlock = 256;
    std::size_t i = 0;
    for (; i + kBlock <= n; i += kBlock) {
        unsigned differs = 0;
        for (std::size_t k = 0; k < kBlock; ++k) differs |= p[i + k] == q[i + k] ? 0u : 1u;
        if (differs != 0) return false;
    }
    for (; i < n; ++i)
        if (!(p[i] == q[i])) return false;
    return true;
}

namespace {

// The level quantise8 (scoring.cpp) puts v on, 0..255, in the same exact steps.
inline int level8(float v) {
    const float positive = v > 0.0f ? v : 0.0f;  // NaN fails v > 0: 0
    const float x = (positive < 1.0f ? positive : 1.0f) * 255.0f;
    const int k = static_cast<int>(x);
    return k + (x - static_cast<float>(k) >= 0.5f ? 1 : 0);
}

}  // namespace

bool quantisedPixelsEqual(const Image& a, const Image& b) {
    if (a.width != b.width || a.height != b.height || a.channels != b.channels ||
        a.pixels.size() != b.pixels.size())
        return false;
    const float* p = a.pixels.data();
    const float* q = b.pixels.data();
    const std::size_t n = a.pixels.size();
    constexpr std::size_t kBlock = 256;
    std::size_t i = 0;
    for (; i + kBlock <= n; i += kBlock) {
        int differs = 0;
        for (std::size_t k = 0; k < kBlock; ++k) differs |= level8(p[i + k]) ^ level8(q[i + k]);
        if (differs != 0) return false;
    }
    for (; i < n; ++i)
        if (level8(p[i]) != level8(q[i])) return false;
    return true;
}

}  // namespace detail

}  // namespace grader
