// NaN / Inf scan of one image, every channel including alpha (see grader/metrics.h).
#include <cmath>

#include "grader/metrics/metrics.h"

namespace grader {

NonFiniteResult scanNonFinite(const Image& image, const NonFiniteConfig& config) {
    NonFiniteResult result;
    const int channels = image.channels;
    if (image.width <= 0 || image.height <= 0 || channels <= 0 ||
        image.pixels.size() < static_cast<std::size_t>(image.width) * image.height * channels) {
        return result;  // nothing (consistent) to scan
    }
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

}  // namespace grader
