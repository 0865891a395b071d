// Border handling and the separable filter passes of filter.h; the passes themselves run in
// the kernel table (kernels.h), which picks the widest vector unit the CPU has.
#include "filter.h"

namespace grader::detail {
namespace {

// Weights at offsets 0 .. radius.
inline const float* positiveHalf(const Kernel& kernel) { return kernel.taps.data() + kernel.radius; }

}  // namespace

int borderIndex(int i, int n, Border border) {
    if (border == Border::ClampToEdge) {
        return i < 0 ? 0 : (i >= n ? n - 1 : i);
    }
    // Reflect about the pixel edges, repeating as often as needed for tiny n: the signal
    // continues as its mirror image, period 2n.
    const int period = 2 * n;
    int j = i % period;
    if (j < 0) j += period;
    return j < n ? j : period - 1 - j;
}

ColumnOffsets::ColumnOffsets(int max_radius) : offsets_(static_cast<std::size_t>(2 * max_radius + 1)) {
    for (int j = 0; j <= 2 * max_radius; ++j) offsets_[static_cast<std::size_t>(j)] = j;
}

RowRing::RowRing(int height, int max_radius, Border border)
    : height_(height), max_radius_(max_radius), slots_(2 * max_radius + 2), border_(border) {}

void RowRing::window(int y, int* offsets) const {
    for (int j = 0; j <= 2 * max_radius_ + 1; ++j) {
        offsets[j] = borderIndex(y + j - max_radius_, height_, border_) % slots_;
    }
}

std::size_t ringStride(int width) { return static_cast<std::size_t>(paddedRowLength(width)) + 16; }

void filterEven(const FilterTaps& taps, int begin, int end, const Kernel& kernel, float* out) {
    kernels().filter_even(taps, kernel.radius, begin, end, positiveHalf(kernel), out);
}

void filterEven(const FilterTapsF64& taps, int begin, int end, const Kernel& kernel, double* out) {
    kernels().filter_even_f64(taps, kernel.radius, begin, end, kernel.taps_f64.data() + kernel.radius, out);
}

void filterEvenEven(const FilterTaps& taps, int begin, int end, const Kernel& first, const Kernel& second,
                    float* out_first, float* out_second) {
    kernels().filter_even_even(taps, first.radius, begin, end, positiveHalf(first), positiveHalf(second),
                               out_first, out_second);
}

void filterOddEven(const FilterTaps& taps, int begin, int end, const Kernel& odd, const Kernel& even,
                   float* out_odd, float* out_even) {
    kernels().filter_odd_even(taps, odd.radius, begin, end, positiveHalf(odd), positiveHalf(even), out_odd,
                              out_even);
}

void filterEvenOddEven(const FilterTaps& taps, int begin, int end, const Kernel& first, const Kernel& odd,
                       const Kernel& third, float* out_first, float* out_odd, float* out_third) {
    kernels().filter_even_odd_even(taps, first.radius, begin, end, positiveHalf(first), positiveHalf(odd),
                                   positiveHalf(third), out_first, out_odd, out_third);
}

void filterEvenEvenOddEven(const FilterTaps& taps, int begin, int end, const Kernel& first,
                           const Kernel& second, const Kernel& odd, const Kernel& fourth, float* out_first,
                           float* out_second, float* out_odd, float* out_fourth) {
    kernels().filter_even_even_odd_even(taps, first.radius, begin, end, positiveHalf(first),
                                        positiveHalf(second), positiveHalf(odd), positiveHalf(fourth),
                                        out_first, out_second, out_odd, out_fourth);
}

void filterEvenRows2(const FilterTaps& taps, int begin, int end, const Kernel& kernel, float* out0,
                     float* out1) {
    kernels().filter_even_rows2(taps, kernel.radius, begin, end, positiveHalf(kernel), out0, out1);
}

void filterEvenRows2(const FilterTapsF64& taps, int begin, int end, const Kernel& kernel, double* out0,
                     double* out1) {
    kernels().filter_even_rows2_f64(taps, kernel.radius, begin, end, kernel.taps_f64.data() + kernel.radius,
                                    out0, out1);
}

void filterOddEvenRows2(const FilterTaps& taps, int begin, int end, const Kernel& odd, const Kernel& even,
                        float* out0_odd, float* out0_even, float* out1_odd, float* out1_even) {
    kernels().filter_odd_even_rows2(taps, odd.radius, begin, end, positiveHalf(odd), positiveHalf(even),
                                    out0_odd, out0_even, out1_odd, out1_even);
}

}  // namespace grader::detail
