// LDR-FLIP (Andersson et al., HPG 2020; formula, constants and conventions in
// grader/metrics.h), written from the paper and checked against the structure of the
// authors' reference implementation (github.com/NVlabs/flip): the same separable filters, the
// same clamp-to-edge borders, the same pooling. Not here: HDR-FLIP (exposure sweeps and tone
// mapping), which LDR renders do not need.
//
// Data flow, per image, all float and planar:
//   1. each input row -> Cx, Cz and luminance Y / Y_white (sRGB decode, matrix, linearised Lab
//      axes). The Y channel of YCxCz is 116 luminance - 16, and the achromatic filter sums to
//      1, so the luminance is filtered in its place and mapped back after;
//   2. horizontal passes of the contrast sensitivity filters (the blue-yellow one is a sum of
//      two Gaussians, so two separable passes) and of the feature filters (Gaussian, first and
//      second derivative) into seven rings of rows (filter.h); the achromatic and the feature
//      filters share one pass over the luminance;
//   3. per output row: vertical passes into row buffers, then colour error, feature error and
//      the combined error for that row.
// Steps 1 and 2 run for an image row just before step 3 first needs it, so no whole plane is
// stored. The inner loops and all filter passes run in the kernel table (kernels.h).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "filter.h"
#include "flip_constants.h"
#include "grader/metrics/metrics.h"
#include "image_access.h"
#include "kernels.h"

