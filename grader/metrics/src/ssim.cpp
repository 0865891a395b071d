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
// 256 times smaller for the moments of d, and those run in float (see SsimPasses).
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
    kernel.radius = ssimWindowRadius(sigma);
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

// The two passes and the SSIM formula over one image pair whose inputs computeSsim has checked:
// rows are filtered horizontally into rings as the vertical pass needs them, and the SSIM of
// each pair of output rows is formed at once, summed per channel and added into the map.
class SsimPasses {
  public:
    SsimPasses(const Image& reference, const Image& test, const SsimConfig& config,
               const detail::Kernel& window, int channel_count, SsimResult& result)
        : reference_(reference),
          test_(test),
          config_(config),
          window_(window),
          width_(reference.width),
          height_(reference.height),
          radius_(window.radius),
          channel_count_(channel_count),
          c1_((config.k1 * config.data_range) * (config.k1 * config.data_range)),
          c2_((config.k2 * config.data_range) * (config.k2 * config.data_range)),
          kernels_(detail::kernels()),
          ring_(height_, radius_, detail::Border::Reflect),
          columns_(radius_),
          sums_(width_, radius_, ring_),
          differences_(width_, radius_, ring_),
          small_differences_(width_, radius_, ring_),
          slot_state_(static_cast<std::size_t>(3 * ring_.slots()), kDouble),
          row_stride_(detail::paddedRowLength(width_)),
          rows_(7 * row_stride_, 0.0f),
          window_slots_(2 * radius_ + 2),
          result_(result) {
        for (int channel = 0; channel < 3; ++channel) {
            reference_channels_[channel] = &rows_[channel * row_stride_];
            test_channels_[channel] = &rows_[(3 + channel) * row_stride_];
        }
        ssim_row_ = &rows_[6 * row_stride_];
        if (config.want_map) result.map.assign(static_cast<std::size_t>(width_) * height_, 0.0f);
    }

    // Vertical pass and the SSIM formula, two output rows at a time; the sums of each channel's
    // SSIM over the counted pixels into `channel_sums`.
    void run(double channel_sums[3]) {
        channel_sums_ = channel_sums;
        int next_row = 0;
        for (int y = 0; y < height_; y += 2) {
            for (; next_row <= ring_.lastRowNeeded(y); ++next_row) filterRow(next_row);
            ring_.window(y, window_slots_.data());
            const bool pair = y + 1 < height_;
            for (int channel = 0; channel < channel_count_; ++channel) {
                const bool small = filterColumns(channel, pair);
                finishRow(y, channel, 0, small);
                if (pair) finishRow(y + 1, channel, 1, small);
            }
        }
    }

  private:
    // Rows whose differences d are all small get the moments of d in float, both passes (eight
    // lanes instead of four): a float variance E[d^2] - E[d]^2 is off by about 1e-6 of the
    // largest d^2 in the window, so with |d| <= 1/16 by at most ~4e-9, which moves SSIM by at
    // most ~4e-9 / C2 = 5e-6 (measured 1.2e-6 per pixel for a flat offset of 0.0624, against
    // 1.3e-7 all in double: grader/metrics/tests/ssim_test.cpp). Where a window holds a row with
    // a larger difference, its vertical pass runs in double, the small rows widened (exactly)
    // into the double ring first. Rendered images mostly agree with their references to within
    // a few levels, so most windows take the float passes.
    static constexpr float kSmallDifference = 1.0f / 16.0f;
    enum SlotState : std::uint8_t { kDouble, kFloat, kFloatAndDouble };

    // Horizontal pass of image row y, every channel, into the rings.
    void filterRow(int y) {
        const int slot = y % ring_.slots();
        kernels_.deinterleave_rgb(
            &reference_.pixels[static_cast<std::size_t>(y) * width_ * reference_.channels],
            reference_.channels, width_, reference_channels_[0], reference_channels_[1],
            reference_channels_[2]);
        kernels_.deinterleave_rgb(&test_.pixels[static_cast<std::size_t>(y) * width_ * test_.channels],
                                  test_.channels, width_, test_channels_[0], test_channels_[1],
                                  test_channels_[2]);
        for (int channel = 0; channel < channel_count_; ++channel) {
            const float* x = reference_channels_[channel];
            const float* y_values = test_channels_[channel];
            kernels_.ssim_inputs_row(x, y_values, width_, false, sums_.input(channel, 0) + radius_,
                                     sums_.input(channel, 1) + radius_);
            sums_.filterRow(channel, slot, window_, columns_);
            std::uint8_t& state = slot_state_[static_cast<std::size_t>(channel * ring_.slots() + slot)];
            if (kernels_.ssim_small_differences_row(x, y_values, width_, kSmallDifference,
                                                    small_differences_.input(channel, 0) + radius_,
                                                    small_differences_.input(channel, 1) + radius_)) {
                small_differences_.filterRow(channel, slot, window_, columns_);
                state = kFloat;
            } else {
                kernels_.ssim_inputs_row(x, y_values, width_, true, differences_.input(channel, 0) + radius_,
                                         differences_.input(channel, 1) + radius_);
                differences_.filterRow(channel, slot, window_, columns_);
                state = kDouble;
            }
        }
    }

