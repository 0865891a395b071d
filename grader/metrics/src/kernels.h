// Internal: the inner loops of SSIM and FLIP (separable filter passes and the per-pixel
// arithmetic), in two builds of the same source (kernels_impl.h): a portable one (four-lane
// SSE2 on x86-64, whatever the compiler gives elsewhere) and, on x86-64, an AVX2 + FMA one
// with eight lanes. kernels() picks the AVX2 build when the CPU and OS support it.
//
// Why: the three metrics together must take under 20 ms on a 512x512 pair on one core at
// -O2. The portable build takes ~31 ms; eight lanes and fused multiply-adds bring it to ~17.
// The two builds agree to float rounding (FLIP ~1e-7, SSIM ~1e-9; tests/kernels_test.cpp).
//
// Row pointers handed to the per-pixel functions (ssim_row, flip_colour_row, flip_error_row)
// must be readable, and their outputs writable, up to the row width rounded up to kMaxLanes:
// they work in whole vector groups, and the extra lanes never affect the first `width`
// results. The filter passes, deinterleave_rgb, the ssim_*_row inputs, widen_row and the reductions touch
// exactly the range they are given.
#pragma once

#include <cstddef>

namespace grader::detail {

constexpr int kMaxLanes = 8;

// Rounds n up to a whole number of kMaxLanes.
constexpr int paddedRowLength(int n) { return (n + kMaxLanes - 1) / kMaxLanes * kMaxLanes; }

// Where a filter pass reads its input (see KernelTable::filter_even).
template <typename T>
struct BasicFilterTaps {
    const T* base;
    const int* offsets;     // 2 * radius + 1 entries (2 * radius + 2 for the two-row passes)
    std::ptrdiff_t stride;  // values per offset step: 1 along a row, the row stride down a column
};
using FilterTaps = BasicFilterTaps<float>;
using FilterTapsF64 = BasicFilterTaps<double>;

// Constants of FLIP's colour error redistribution (see flip.cpp).
struct FlipColourConstants {
    float pccmax;       // pc * cmax
    float below_scale;  // pt / pccmax
    float above_scale;  // (1 - pt) / (cmax - pccmax)
    float pt;
};

struct KernelTable {
    const char* name;  // "avx2-fma" or "portable"

    // Filter passes (see filter.h), computing out[x] for x in [begin, end): tap j (offset
    // j - radius) of output x is taps.base[taps.offsets[j] * taps.stride + x]; `half[k]` is a
    // kernel's weight at offset +k, k in [0, radius]. Odd kernels weigh offset -k by -half[k].
    void (*filter_even)(const FilterTaps& taps, int radius, int begin, int end, const float* half,
                        float* out);
    void (*filter_even_even)(const FilterTaps& taps, int radius, int begin, int end, const float* half_a,
                             const float* half_b, float* out_a, float* out_b);
    void (*filter_odd_even)(const FilterTaps& taps, int radius, int begin, int end, const float* half_odd,
                            const float* half_even, float* out_odd, float* out_even);
    void (*filter_even_odd_even)(const FilterTaps& taps, int radius, int begin, int end, const float* half_a,
                                 const float* half_odd, const float* half_c, float* out_a, float* out_odd,
                                 float* out_c);
    void (*filter_even_even_odd_even)(const FilterTaps& taps, int radius, int begin, int end,
                                      const float* half_a, const float* half_b, const float* half_odd,
                                      const float* half_d, float* out_a, float* out_b, float* out_odd,
                                      float* out_d);

    // The same single even pass in double precision (SSIM, see ssim.cpp).
    void (*filter_even_f64)(const FilterTapsF64& taps, int radius, int begin, int end, const double* half,
                            double* out);

    // Vertical passes producing output rows y and y + 1 together (each input row loaded once
    // for both): taps.offsets holds the 2 * radius + 2 rows y - radius .. y + 1 + radius.
    void (*filter_even_rows2)(const FilterTaps& taps, int radius, int begin, int end, const float* half,
                              float* out0, float* out1);
    void (*filter_odd_even_rows2)(const FilterTaps& taps, int radius, int begin, int end,
                                  const float* half_odd, const float* half_even, float* out0_odd,
                                  float* out0_even, float* out1_odd, float* out1_even);
    void (*filter_even_rows2_f64)(const FilterTapsF64& taps, int radius, int begin, int end,
                                  const double* half, double* out0, double* out1);