namespace grader {
namespace {

using namespace detail::flip_constants;

// Constants of the paper (its colour and feature pipelines).
constexpr float kQc = 0.7f;    // exponent applied to the HyAB colour distance
constexpr float kPc = 0.4f;    // fraction of cmax where the colour error redistribution bends
constexpr float kPt = 0.95f;   // error value at that bend
constexpr float kGw = 0.082f;  // feature filter width, in degrees
constexpr double kPi = 3.14159265358979323846;

// Contrast sensitivity of each YCxCz channel as Gaussians a * sqrt(pi / b) * exp(-pi^2 x^2 / b),
// x in degrees (paper, colour pipeline): achromatic and red-green are one Gaussian each,
// blue-yellow a sum of two.
struct CsfGaussian {
    double a;
    double b;
};
constexpr CsfGaussian kCsfAchromatic{1.0, 0.0047};
constexpr CsfGaussian kCsfRedGreen{1.0, 0.0053};
constexpr CsfGaussian kCsfBlueYellow1{34.1, 0.04};
constexpr CsfGaussian kCsfBlueYellow2{13.5, 0.025};

// ---- scalar double versions, for the constant cmax -----------------------------------------

struct Lab {
    double l, a, b;
};

Lab linearRgbToHuntLab(double r, double g, double b) {
    double f[3];
    for (int i = 0; i < 3; ++i) {
        const double normalised =
            (kRgbToXyz[i][0] * r + kRgbToXyz[i][1] * g + kRgbToXyz[i][2] * b) * kInvWhite[i];
        f[i] = normalised > kLabDeltaCube ? std::cbrt(normalised)
                                          : normalised * kLabLinearSlope + kLabLinearOffset;
    }
    const double l = 116.0 * f[1] - 16.0;
    // Hunt effect: colourfulness falls with lightness (paper): a, b scaled by 0.01 L.
    return {l, 0.01 * l * 500.0 * (f[0] - f[1]), 0.01 * l * 200.0 * (f[1] - f[2])};
}

double hyab(const Lab& p, const Lab& q) {
    return std::abs(p.l - q.l) + std::sqrt((p.a - q.a) * (p.a - q.a) + (p.b - q.b) * (p.b - q.b));
}

// ---- filters ------------------------------------------------------------------------------

struct Filters {
    detail::Kernel achromatic, red_green, blue_yellow1, blue_yellow2;  // spatial (CSF)
    detail::Kernel gauss, first_derivative, second_derivative;         // features
    // The achromatic and the three feature kernels zero-padded to one radius, for the shared
    // horizontal pass over the luminance.
    detail::Kernel luminance_achromatic, luminance_gauss, luminance_first, luminance_second;
    int pad_radius = 0;  // the largest radius: one padded row serves every kernel
};

// Spatial radius from the widest Gaussian: 3 standard deviations, b = 2 pi^2 sigma^2 (in float,
// as the reference computes it, so that the radius agrees at every ppd).
int spatialRadius(float ppd) {
    const float b_max = static_cast<float>(
        std::max({kCsfAchromatic.b, kCsfRedGreen.b, kCsfBlueYellow1.b, kCsfBlueYellow2.b}));
    const float pi_squared = static_cast<float>(kPi * kPi);
    return static_cast<int>(std::ceil(3.0f * std::sqrt(b_max / (2.0f * pi_squared)) * ppd));
}

detail::Kernel makeKernel(const std::vector<double>& taps, double scale) {
    detail::Kernel kernel;
    kernel.radius = static_cast<int>(taps.size() / 2);
    for (double t : taps) kernel.taps.push_back(static_cast<float>(t * scale));
    return kernel;
}

// Drops outer taps below 1e-8 (of a kernel summing to 1). The achromatic and red-green
// Gaussians are ~1 pixel wide but get the blue-yellow radius (10 at 67 ppd): taps 7 to 10 are
// below 1e-9 and move a filtered value by less than its float rounding, yet would cost a third
// of the time those two filters take. At 67 ppd both keep radius 6.
void trimNegligibleTaps(detail::Kernel& kernel) {
    int drop = 0;
    while (drop < kernel.radius && std::abs(kernel.taps[drop]) < 1e-8f) ++drop;
    kernel.taps.erase(kernel.taps.end() - drop, kernel.taps.end());
    kernel.taps.erase(kernel.taps.begin(), kernel.taps.begin() + drop);
    kernel.radius -= drop;
}

// The kernel with zero taps added on both sides up to `radius` (not below its own).
detail::Kernel zeroPadded(const detail::Kernel& kernel, int radius) {
    detail::Kernel padded;
    padded.radius = std::max(radius, kernel.radius);
    const int extra = padded.radius - kernel.radius;
    padded.taps.assign(static_cast<std::size_t>(extra), 0.0f);
    padded.taps.insert(padded.taps.end(), kernel.taps.begin(), kernel.taps.end());
    padded.taps.insert(padded.taps.end(), static_cast<std::size_t>(extra), 0.0f);
    return padded;
}

Filters makeFilters(float ppd) {
    Filters f;
    const int radius = spatialRadius(ppd);
    const int taps = 2 * radius + 1;
    std::vector<double> achromatic(taps), red_green(taps), blue_yellow1(taps), blue_yellow2(taps);
    double sum_a = 0.0, sum_rg = 0.0, sum_by1 = 0.0, sum_by2 = 0.0;
    auto gaussian = [](double x2, const CsfGaussian& g) {
        return g.a * std::sqrt(kPi / g.b) * std::exp(-kPi * kPi * x2 / g.b);
    };
    // The blue-yellow filter g1(x)g1(y) + g2(x)g2(y) is a sum of two separable filters; each
    // 1D factor carries the square root of its 2D amplitude.
    auto root_gaussian = [](double x2, const CsfGaussian& g) {
        return std::sqrt(g.a * std::sqrt(kPi / g.b)) * std::exp(-kPi * kPi * x2 / g.b);
    };
    for (int i = 0; i < taps; ++i) {
        const double x = (i - radius) / static_cast<double>(ppd);  // degrees
        const double x2 = x * x;
        achromatic[i] = gaussian(x2, kCsfAchromatic);
        red_green[i] = gaussian(x2, kCsfRedGreen);
        blue_yellow1[i] = root_gaussian(x2, kCsfBlueYellow1);
        blue_yellow2[i] = root_gaussian(x2, kCsfBlueYellow2);
        sum_a += achromatic[i];
        sum_rg += red_green[i];
        sum_by1 += blue_yellow1[i];
        sum_by2 += blue_yellow2[i];
    }
    // Each 2D filter sums to 1; for the blue-yellow pair the 2D sum is S1^2 + S2^2.
    const double blue_yellow_scale = 1.0 / std::sqrt(sum_by1 * sum_by1 + sum_by2 * sum_by2);
    f.achromatic = makeKernel(achromatic, 1.0 / sum_a);
    f.red_green = makeKernel(red_green, 1.0 / sum_rg);
    f.blue_yellow1 = makeKernel(blue_yellow1, blue_yellow_scale);
    f.blue_yellow2 = makeKernel(blue_yellow2, blue_yellow_scale);
    trimNegligibleTaps(f.achromatic);
    trimNegligibleTaps(f.red_green);

    // Feature filters (paper, feature pipeline): Gaussian derivatives with sigma = 0.5 * w * ppd
    // pixels, radius ceil(3 sigma). The Gaussian sums to 1; the positive and the negative
    // weights of each derivative sum to +1 and -1.
    const float sigma = 0.5f * kGw * ppd;
    const int feature_radius = static_cast<int>(std::ceil(3.0f * sigma));
    const int feature_taps = 2 * feature_radius + 1;
    std::vector<double> g(feature_taps), dg(feature_taps), ddg(feature_taps);
    double g_sum = 0.0, dg_positive = 0.0, ddg_positive = 0.0, ddg_negative = 0.0;
    for (int i = 0; i < feature_taps; ++i) {
        const double x = i - feature_radius;
        const double s2 = static_cast<double>(sigma) * sigma;
        g[i] = std::exp(-(x * x) / (2.0 * s2));
        dg[i] = -x * g[i];
        ddg[i] = (x * x / s2 - 1.0) * g[i];
        g_sum += g[i];
        if (dg[i] > 0.0) dg_positive += dg[i];
        (ddg[i] > 0.0 ? ddg_positive : ddg_negative) += std::abs(ddg[i]);
    }
    // The first derivative is odd: its negative weights mirror the positive ones, one scale
    // serves both. The second derivative's two signs are scaled separately.
    for (int i = 0; i < feature_taps; ++i) ddg[i] /= ddg[i] > 0.0 ? ddg_positive : ddg_negative;
    f.gauss = makeKernel(g, 1.0 / g_sum);
    f.first_derivative = makeKernel(dg, 1.0 / dg_positive);
    f.second_derivative = makeKernel(ddg, 1.0);
    f.pad_radius = std::max(radius, feature_radius);
    const int shared = std::max(f.achromatic.radius, feature_radius);
    f.luminance_achromatic = zeroPadded(f.achromatic, shared);
    f.luminance_gauss = zeroPadded(f.gauss, shared);
    f.luminance_first = zeroPadded(f.first_derivative, shared);
    f.luminance_second = zeroPadded(f.second_derivative, shared);
    return f;
}

// ---- pooling -----------------------------------------------------------------------------

// The FLIP tool's weighted percentile: with the errors sorted ascending, the first e_i whose
// running sum exceeds p * (sum of all errors); 0 when the sum is 0. Sorting a quarter million
// floats would take longer than FLIP itself, so the errors (all in [0, 1]) are binned as they
// are computed, the running sum is located at bin level, and only the bins holding the
// answers are collected and sorted.
class ErrorPool {
  public:
    // Adds the errors of one row whose mask is non-zero (all of them if mask is nullptr). Four
    // interleaved copies of the bins: neighbouring pixels tend to fall in the same bin, and
    // adding into one memory cell back to back would serialise on it.
    void addRow(const float* errors, const std::uint8_t* mask, int width) {
        count_ += static_cast<std::size_t>(
            detail::kernels().add_to_bins(errors, mask, width, kBins, partial_.data()));
    }
    std::size_t count() const { return count_; }

