// SSIM with a Gaussian window, per colour channel, averaged over channels, following
// scikit-image's conventions (see grader/metrics.h for the formula and the source).
//
// SSIM needs mu_x, mu_y, sigma_x^2 + sigma_y^2 and sigma_xy, and four windowed moments of
// s = x + y and d = x - y give them as well as the usual five of x and y:
//   2 mu_x mu_y = (mu_s^2 - mu_d^2) / 2,          mu_x^2 + mu_y^2 = (mu_s^2 + mu_d^2) / 2,
//   2 sigma_xy = (var_s - var_d) / 2,             sigma_x^2 + sigma_y^2 = (var_s + var_d) / 2,
// with var_s = E[s^2] - mu_s^2 and var_d = E[d^2] - mu_d^2: one filtered moment fewer.
//
// Precision: double. A variance computed as E[v^2] - E[v]^2 loses to rounding about 1e-7 of
// v^2 in float, and SSIM moves by up to (that error) / C2 in flat or smooth regions,
// C2 = 9e-4: measured against scikit-image, float filtering was off by up to 3e-4 (and above
// 1 on flat images), and float for the moments of d alone still by 1.2e-4 on flat regions far
// apart in value. In double the agreement is ~1e-8, at twice the filtering time. The one
// exception: where every difference d in a window is at most 1/16, the error bound above is
// 256 times smaller for the moments of d, and those run in float (see computeSsim).
//
// Per channel the moments come from a horizontal pass into rings of rows and a vertical pass
// for two output rows at a time (filter.h); the SSIM of those rows is formed right away, so no
// whole plane is ever stored. The inner loops run in the kernel table (kernels.h).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "filter.h"
#include "grader/metrics/metrics.h"
#include "image_access.h"
#include "kernels.h"

namespace grader {
namespace {

// scipy.ndimage.gaussian_filter's kernel: exp(-x^2 / (2 sigma^2)) on integer offsets up to
// radius = int(truncate * sigma + 0.5), normalised to sum 1; truncate = 3.5 as in skimage,
// which gives 11 taps for sigma 1.5 (Wang et al. use an 11x11 window).
detail::Kernel gaussianWindow(double sigma) {
    detail::Kernel kernel;
    kernel.radius = static_cast<int>(3.5 * sigma + 0.5);
    std::vector<double> weights(2 * kernel.radius + 1);
    double sum = 0.0;
    for (int k = -kernel.radius; k <= kernel.radius; ++k) {
        weights[k + kernel.radius] = std::exp(-0.5 * k * k / (sigma * sigma));
        sum += weights[k + kernel.radius];
    }
    for (double w : weights) {
        kernel.taps_f64.push_back(w / sum);
        kernel.taps.push_back(static_cast<float>(w / sum));
    }
    return kernel;
}

// The two moments of one quantity (its mean and the mean of its square) for every channel, in
// precision T: padded input rows, rings of horizontally filtered rows, and the vertically
// filtered rows of a pair of output rows. Zeroed, rows padded to whole vector groups.
template <typename T>
class MomentPair {
  public:
    MomentPair(int width, int radius, const detail::RowRing& ring)
        : width_(width),
          radius_(radius),
          padded_width_(static_cast<std::size_t>(width) + 2 * radius),
          ring_stride_(detail::ringStride(width)),
          ring_size_(ring_stride_ * ring.slots()),
          row_stride_(detail::paddedRowLength(width)),
          storage_(3 * 2 * (padded_width_ + ring_size_) + 2 * 2 * row_stride_, T(0)) {}

    // Input row (value, square) of a channel, to be filled in [radius, radius + width).
    T* input(int channel, int which) { return &storage_[(channel * 2 + which) * padded_width_]; }
    T* ring(int channel, int which) {
        return &storage_[3 * 2 * padded_width_ + (channel * 2 + which) * ring_size_];
    }
    // Vertically filtered row `which` of output row y + pair.
    T* filtered(int pair, int which) {
        return &storage_[3 * 2 * (padded_width_ + ring_size_) + (pair * 2 + which) * row_stride_];
    }

    // Horizontal pass of the channel's two input rows into ring slot `slot`.
    void filterRow(int channel, int slot, const detail::Kernel& window,
                   const detail::ColumnOffsets& columns) {
        for (int which = 0; which < 2; ++which) {
            T* row = input(channel, which);
            detail::fillBorders(row, width_, radius_, detail::Border::Reflect);
            detail::filterEven(detail::horizontalTaps(static_cast<const T*>(row), radius_, radius_, columns),
                               0, width_, window, ring(channel, which) + slot * ring_stride_);
        }
    }

    // Row `slot` of a ring, for copying between the float and the double rings.
    T* ringRow(int channel, int which, int slot) { return ring(channel, which) + slot * ring_stride_; }

