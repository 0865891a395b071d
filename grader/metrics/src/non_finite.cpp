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

namespace {

// True when `same(p[i], q[i])` holds for every i < n. Blocks of a fixed length without an exit
// inside, so that the compiler vectorises them; the first block with a difference ends the scan.
template <typename Same>
bool everyValue(const float* p, const float* q, std::size_t n, Same same) {
    constexpr std::size_t kBlock = 256;
    std::size_t i = 0;
    for (; i + kBlock <= n; i += kBlock) {
        unsigned differs = 0;
        for (std::size_t k = 0; k < kBlock; ++k) differs |= same(p[i + k], q[i + k]) ? 0u : 1u;
        if (differs != 0) return false;
    }
    for (; i < n; ++i)
        if (!same(p[i], q[i])) return false;
    return true;
}

}  // namespace

bool identicalPixels(const Image& a, const Image& b) {
    if (a.channels != b.channels || a.pixels.size() != b.pixels.size()) return false;
    // float ==: a NaN is never identical, -0 equals +0.
    return everyValue(a.pixels.data(), b.pixels.data(), a.pixels.size(),
                      [](float x, float y) { return x == y; });
}

bool quantisedPixelsEqual(const Image& a, const Image& b) {
    if (a.width != b.width || a.height != b.height || a.channels != b.channels ||
        a.pixels.size() != b.pixels.size())
        return false;
    return everyValue(a.pixels.data(), b.pixels.data(), a.pixels.size(),
                      [](float x, float y) { return level8(x) == level8(y); });
}

}  // namespace detail

}  // namespace grader