    // Percentiles at `fractions`. `collect(low, high, out)` must append to `out` every added
    // error e with low <= e < high.
    template <typename Collect>
    void weightedPercentiles(const double* fractions, int n, double* out, Collect collect) const {
        std::vector<double> bin_sum(kBins);
        double total = 0.0;
        for (int b = 0; b < kBins; ++b) {
            bin_sum[b] =
                partial_[b] + partial_[kBins + b] + partial_[2 * kBins + b] + partial_[3 * kBins + b];
            total += bin_sum[b];
        }
        std::vector<float> values;
        for (int p = 0; p < n; ++p) {
            out[p] = 0.0;
            if (!(total > 0.0)) continue;
            // The fraction's bin and the running sum before it...
            const double target = fractions[p] * total;
            double running = 0.0;
            int bin = 0;
            while (bin < kBins - 1 && running + bin_sum[bin] <= target) running += bin_sum[bin++];
            // ...then a walk through that bin's sorted values. Bin b holds [b, b + 1) / kBins
            // (the last one everything above), exactly as add_to_bins assigns them.
            values.clear();
            collect(static_cast<float>(bin) / kBins,
                    bin == kBins - 1 ? std::numeric_limits<float>::infinity()
                                     : static_cast<float>(bin + 1) / kBins,
                    values);
            std::sort(values.begin(), values.end());
            out[p] = values.empty() ? 0.0 : values.back();
            for (float e : values) {
                running += e;
                if (running > target) {
                    out[p] = e;
                    break;
                }
            }
        }
    }