    // Vertical pass for output rows y and (if `pair`) y + 1.
    void filterColumns(int channel, const detail::RowRing& rows, const int* window_slots, bool pair,
                       const detail::Kernel& window) {
        for (int which = 0; which < 2; ++which) {
            const auto taps =
                rows.taps(static_cast<const T*>(ring(channel, which)), ring_stride_, window_slots, radius_);
            if (pair) {
                detail::filterEvenRows2(taps, 0, width_, window, filtered(0, which), filtered(1, which));
            } else {
                detail::filterEven(taps, 0, width_, window, filtered(0, which));
            }
        }
    }

  private:
    int width_, radius_;
    std::size_t padded_width_, ring_stride_, ring_size_, row_stride_;
    std::vector<T> storage_;
};

}  // namespace

SsimResult computeSsim(const Image& reference, const Image& test, const SsimConfig& config) {
    SsimResult result;
    result.error = detail::checkPair(reference, test, config.mask);
    if (!result.error.empty()) return result;
    if (!(config.sigma > 0.0) || !(config.data_range > 0.0)) {
        result.error = "SSIM sigma and data_range must be positive";
        return result;
    }

    const int width = reference.width;
    const int height = reference.height;
    const detail::Kernel window = gaussianWindow(config.sigma);
    const int radius = window.radius;
    if (width < 2 * radius + 1 || height < 2 * radius + 1) {
        result.error = "SSIM needs images of at least " + std::to_string(2 * radius + 1) + "x" +
                       std::to_string(2 * radius + 1) + " pixels; these are " + std::to_string(width) + "x" +
                       std::to_string(height);
        return result;
    }

    // The mean leaves out `radius` pixels on each side (skimage's crop): there the window
    // reaches past the image and the statistics depend on the border rule.
    std::size_t counted = 0;
    if (config.mask == nullptr) {
        counted = static_cast<std::size_t>(width - 2 * radius) * (height - 2 * radius);
    } else {
        for (int y = radius; y < height - radius; ++y) {
            for (int x = radius; x < width - radius; ++x) {
                counted += config.mask->values[static_cast<std::size_t>(y) * width + x] != 0;
            }
        }
    }
    if (counted == 0) {
        result.error = "the mask selects no pixels inside the SSIM border; SSIM is undefined";
        return result;
    }

    const int channel_count = (reference.channels == 1 && test.channels == 1) ? 1 : 3;
    if (detail::identicalPixels(reference, test)) {
        // Equal windows: both SSIM factors are exactly 1 (Wang et al. 2004, eq. 13).
        result.ok = true;
        result.channel_count = channel_count;
        for (int channel = 0; channel < channel_count; ++channel) result.channel_ssim[channel] = 1.0;
        result.pixel_count = counted;
        result.ssim = 1.0;
        if (config.want_map) result.map.assign(static_cast<std::size_t>(width) * height, 1.0f);
        return result;
    }
    const double c1 = (config.k1 * config.data_range) * (config.k1 * config.data_range);
    const double c2 = (config.k2 * config.data_range) * (config.k2 * config.data_range);
    const detail::KernelTable& kernels = detail::kernels();
    const detail::RowRing ring(height, radius, detail::Border::Reflect);
    const detail::ColumnOffsets columns(radius);
    MomentPair<double> sums(width, radius, ring);         // s = x + y and s^2
    MomentPair<double> differences(width, radius, ring);  // d = x - y and d^2
    // Rows whose differences d are all small get the moments of d in float, both passes (eight
    // lanes instead of four): a float variance E[d^2] - E[d]^2 is off by about 1e-6 of the
    // largest d^2 in the window, so with |d| <= 1/16 by at most ~4e-9, which moves SSIM by at
    // most ~4e-9 / C2 = 5e-6 (measured 1.2e-6 per pixel for a flat offset of 0.0624, against
    // 1.3e-7 all in double: tests/ssim_test.cpp). Where a window holds a row with a larger
    // difference, its vertical pass runs in double, the small rows widened (exactly) into the
    // double ring first. Rendered images mostly agree with their references to within a few
    // levels, so most windows take the float passes.
    constexpr float kSmallDifference = 1.0f / 16.0f;
    MomentPair<float> small_differences(width, radius, ring);
    enum SlotState : std::uint8_t { kDouble, kFloat, kFloatAndDouble };
    std::vector<std::uint8_t> slot_state(static_cast<std::size_t>(3 * ring.slots()), kDouble);
    const std::size_t row_stride = detail::paddedRowLength(width);
    std::vector<float> rows(7 * row_stride, 0.0f);
    float* reference_channels[3] = {&rows[0], &rows[row_stride], &rows[2 * row_stride]};
    float* test_channels[3] = {&rows[3 * row_stride], &rows[4 * row_stride], &rows[5 * row_stride]};
    float* ssim_row = &rows[6 * row_stride];
    std::vector<int> window_slots(2 * radius + 2);
    if (config.want_map) result.map.assign(static_cast<std::size_t>(width) * height, 0.0f);

    // Horizontal pass of image row y, every channel, into the rings.
    auto filter_row = [&](int y) {
        const int slot = y % ring.slots();
        kernels.deinterleave_rgb(&reference.pixels[static_cast<std::size_t>(y) * width * reference.channels],
                                 reference.channels, width, reference_channels[0], reference_channels[1],
                                 reference_channels[2]);
        kernels.deinterleave_rgb(&test.pixels[static_cast<std::size_t>(y) * width * test.channels],
                                 test.channels, width, test_channels[0], test_channels[1], test_channels[2]);
        for (int channel = 0; channel < channel_count; ++channel) {
            const float* x = reference_channels[channel];
            const float* y_values = test_channels[channel];
            kernels.ssim_inputs_row(x, y_values, width, false, sums.input(channel, 0) + radius,
                                    sums.input(channel, 1) + radius);
            sums.filterRow(channel, slot, window, columns);
            std::uint8_t& state = slot_state[static_cast<std::size_t>(channel * ring.slots() + slot)];
            if (kernels.ssim_small_differences_row(x, y_values, width, kSmallDifference,
                                                   small_differences.input(channel, 0) + radius,
                                                   small_differences.input(channel, 1) + radius)) {
                small_differences.filterRow(channel, slot, window, columns);
                state = kFloat;
            } else {
                kernels.ssim_inputs_row(x, y_values, width, true, differences.input(channel, 0) + radius,
                                        differences.input(channel, 1) + radius);
                differences.filterRow(channel, slot, window, columns);
                state = kDouble;
            }
        }
    };

    // Vertical passes of a channel for output rows y and (if `pair`) y + 1; returns whether the
    // moments of d are in small_differences (float) rather than differences (double).
    auto filter_columns = [&](int channel, bool pair) {
        sums.filterColumns(channel, ring, window_slots.data(), pair, window);
        const int rows_used = pair ? 2 * radius + 2 : 2 * radius + 1;
        std::uint8_t* states = &slot_state[static_cast<std::size_t>(channel * ring.slots())];
        bool all_small = true;
        for (int i = 0; i < rows_used; ++i) all_small = all_small && states[window_slots[i]] != kDouble;
        if (all_small) {
            small_differences.filterColumns(channel, ring, window_slots.data(), pair, window);
            return true;
        }
        for (int i = 0; i < rows_used; ++i) {
            const int slot = window_slots[i];
            if (states[slot] != kFloat) continue;
            for (int which = 0; which < 2; ++which) {
                kernels.widen_row(small_differences.ringRow(channel, which, slot), width,
                                  differences.ringRow(channel, which, slot));
            }
            states[slot] = kFloatAndDouble;
        }
        differences.filterColumns(channel, ring, window_slots.data(), pair, window);
        return false;
    };

    // The SSIM of one output row from its moments, into the map and the channel's sum.
    double channel_sums[3] = {0.0, 0.0, 0.0};
    auto finish_row = [&](int y, int channel, int pair, bool small) {
        const double* sum_moments[2] = {sums.filtered(pair, 0), sums.filtered(pair, 1)};
        if (small) {
            const float* difference_moments[2] = {small_differences.filtered(pair, 0),
                                                  small_differences.filtered(pair, 1)};
            kernels.ssim_row_small_differences(sum_moments, difference_moments, 0, width, c1, c2, ssim_row);
        } else {
            const double* difference_moments[2] = {differences.filtered(pair, 0),
                                                   differences.filtered(pair, 1)};
            kernels.ssim_row(sum_moments, difference_moments, 0, width, c1, c2, ssim_row);
        }
        const std::size_t row_start = static_cast<std::size_t>(y) * width;
        if (config.want_map) {
            float* map_row = &result.map[row_start];
            for (int i = 0; i < width; ++i) map_row[i] += ssim_row[i];
        }
        if (y >= radius && y < height - radius) {
            const std::uint8_t* mask_row = config.mask ? config.mask->values.data() + row_start : nullptr;
            float unused_max = 0.0f;
            channel_sums[channel] +=
                kernels.masked_sum_max(ssim_row, mask_row, radius, width - radius, &unused_max);
        }
    };

    // Vertical pass and the SSIM formula, two output rows at a time.
    int next_row = 0;
    for (int y = 0; y < height; y += 2) {
        for (; next_row <= ring.lastRowNeeded(y); ++next_row) filter_row(next_row);
        ring.window(y, window_slots.data());
        const bool pair = y + 1 < height;
        for (int channel = 0; channel < channel_count; ++channel) {
            const bool small = filter_columns(channel, pair);
            finish_row(y, channel, 0, small);
            if (pair) finish_row(y + 1, channel, 1, small);
        }
    }

    double channel_total = 0.0;
    for (int channel = 0; channel < channel_count; ++channel) {
        result.channel_ssim[channel] = channel_sums[channel] / static_cast<double>(counted);
        channel_total += result.channel_ssim[channel];
    }
    if (config.want_map && channel_count > 1) {
        for (float& v : result.map) v /= static_cast<float>(channel_count);
    }
    result.ok = true;
    result.channel_count = channel_count;
    result.pixel_count = counted;
    result.ssim = channel_total / channel_count;
    return result;
}

}  // namespace grader