    // Vertical passes of a channel for output rows y and (if `pair`) y + 1; returns whether the
    // moments of d are in small_differences_ (float) rather than differences_ (double).
    bool filterColumns(int channel, bool pair) {
        sums_.filterColumns(channel, ring_, window_slots_.data(), pair, window_);
        const int rows_used = pair ? 2 * radius_ + 2 : 2 * radius_ + 1;
        std::uint8_t* states = &slot_state_[static_cast<std::size_t>(channel * ring_.slots())];
        bool all_small = true;
        for (int i = 0; i < rows_used; ++i) all_small = all_small && states[window_slots_[i]] != kDouble;
        if (all_small) {
            small_differences_.filterColumns(channel, ring_, window_slots_.data(), pair, window_);
            return true;
        }
        for (int i = 0; i < rows_used; ++i) {
            const int slot = window_slots_[i];
            if (states[slot] != kFloat) continue;
            for (int which = 0; which < 2; ++which) {
                kernels_.widen_row(small_differences_.ringRow(channel, which, slot), width_,
                                   differences_.ringRow(channel, which, slot));
            }
            states[slot] = kFloatAndDouble;
        }
        differences_.filterColumns(channel, ring_, window_slots_.data(), pair, window_);
        return false;
    }

    // The SSIM of one output row from its moments, into the map and the channel's sum.
    void finishRow(int y, int channel, int pair, bool small) {
        const double* sum_moments[2] = {sums_.filtered(pair, 0), sums_.filtered(pair, 1)};
        if (small) {
            const float* difference_moments[2] = {small_differences_.filtered(pair, 0),
                                                  small_differences_.filtered(pair, 1)};
            kernels_.ssim_row_small_differences(sum_moments, difference_moments, 0, width_, c1_, c2_,
                                                ssim_row_);
        } else {
            const double* difference_moments[2] = {differences_.filtered(pair, 0),
                                                   differences_.filtered(pair, 1)};
            kernels_.ssim_row(sum_moments, difference_moments, 0, width_, c1_, c2_, ssim_row_);
        }
        const std::size_t row_start = static_cast<std::size_t>(y) * width_;
        if (config_.want_map) {
            float* map_row = &result_.map[row_start];
            for (int i = 0; i < width_; ++i) map_row[i] += ssim_row_[i];
        }
        if (y >= radius_ && y < height_ - radius_) {
            const std::uint8_t* mask_row = config_.mask ? config_.mask->values.data() + row_start : nullptr;
            float unused_max = 0.0f;
            channel_sums_[channel] +=
                kernels_.masked_sum_max(ssim_row_, mask_row, radius_, width_ - radius_, &unused_max);
        }
    }

    const Image& reference_;
    const Image& test_;
    const SsimConfig& config_;
    const detail::Kernel& window_;
    const int width_, height_, radius_, channel_count_;
    const double c1_, c2_;
    const detail::KernelTable& kernels_;
    const detail::RowRing ring_;
    const detail::ColumnOffsets columns_;
    MomentPair<double> sums_;         // s = x + y and s^2
    MomentPair<double> differences_;  // d = x - y and d^2
    MomentPair<float> small_differences_;
    std::vector<std::uint8_t> slot_state_;
    const std::size_t row_stride_;
    std::vector<float> rows_;  // the channels of a reference row and a test row, and an SSIM row
    float* reference_channels_[3];
    float* test_channels_[3];
    float* ssim_row_;
    std::vector<int> window_slots_;
    SsimResult& result_;
    double* channel_sums_ = nullptr;
};

// The pixels the mean counts: all but `radius` on each side (skimage's crop: there the window
// reaches past the image and the statistics depend on the border rule), within the mask.
std::size_t countedPixels(int width, int height, int radius, const Mask* mask) {
    if (mask == nullptr) return static_cast<std::size_t>(width - 2 * radius) * (height - 2 * radius);
    std::size_t counted = 0;
    for (int y = radius; y < height - radius; ++y) {
        for (int x = radius; x < width - radius; ++x) {
            counted += mask->values[static_cast<std::size_t>(y) * width + x] != 0;
        }
    }
    return counted;
}

}  // namespace

int ssimWindowRadius(double sigma) { return static_cast<int>(3.5 * sigma + 0.5); }

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
    const std::size_t counted = countedPixels(width, height, radius, config.mask);
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
    double channel_sums[3] = {0.0, 0.0, 0.0};
    SsimPasses(reference, test, config, window, channel_count, result).run(channel_sums);

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