  private:
    static constexpr int kBins = 4096;
    std::vector<double> partial_ = std::vector<double>(4 * kBins, 0.0);
    std::size_t count_ = 0;
};

// Steps 1 to 3 of FLIP over one image pair that computeFlip has checked, streamed by rows: each
// image row is converted and filtered horizontally into rings as the vertical passes need it,
// and the per-pixel error of each pair of output rows is formed at once, into the error map (or
// a copy of the counted errors) and the pooled statistics.
class FlipPasses {
  public:
    FlipPasses(const Image& reference, const Image& test, const FlipConfig& config, FlipResult& result)
        : kernels_(detail::kernels()),
          config_(config),
          result_(result),
          width_(reference.width),
          height_(reference.height),
          plane_size_(static_cast<std::size_t>(width_) * height_),
          filters_(makeFilters(config.pixels_per_degree)),
          pad_(filters_.pad_radius),
          colour_constants_(colourConstants()),
          ring_(height_, pad_, detail::Border::ClampToEdge),
          ring_stride_(detail::ringStride(width_)),
          ring_size_(ring_stride_ * ring_.slots()),
          row_stride_(detail::paddedRowLength(width_)),
          padded_stride_(detail::paddedRowLength(width_ + 2 * pad_)),
          columns_(pad_),
          window_slots_(2 * pad_ + 2),
          images_{&reference, &test} {
        allocate();
        // Statistics as the rows come. The percentiles need a second look at the errors: the
        // error map when there is one, otherwise a copy of the counted errors.
        if (config.want_map) result.error_map.resize(plane_size_);
        if (!config.want_map) kept_errors_.reserve(plane_size_);
    }

    // Step 3: vertical passes and the per-pixel error, two output rows at a time.
    void run() {
        int next_row = 0;
        for (int y = 0; y < height_; y += 2) {
            for (; next_row <= ring_.lastRowNeeded(y); ++next_row) filterRow(next_row);
            ring_.window(y, window_slots_.data());
            const bool pair = y + 1 < height_;
            for (int which = 0; which < 2; ++which) filterColumns(which, pair);
            finishRow(y, outputs_[0][0], outputs_[0][1]);
            if (pair) finishRow(y + 1, outputs_[1][0], outputs_[1][1]);
        }
    }