    // Splits `width` interleaved pixels of `channels` (1, 3 or 4) floats into R, G and B rows
    // (a grey pixel goes to all three; alpha is dropped). Writes exactly `width` values each.
    void (*deinterleave_rgb)(const float* pixels, int channels, int width, float* r, float* g, float* b);

    // PSNR: sum of squared differences over R, G, B of `count` pixels of two images with the
    // same number (3 or 4) of channels, in double.
    double (*squared_error_rgb)(const float* a, const float* b, int channels, int count);

    // SSIM, the inputs of the two moments of s = x + y (or, with `difference`, of d = x - y) in
    // double: v and v^2. Writes exactly `width` values each.
    void (*ssim_inputs_row)(const float* x, const float* y, int width, bool difference, double* v,
                            double* vv);
    // The same for d in float (d and d^2). Returns whether every |d| is at most `limit` (false
    // for NaN). Writes exactly `width` values each.
    bool (*ssim_small_differences_row)(const float* x, const float* y, int width, float limit, float* d,
                                       float* dd);
    // out[i] = in[i] in double, i in [0, n).
    void (*widen_row)(const float* in, int n, double* out);
    // SSIM at x in [begin, end) of one row from its windowed moments (means of s, s^2 and of
    // d, d^2), computed in double, stored as float. `begin` must be a multiple of kMaxLanes.
    // The _small_differences variant takes the moments of d in float (see ssim.cpp).
    void (*ssim_row)(const double* const* s_moments, const double* const* d_moments, int begin, int end,
                     double c1, double c2, float* out);
    void (*ssim_row_small_differences)(const double* const* s_moments, const float* const* d_moments,
                                       int begin, int end, double c1, double c2, float* out);

    // Sum (in double) and maximum of values[begin, end) where mask is non-zero (mask may be
    // nullptr: every value counts). The maximum starts at `*max` and ignores NaN.
    double (*masked_sum_max)(const float* values, const unsigned char* mask, int begin, int end, float* max);

    // FLIP's error histogram: adds each values[i], i in [0, n), with mask[i] non-zero (mask may
    // be nullptr) to bins[(i % 4) * bin_count + clamp(int(values[i] * bin_count), 0,
    // bin_count - 1)] (four interleaved copies of the bins; see flip.cpp). Returns how many.
    int (*add_to_bins)(const float* values, const unsigned char* mask, int n, int bin_count, double* bins);

    // Copies the values[i], i in [begin, end), with mask[i] non-zero (mask may be nullptr) and
    // low <= values[i] < high to `out`, in order; returns how many.
    int (*collect_range)(const float* values, const unsigned char* mask, int begin, int end, float low,
                         float high, float* out);

    // FLIP, step 1: sRGB rows (R, G, B; any values, clamped to [0,1] here) to the Cx and Cz
    // channels of YCxCz and the luminance Y / Y_white (whose Y channel is 116 luminance - 16).
    // Writes whole vector groups.
    void (*flip_colour_row)(const float* const* srgb, int width, float* cx, float* cz, float* luminance);

    // FLIP, step 3: the per-pixel error at x in [begin, end) of one row. `reference` and `test`
    // each point at eight filtered rows: the luminance through the achromatic filter (the Y
    // channel's (Y + 16) / 116), Cx, Cz part 1, Cz part 2, dx, ddx, dy, ddy of the luminance. `begin` must be
    // a multiple of kMaxLanes.
    void (*flip_error_row)(const float* const* reference, const float* const* test, int begin, int end,
                           const FlipColourConstants& constants, float* error);
};

// The table this CPU runs fastest, chosen once; the environment variable
// SHADERLAB_GRADER_KERNELS=portable forces the portable one.
const KernelTable& kernels();

// For tests: the portable table, and the AVX2 one if it was built and the CPU runs it
// (nullptr otherwise). setKernelsForTesting(nullptr) returns to the automatic choice.
const KernelTable& portableKernels();
const KernelTable* avx2Kernels();
void setKernelsForTesting(const KernelTable* table);

}  // namespace grader::detail
