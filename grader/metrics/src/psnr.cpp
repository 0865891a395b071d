// PSNR over R, G, B of the counted pixels (formula and conventions in grader/metrics.h). It does
// not look for NaN or Inf (scanNonFinite does); they propagate into the result.
#include <cmath>
#include <limits>

#include "grader/metrics/metrics.h"
#include "image_access.h"
#include "kernels.h"

namespace grader {
namespace {

PsnrResult finish(PsnrResult& result, double squared_sum, std::size_t counted, double peak) {
    result.ok = true;
    result.pixel_count = counted;
    result.mse = squared_sum / (3.0 * static_cast<double>(counted));
    result.psnr_db = result.mse == 0.0 ? std::numeric_limits<double>::infinity()
                                       : 10.0 * std::log10(peak * peak / result.mse);
    return result;
}

}  // namespace

PsnrResult computePsnr(const Image& reference, const Image& test, const PsnrConfig& config) {
    PsnrResult result;
    result.error = detail::checkPair(reference, test, config.mask);
    if (!result.error.empty()) return result;
    if (!(config.peak > 0.0)) {
        result.error = "PSNR peak must be positive";
        return result;
    }

    const int ref_channels = reference.channels;
    const int test_channels = test.channels;
    const int ref_offsets[3] = {detail::colourChannel(reference, 0), detail::colourChannel(reference, 1),
                                detail::colourChannel(reference, 2)};
    const int test_offsets[3] = {detail::colourChannel(test, 0), detail::colourChannel(test, 1),
                                 detail::colourChannel(test, 2)};
    const std::size_t pixels = static_cast<std::size_t>(reference.width) * reference.height;

    if (config.mask == nullptr && ref_channels == test_channels && ref_channels >= 3) {
        // The common case, vectorised (kernels.h).
        const detail::KernelTable& kernels = detail::kernels();
        double squared_sum = 0.0;
        const std::size_t row_values = static_cast<std::size_t>(reference.width) * ref_channels;
        for (int y = 0; y < reference.height; ++y) {
            squared_sum +=
                kernels.squared_error_rgb(&reference.pixels[y * row_values], &test.pixels[y * row_values],
                                          ref_channels, reference.width);
        }
        return finish(result, squared_sum, pixels, config.peak);
    }

    // Double accumulation: a million squared differences of ~1e-6 each would lose digits in
    // float. One accumulator per channel, so the adds do not queue behind each other.
    double channel_sums[3] = {0.0, 0.0, 0.0};
    std::size_t counted = 0;
    for (std::size_t i = 0; i < pixels; ++i) {
        if (!detail::counts(config.mask, i)) continue;
        const float* r = &reference.pixels[i * ref_channels];
        const float* t = &test.pixels[i * test_channels];
        for (int c = 0; c < 3; ++c) {
            const double d = static_cast<double>(t[test_offsets[c]]) - r[ref_offsets[c]];
            channel_sums[c] += d * d;
        }
        ++counted;
    }
    if (counted == 0) {
        result.error = "the mask selects no pixels; PSNR is undefined";
        return result;
    }
    return finish(result, channel_sums[0] + channel_sums[1] + channel_sums[2], counted, config.peak);
}

}  // namespace grader