    const ErrorPool& pool() const { return pool_; }
    const std::vector<float>& keptErrors() const { return kept_errors_; }
    double errorSum() const { return error_sum_; }
    float maxError() const { return max_error_; }

  private:
    enum Plane { kY, kCx, kBy1, kBy2, kGauss, kFirst, kSecond, kPlaneCount };
    enum Channel { kChannelCx, kChannelCz, kChannelLuminance, kChannelCount };
    enum Output { kOutY, kOutCx, kOutBy1, kOutBy2, kOutDx, kOutDdx, kOutDy, kOutDdy, kOutputCount };

    // Largest possible colour distance (green against blue), and where redistribution bends.
    static detail::FlipColourConstants colourConstants() {
        const float cmax =
            static_cast<float>(std::pow(hyab(linearRgbToHuntLab(0, 1, 0), linearRgbToHuntLab(0, 0, 1)), kQc));
        const float pccmax = kPc * cmax;
        return detail::FlipColourConstants{pccmax, kPt / pccmax, (1.0f - kPt) / (cmax - pccmax), kPt};
    }

    // Buffers, in one allocation: per image seven rings of horizontally filtered rows
    // (filter.h; kY holds the filtered luminance, not Y), the padded rows of the three channels being
    // filtered, the deinterleaved sRGB row, per image eight vertically filtered rows, and the error row. Rows
    // are padded to whole vector groups (kernels.h) and everything is zeroed, so the groups past the end of
    // a row compute harmless values.
    void allocate() {
        const std::size_t total = 2 * kPlaneCount * ring_size_ + kChannelCount * padded_stride_ +
                                  (3 + 2 * 2 * kOutputCount + 1) * row_stride_;
        storage_.reset(new float[total]);
        std::fill(storage_.get(), storage_.get() + total, 0.0f);
        float* cursor = storage_.get();
        auto take = [&cursor](std::size_t n) {
            float* p = cursor;
            cursor += n;
            return p;
        };
        for (auto& image_rings : rings_) {
            for (float*& p : image_rings) p = take(ring_size_);
        }
        for (float*& p : padded_) p = take(padded_stride_);
        for (float*& p : srgb_row_) p = take(row_stride_);
        for (auto& row_outputs : outputs_) {
            for (auto& image_outputs : row_outputs) {
                for (float*& p : image_outputs) p = take(row_stride_);
            }
        }
        error_row_ = take(row_stride_);
    }

    // Steps 1 and 2 for image row y of both images: colour conversion, horizontal filtering.
    void filterRow(int y) {
        const std::size_t slot = static_cast<std::size_t>(y % ring_.slots()) * ring_stride_;
        for (int which = 0; which < 2; ++which) {
            const Image& image = *images_[which];
            const int channels = image.channels;
            const float* row = &image.pixels[static_cast<std::size_t>(y) * width_ * channels];
            kernels_.deinterleave_rgb(row, channels, width_, srgb_row_[0], srgb_row_[1], srgb_row_[2]);
            kernels_.flip_colour_row(srgb_row_, width_, padded_[kChannelCx] + pad_,
                                     padded_[kChannelCz] + pad_, padded_[kChannelLuminance] + pad_);
            for (float* p : padded_) detail::fillBorders(p, width_, pad_, detail::Border::ClampToEdge);

            float* const* out = rings_[which];
            auto taps = [&](Channel channel, const detail::Kernel& kernel) {
                return detail::horizontalTaps(padded_[channel], pad_, kernel.radius, columns_);
            };
            detail::filterEven(taps(kChannelCx, filters_.red_green), 0, width_, filters_.red_green,
                               out[kCx] + slot);
            detail::filterEvenEven(taps(kChannelCz, filters_.blue_yellow1), 0, width_, filters_.blue_yellow1,
                                   filters_.blue_yellow2, out[kBy1] + slot, out[kBy2] + slot);
            detail::filterEvenEvenOddEven(taps(kChannelLuminance, filters_.luminance_gauss), 0, width_,
                                          filters_.luminance_achromatic, filters_.luminance_gauss,
                                          filters_.luminance_first, filters_.luminance_second, out[kY] + slot,
                                          out[kGauss] + slot, out[kFirst] + slot, out[kSecond] + slot);
        }
    }

