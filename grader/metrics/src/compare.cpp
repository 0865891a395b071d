// Shift-tolerant comparison, worst-region search and coverage masks (see grader/compare.h).
#include "grader/metrics/compare.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "image_access.h"

namespace grader {
namespace {

// Every colour channel within tolerance. Written as three <= tests (not a max of
// differences) so that a NaN anywhere makes the pair fail instead of vanishing inside max().
inline bool closeEnough(const float* a, const int* a_offsets, const float* b, const int* b_offsets,
                        float tolerance) {
    return std::abs(a[a_offsets[0]] - b[b_offsets[0]]) <= tolerance &&
           std::abs(a[a_offsets[1]] - b[b_offsets[1]]) <= tolerance &&
           std::abs(a[a_offsets[2]] - b[b_offsets[2]]) <= tolerance;
}

// Whether pixel (x, y) of `from` has a close pixel within `radius` in `to`.
bool hasMatch(const Image& from, const int* from_offsets, const Image& to, const int* to_offsets, int x,
              int y, int radius, float tolerance) {
    const float* pixel = &from.pixels[from.index(x, y)];
    const int y0 = std::max(0, y - radius), y1 = std::min(to.height - 1, y + radius);
    const int x0 = std::max(0, x - radius), x1 = std::min(to.width - 1, x + radius);
    // The same position first: it matches in the common case, ending the search at once.
    if (closeEnough(pixel, from_offsets, &to.pixels[to.index(x, y)], to_offsets, tolerance)) return true;
    for (int qy = y0; qy <= y1; ++qy) {
        for (int qx = x0; qx <= x1; ++qx) {
            if (closeEnough(pixel, from_offsets, &to.pixels[to.index(qx, qy)], to_offsets, tolerance))
                return true;
        }
    }
    return false;
}

// Finds the tile_w x tile_h window with the most mismatches (summed-area table), then slides
// it, without losing any of them, so that it is centred on the mismatches it holds.
WorstRegion findWorstRegion(const Mask& mismatches, int tile_size) {
    WorstRegion worst;
    const int width = mismatches.width;
    const int height = mismatches.height;
    const int tile_w = std::min(std::max(tile_size, 1), width);
    const int tile_h = std::min(std::max(tile_size, 1), height);

    // sat[(y) * (width + 1) + x] = mismatches in [0, x) x [0, y).
    const int stride = width + 1;
    std::vector<std::uint32_t> sat(static_cast<std::size_t>(stride) * (height + 1), 0);
    for (int y = 0; y < height; ++y) {
        std::uint32_t row_sum = 0;
        for (int x = 0; x < width; ++x) {
            row_sum += mismatches.at(x, y) != 0;
            sat[static_cast<std::size_t>(y + 1) * stride + x + 1] =
                sat[static_cast<std::size_t>(y) * stride + x + 1] + row_sum;
        }
    }
    auto count_in = [&](int x0, int y0, int w, int h) {
        const std::size_t top = static_cast<std::size_t>(y0) * stride,
                          bottom = static_cast<std::size_t>(y0 + h) * stride;
        return sat[bottom + x0 + w] - sat[bottom + x0] - sat[top + x0 + w] + sat[top + x0];
    };

    std::uint32_t best = 0;
    int best_x = 0, best_y = 0;
    for (int y0 = 0; y0 + tile_h <= height; ++y0) {
        for (int x0 = 0; x0 + tile_w <= width; ++x0) {
            const std::uint32_t n = count_in(x0, y0, tile_w, tile_h);
            if (n > best) {
                best = n;
                best_x = x0;
                best_y = y0;
            }
        }
    }
    if (best == 0) return worst;

    PixelBox inside;
    for (int y = best_y; y < best_y + tile_h; ++y) {
        for (int x = best_x; x < best_x + tile_w; ++x) {
            if (mismatches.at(x, y)) inside.include(x, y);
        }
    }
    // Any window position in [x1 - tile_w + 1, x0] still holds that bounding box (it is at
    // most tile_w wide), so the count cannot drop; pick the centred one, kept in the image.
    auto centred = [](int lo, int hi, int tile, int extent) {
        const int ideal = (lo + hi + 1 - tile) / 2;
        const int min_start = std::max(hi - tile + 1, 0);
        const int max_start = std::min(lo, extent - tile);
        return std::min(std::max(ideal, min_start), max_start);
    };
    const int x0 = centred(inside.x0, inside.x1, tile_w, width);
    const int y0 = centred(inside.y0, inside.y1, tile_h, height);
    worst.tile = {x0, y0, x0 + tile_w - 1, y0 + tile_h - 1};
    worst.centre = {x0 + tile_w / 2, y0 + tile_h / 2};
    worst.mismatch_count = count_in(x0, y0, tile_w, tile_h);
    for (int y = y0; y < y0 + tile_h; ++y) {
        for (int x = x0; x < x0 + tile_w; ++x) {
            if (mismatches.at(x, y)) worst.mismatch_bounds.include(x, y);
        }
    }
    return worst;
}

bool sameSize(const Image& a, const Image& b) {
    return detail::checkImage(a, "a").empty() && detail::checkImage(b, "b").empty() && a.width == b.width &&
           a.height == b.height;
}

}  // namespace

ToleranceCompareResult compareShiftTolerant(const Image& reference, const Image& test,
                                            const ToleranceCompareConfig& config) {
    ToleranceCompareResult result;
    result.error = detail::checkPair(reference, test, config.mask);
    if (!result.error.empty()) return result;
    if (config.search_radius < 0 || !(config.tolerance >= 0.0f)) {
        result.error = "search_radius and tolerance must not be negative";
        return result;
    }

    const int width = reference.width;
    const int height = reference.height;
    const int ref_offsets[3] = {detail::colourChannel(reference, 0), detail::colourChannel(reference, 1),
                                detail::colourChannel(reference, 2)};
    const int test_offsets[3] = {detail::colourChannel(test, 0), detail::colourChannel(test, 1),
                                 detail::colourChannel(test, 2)};
    result.mismatches = Mask(width, height, 0);
    if (detail::identicalPixels(reference, test)) {
        // Every pixel finds itself: nothing to search.
        for (std::size_t i = 0; i < result.mismatches.values.size(); ++i)
            result.compared_count += detail::counts(config.mask, i) ? 1 : 0;
        result.worst = findWorstRegion(result.mismatches, config.tile_size);
        result.ok = true;
        return result;
    }
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * width + x;
            if (!detail::counts(config.mask, i)) continue;
            ++result.compared_count;
            // The reference pixel must find its colour near it in the test image, and the test
            // pixel its colour near it in the reference (the second search only if needed).
            const bool matched = hasMatch(reference, ref_offsets, test, test_offsets, x, y,
                                          config.search_radius, config.tolerance) &&
                                 hasMatch(test, test_offsets, reference, ref_offsets, x, y,
                                          config.search_radius, config.tolerance);
            if (!matched) {
                result.mismatches.values[i] = 1;
                ++result.mismatch_count;
                result.mismatch_bounds.include(x, y);
            }
        }
    }
    result.mismatch_fraction = result.compared_count == 0 ? 0.0
                                                          : static_cast<double>(result.mismatch_count) /
                                                                static_cast<double>(result.compared_count);
    result.worst = findWorstRegion(result.mismatches, config.tile_size);
    result.ok = true;
    return result;
}

