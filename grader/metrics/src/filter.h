// Internal: separable filtering of planar float (or double) images with mirror-symmetric
// kernels, the building block of SSIM's Gaussian window and of FLIP's spatial and feature
// filters. No allocation happens per pass; callers own every buffer.
//
// A pass computes, for each output x in [begin, end), the sum over k in [-r, r] of
// w[k] * input at offset k: along a row for a horizontal pass (the row copied into a buffer
// with r border samples on each side), down a column for a vertical pass (rows kept in a
// RowRing). Every kernel used here is even (w[-k] = w[k]: Gaussians, second derivatives) or
// odd (w[-k] = -w[k]: first derivatives), so a pass adds or subtracts the two mirrored samples
// first and multiplies once per pair, and kernels run together share the loads and the sums.
// The arithmetic runs in the kernel table (kernels.h).
#pragma once

#include <cstddef>
#include <vector>

#include "kernels.h"

namespace grader::detail {

// How samples outside [0, n) are made up.
enum class Border {
    ClampToEdge,  // ... a a | a b c d | d d ...  (FLIP reference implementation)
    Reflect,      // ... b a | a b c d | d c ...  (scipy.ndimage mode 'reflect', used by SSIM)
};

// Index in [0, n) that stands in for sample i.
int borderIndex(int i, int n, Border border);

// An odd-length kernel: taps[radius + k] weighs the sample at offset k, k in [-radius, radius];
// taps_f64 holds the same weights in double where a double pass needs them (else empty).
// Whether it is even or odd is up to its maker; the passes below say which they expect.
struct Kernel {
    int radius = 0;
    std::vector<float> taps;
    std::vector<double> taps_f64;
};

// `padded` holds width + 2 * radius values with the row's samples already in
// padded[radius .. radius + width); fills the `radius` border samples on each side.
template <typename T>
void fillBorders(T* padded, int width, int radius, Border border) {
    T* row = padded + radius;
    for (int k = 0; k < radius; ++k) {
        padded[k] = row[borderIndex(k - radius, width, border)];
        row[width + k] = row[borderIndex(width + k, width, border)];
    }
}

// Offsets 0, 1, 2, ... for horizontal passes over a padded row.
class ColumnOffsets {
  public:
    explicit ColumnOffsets(int max_radius);
    const int* data() const { return offsets_.data(); }

  private:
    std::vector<int> offsets_;
};

// Taps of a horizontal pass of radius r over a row padded with pad_radius >= r samples.
template <typename T>
BasicFilterTaps<T> horizontalTaps(const T* padded, int pad_radius, int r, const ColumnOffsets& offsets) {
    return {padded + (pad_radius - r), offsets.data(), 1};
}

// Vertical passes read horizontally filtered rows from a ring of 2 * max_radius + 2 row
// buffers rather than from whole planes: image row i lives in slot i % slots, and is filtered
// just before the first output row that needs it. The working set then stays in the L2 cache
// (the whole planes of a 512x512 FLIP would take 14 MB, its rings take 0.7 MB). Output rows
// are produced in pairs (y, y + 1; the kernels' *_rows2 passes), hence the one extra slot. Valid when every
// row of a pair's window, after the border rule, lies within [y - max_radius, y + 1 + max_radius]: always for
// ClampToEdge, and for Reflect when the image has at least max_radius + 1 rows.
class RowRing {
  public:
    RowRing(int height, int max_radius, Border border);
    int slots() const { return slots_; }
    // Rows up to this one must have been filtered before output rows y and y + 1 are computed.
    int lastRowNeeded(int y) const {
        return y + 1 + max_radius_ < height_ ? y + 1 + max_radius_ : height_ - 1;
    }
    // Points `offsets` (2 * max_radius + 2 entries) at the slots of rows y - max_radius ..
    // y + 1 + max_radius.
    void window(int y, int* offsets) const;
    // Taps of a vertical pass of radius r <= max_radius over the ring, using the window filled
    // by window(): slot rows lie `stride` values apart from `base`. Serves single-row passes
    // for output row y and two-row passes for rows y and y + 1.
    template <typename T>
    BasicFilterTaps<T> taps(const T* base, std::size_t stride, const int* offsets, int r) const {
        return {base, offsets + (max_radius_ - r), static_cast<std::ptrdiff_t>(stride)};
    }

  private:
    int height_;
    int max_radius_;
    int slots_;
    Border border_;
};

// Row stride (in values) for buffers that vertical passes read: whole vector groups plus 16
// values, so that rows a power of two apart do not all fall into the same few L1 cache sets.
std::size_t ringStride(int width);

// One even kernel, or several kernels of one radius (the first kernel's) over the same taps;
// the parity each expects is in its name. Outputs out[x] for x in [begin, end).
void filterEven(const FilterTaps& taps, int begin, int end, const Kernel& kernel, float* out);
void filterEven(const FilterTapsF64& taps, int begin, int end, const Kernel& kernel, double* out);
void filterEvenEven(const FilterTaps& taps, int begin, int end, const Kernel& first, const Kernel& second,
                    float* out_first, float* out_second);
void filterOddEven(const FilterTaps& taps, int begin, int end, const Kernel& odd, const Kernel& even,
                   float* out_odd, float* out_even);
void filterEvenOddEven(const FilterTaps& taps, int begin, int end, const Kernel& first, const Kernel& odd,
                       const Kernel& third, float* out_first, float* out_odd, float* out_third);
void filterEvenEvenOddEven(const FilterTaps& taps, int begin, int end, const Kernel& first,
                           const Kernel& second, const Kernel& odd, const Kernel& fourth, float* out_first,
                           float* out_second, float* out_odd, float* out_fourth);

// Vertical passes for output rows y and y + 1 at once (taps from RowRing::taps).
void filterEvenRows2(const FilterTaps& taps, int begin, int end, const Kernel& kernel, float* out0,
                     float* out1);
void filterEvenRows2(const FilterTapsF64& taps, int begin, int end, const Kernel& kernel, double* out0,
                     double* out1);
void filterOddEvenRows2(const FilterTaps& taps, int begin, int end, const Kernel& odd, const Kernel& even,
                        float* out0_odd, float* out0_even, float* out1_odd, float* out1_even);

}  // namespace grader::detail