    // The vertical passes of one image for output rows y and (if `pair`) y + 1.
    void filterColumns(int which, bool pair) {
        float* const* in = rings_[which];
        float* const* out0 = outputs_[0][which];
        float* const* out1 = outputs_[1][which];
        auto taps = [&](Plane plane, const detail::Kernel& kernel) {
            return ring_.taps(in[plane], ring_stride_, window_slots_.data(), kernel.radius);
        };
        // One Gaussian pass per plane, except on the luminance's horizontal Gaussian, which
        // gets the first and second derivative (d/dy, d^2/dy^2); d/dx comes from the
        // horizontal derivative planes with a Gaussian down the columns.
        const struct {
            Plane plane;
            const detail::Kernel* kernel;
            Output output;
        } singles[] = {{kY, &filters_.achromatic, kOutY},       {kCx, &filters_.red_green, kOutCx},
                       {kBy1, &filters_.blue_yellow1, kOutBy1}, {kBy2, &filters_.blue_yellow2, kOutBy2},
                       {kFirst, &filters_.gauss, kOutDx},       {kSecond, &filters_.gauss, kOutDdx}};
        for (const auto& pass : singles) {
            if (pair) {
                detail::filterEvenRows2(taps(pass.plane, *pass.kernel), 0, width_, *pass.kernel,
                                        out0[pass.output], out1[pass.output]);
            } else {
                detail::filterEven(taps(pass.plane, *pass.kernel), 0, width_, *pass.kernel,
                                   out0[pass.output]);
            }
        }
        if (pair) {
            detail::filterOddEvenRows2(taps(kGauss, filters_.first_derivative), 0, width_,
                                       filters_.first_derivative, filters_.second_derivative, out0[kOutDy],
                                       out0[kOutDdy], out1[kOutDy], out1[kOutDdy]);
        } else {
            detail::filterOddEven(taps(kGauss, filters_.first_derivative), 0, width_,
                                  filters_.first_derivative, filters_.second_derivative, out0[kOutDy],
                                  out0[kOutDdy]);
        }
    }

    // The error of output row y, into the map (or the kept errors) and the statistics.
    void finishRow(int y, float* const* reference_rows, float* const* test_rows) {
        kernels_.flip_error_row(reference_rows, test_rows, 0, width_, colour_constants_, error_row_);
        const std::size_t row_start = static_cast<std::size_t>(y) * width_;
        const std::uint8_t* mask_row = config_.mask ? config_.mask->values.data() + row_start : nullptr;
        if (config_.want_map) {
            std::copy(error_row_, error_row_ + width_, result_.error_map.begin() + row_start);
        } else if (mask_row == nullptr) {
            kept_errors_.insert(kept_errors_.end(), error_row_, error_row_ + width_);
        } else {
            for (int i = 0; i < width_; ++i) {
                if (mask_row[i]) kept_errors_.push_back(error_row_[i]);
            }
        }
        pool_.addRow(error_row_, mask_row, width_);
        error_sum_ += kernels_.masked_sum_max(error_row_, mask_row, 0, width_, &max_error_);
    }