Mask coverageFromAlpha(const Image& reference, const Image& test, float threshold) {
    if (!sameSize(reference, test)) return {};
    Mask mask(reference.width, reference.height, 1);
    if (reference.channels != 4 && test.channels != 4) return mask;
    for (int y = 0; y < reference.height; ++y) {
        for (int x = 0; x < reference.width; ++x) {
            // An image without alpha covers everything; NaN alpha fails "<= threshold" and so
            // counts as covered.
            const bool ref_covered = reference.channels != 4 || !(reference.at(x, y, 3) <= threshold);
            const bool test_covered = test.channels != 4 || !(test.at(x, y, 3) <= threshold);
            mask.at(x, y) = (ref_covered || test_covered) ? 1 : 0;
        }
    }
    return mask;
}

Mask coverageFromImages(const Image& reference_coverage, const Image& test_coverage, float threshold) {
    if (!sameSize(reference_coverage, test_coverage)) return {};
    Mask mask(reference_coverage.width, reference_coverage.height, 0);
    // Colour channels only: an opaque coverage render has alpha 1 everywhere.
    auto covered = [threshold](const Image& image, int x, int y) {
        for (int c = 0; c < 3; ++c) {
            if (!(image.at(x, y, detail::colourChannel(image, c)) <= threshold))
                return true;  // above, or NaN
        }
        return false;
    };
    for (int y = 0; y < mask.height; ++y) {
        for (int x = 0; x < mask.width; ++x) {
            mask.at(x, y) = (covered(reference_coverage, x, y) || covered(test_coverage, x, y)) ? 1 : 0;
        }
    }
    return mask;
}

}  // namespace grader