    const detail::KernelTable& kernels_;
    const FlipConfig& config_;
    FlipResult& result_;
    const int width_, height_;
    const std::size_t plane_size_;
    const Filters filters_;
    const int pad_;
    const detail::FlipColourConstants colour_constants_;
    const detail::RowRing ring_;
    const std::size_t ring_stride_, ring_size_, row_stride_, padded_stride_;
    const detail::ColumnOffsets columns_;
    std::vector<int> window_slots_;
    const Image* images_[2];
    std::unique_ptr<float[]> storage_;
    float* rings_[2][kPlaneCount];
    float* padded_[kChannelCount];
    float* srgb_row_[3];
    float* outputs_[2][2][kOutputCount];  // [output row y or y + 1][image][output]
    float* error_row_ = nullptr;
    ErrorPool pool_;
    std::vector<float> kept_errors_;
    double error_sum_ = 0.0;
    float max_error_ = 0.0f;
};

// The result for two images with identical pixels: every filtered difference is 0, so is every
// pixel's error.
FlipResult identicalImagesResult(const Image& reference, const FlipConfig& config) {
    FlipResult result;
    const std::size_t pixels = static_cast<std::size_t>(reference.width) * reference.height;
    std::size_t counted = pixels;
    if (config.mask) {
        counted = 0;
        for (std::size_t i = 0; i < pixels; ++i) counted += config.mask->values[i] != 0;
    }
    if (counted == 0) {
        result.error = "the mask selects no pixels; FLIP statistics are undefined";
        return result;
    }
    if (config.want_map) result.error_map.assign(pixels, 0.0f);
    result.ok = true;
    result.width = reference.width;
    result.height = reference.height;
    result.pixel_count = counted;
    return result;
}

}  // namespace

double flipPixelsPerDegree(double distance_m, double resolution_x, double monitor_width_m) {
    return distance_m * (resolution_x / monitor_width_m) * (kPi / 180.0);
}

FlipResult computeFlip(const Image& reference, const Image& test, const FlipConfig& config) {
    FlipResult result;
    result.error = detail::checkPair(reference, test, config.mask);
    if (!result.error.empty()) return result;
    if (!(config.pixels_per_degree > 0.0f) || !std::isfinite(config.pixels_per_degree)) {
        result.error = "FLIP pixels_per_degree must be a positive number";
        return result;
    }
    if (detail::identicalPixels(reference, test)) return identicalImagesResult(reference, config);

    const int width = reference.width;
    const int height = reference.height;
    const std::size_t plane_size = static_cast<std::size_t>(width) * height;
    FlipPasses passes(reference, test, config, result);
    passes.run();
    const ErrorPool& pool = passes.pool();
    if (pool.count() == 0) {
        result.error = "the mask selects no pixels; FLIP statistics are undefined";
        return result;
    }

    // Step 4, pooling: the mean, the maximum and the weighted quartiles.
    const detail::KernelTable& kernels = detail::kernels();
    const std::vector<float>& kept_errors = passes.keptErrors();
    const double fractions[3] = {0.25, 0.5, 0.75};
    double percentiles[3];
    std::vector<float> scratch(static_cast<std::size_t>(std::max(width, 1)));
    pool.weightedPercentiles(fractions, 3, percentiles, [&](float low, float high, std::vector<float>& out) {
        auto take_rows = [&](const float* values, const std::uint8_t* mask, std::size_t count) {
            for (std::size_t start = 0; start < count; start += width) {
                const int n = static_cast<int>(std::min<std::size_t>(width, count - start));
                const int found = kernels.collect_range(values + start, mask ? mask + start : nullptr, 0, n,
                                                        low, high, scratch.data());
                out.insert(out.end(), scratch.begin(), scratch.begin() + found);
            }
        };
        if (config.want_map) {
            take_rows(result.error_map.data(), config.mask ? config.mask->values.data() : nullptr,
                      plane_size);
        } else {
            take_rows(kept_errors.data(), nullptr, kept_errors.size());
        }
    });

    result.ok = true;
    result.width = width;
    result.height = height;
    result.pixel_count = pool.count();
    result.mean = passes.errorSum() / static_cast<double>(pool.count());
    result.weighted_p25 = percentiles[0];
    result.weighted_median = percentiles[1];
    result.weighted_p75 = percentiles[2];
    result.max_error = passes.maxError();
    return result;
}

}  // namespace grader
