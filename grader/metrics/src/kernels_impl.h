// Internal: the body of the kernels declared in kernels.h. Included once by kernels_portable.cpp
// and once by kernels_avx2.cpp (compiled with -mavx2 -mfma), each defining
// GRADER_KERNELS_NAMESPACE first. The lane count follows the instruction set the file is
// compiled for: eight floats with AVX, four otherwise.
//
// Everything below has internal linkage (anonymous namespace) except the table accessor, and
// uses no standard-library templates or inline functions: the AVX2 build must not emit a weak
// copy of some shared inline function that the linker could then hand to code running on a
// CPU without AVX2.
//
// Vectors are the GCC/Clang vector extension, so the arithmetic is written once for both
// widths. The fast elementwise functions (log2, exp2, cube root) are accurate to a few 1e-7
// relative, far below what the metrics resolve; std::pow and std::cbrt cost 5-15 ns each and
// FLIP needs 14 of them per pixel.
#ifndef GRADER_KERNELS_NAMESPACE
#error "define GRADER_KERNELS_NAMESPACE before including kernels_impl.h"
#endif

#include <cstddef>
#include <cstdint>
#include <cstring>

#if defined(__SSE__)
#include <immintrin.h>
#endif

#include "flip_constants.h"
#include "kernels.h"

namespace grader::detail::GRADER_KERNELS_NAMESPACE {
namespace {

#if defined(__AVX__)
constexpr int kLanes = 8;
#else
constexpr int kLanes = 4;
#endif
static_assert(kLanes <= kMaxLanes, "rows are padded for at most kMaxLanes");

using F = float __attribute__((vector_size(kLanes * sizeof(float))));
using I = std::int32_t __attribute__((vector_size(kLanes * sizeof(std::int32_t))));
// Doubles in a register of the same width, and the floats that convert to them.
constexpr int kDoubleLanes = kLanes / 2;
using D = double __attribute__((vector_size(kDoubleLanes * sizeof(double))));
using HalfF = float __attribute__((vector_size(kDoubleLanes * sizeof(float))));

template <typename T>
struct VectorOf {
    using type = F;
    static constexpr int lanes = kLanes;
};
template <>
struct VectorOf<double> {
    using type = D;
    static constexpr int lanes = kDoubleLanes;
};

template <typename V, typename T>
inline V loadVector(const T* p) {
    V v;
    std::memcpy(&v, p, sizeof v);
    return v;
}
template <typename V, typename T>
inline void storeVector(T* p, V v) {
    std::memcpy(p, &v, sizeof v);
}

inline F load(const float* p) {
    F v;
    std::memcpy(&v, p, sizeof v);
    return v;
}
inline void store(float* p, F v) { std::memcpy(p, &v, sizeof v); }
inline F splat(float s) { return F{} + s; }
inline I splatInt(std::int32_t s) { return I{} + s; }

template <typename To, typename From>
inline To bitCast(From v) {
    static_assert(sizeof(To) == sizeof(From), "bitCast needs equal sizes");
    To out;
    std::memcpy(&out, &v, sizeof out);
    return out;
}

// a * b + c, fused into one rounding where the CPU has FMA. Written out rather than left to
// the compiler's contraction (-ffp-contract), which may fuse the same expression differently
// in two copies of it: FLIP's reference and test images must go through identical arithmetic,
// or identical images would show a small error.
inline F mulAdd(F a, F b, F c) {
#if defined(__FMA__) && defined(__AVX__)
    return bitCast<F>(_mm256_fmadd_ps(bitCast<__m256>(a), bitCast<__m256>(b), bitCast<__m256>(c)));
#else
    return a * b + c;
#endif
}
inline D mulAdd(D a, D b, D c) {
#if defined(__FMA__) && defined(__AVX__)
    return bitCast<D>(_mm256_fmadd_pd(bitCast<__m256d>(a), bitCast<__m256d>(b), bitCast<__m256d>(c)));
#else
    return a * b + c;
#endif
}
template <typename V, typename T>
inline V broadcast(T value) {
    return V{} + value;
}

// Whether any lane of a comparison result is set.
inline bool anyLane(I mask) {
#if defined(__AVX__)
    return _mm256_movemask_ps(bitCast<__m256>(mask)) != 0;
#elif defined(__SSE__)
    return _mm_movemask_ps(bitCast<__m128>(mask)) != 0;
#else
    bool any = false;
    for (int lane = 0; lane < kLanes; ++lane) any |= mask[lane] != 0;
    return any;
#endif
}

inline F vmax(F a, F b) { return a > b ? a : b; }
inline F vmin(F a, F b) { return a < b ? a : b; }
inline F vabs(F v) { return bitCast<F>(bitCast<I>(v) & splatInt(0x7fffffff)); }
// Clamp to [0, 1]; NaN becomes 0 (NaN > 0 is false), as the FLIP reference's clamp does.
inline F clamp01(F v) {
    const F positive = v > splat(0.0f) ? v : splat(0.0f);
    return positive < splat(1.0f) ? positive : splat(1.0f);
}

inline F vsqrt(F v) {
#if defined(__AVX__)
    return bitCast<F>(_mm256_sqrt_ps(bitCast<__m256>(v)));
#elif defined(__SSE__)
    return bitCast<F>(_mm_sqrt_ps(bitCast<__m128>(v)));
#else
    F r;
    for (int i = 0; i < kLanes; ++i) r[i] = __builtin_sqrtf(v[i]);
    return r;
#endif
}

// log2 of positive normal numbers. x = m * 2^e with m in [sqrt(1/2), sqrt(2)); then
// log2(m) = t q(t), t = m - 1, with q a degree-7 polynomial fitted (least squares on Chebyshev
// nodes) to log2(1 + t) / t on that interval: error below 1.5e-7 in float, and no division,
// the slowest vector operation.
inline F log2Positive(F x) {
    const I bits = bitCast<I>(x);
    I exponent = ((bits >> 23) & splatInt(0xff)) - splatInt(127);
    F mantissa = bitCast<F>((bits & splatInt(0x007fffff)) | splatInt(0x3f800000));  // [1, 2)
    const I above = mantissa > splat(1.41421356f);
    mantissa = above ? mantissa * 0.5f : mantissa;
    exponent = exponent - above;  // `above` is -1 where true
    const F t = mantissa - 1.0f;
    constexpr float kCoefficients[] = {2.342098512e-01f,  -2.488218056e-01f, 2.870756112e-01f,
                                       -3.602419859e-01f, 4.809240386e-01f,  -7.213527588e-01f,
                                       1.442694958e+00f};
    F q = splat(-1.462035344e-01f);
#pragma GCC unroll 8
    for (float c : kCoefficients) q = mulAdd(q, t, splat(c));
    return mulAdd(t, q, __builtin_convertvector(exponent, F));
}

// 2^y; 0 below 2^-126. y = n + f with n an integer and f in [-1/2, 1/2]; 2^f by a degree-6
// polynomial fitted like log2's (relative error about 1e-7 in float).
inline F exp2(F y) {
    const F clamped = vmin(vmax(y, splat(-127.0f)), splat(127.0f));
    const F shifted = clamped + 0.5f;
    I n = __builtin_convertvector(shifted, I);          // truncates toward zero
    n = n + (__builtin_convertvector(n, F) > shifted);  // -> floor(shifted)
    const F f = clamped - __builtin_convertvector(n, F);
    constexpr float kCoefficients[] = {1.340043216e-03f, 9.618025605e-03f, 5.550327214e-02f,
                                       2.402265121e-01f, 6.931472067e-01f, 1.0f};
    F p = splat(1.546973154e-04f);
#pragma GCC unroll 8
    for (float c : kCoefficients) p = mulAdd(p, f, splat(c));
    const F scale = bitCast<F>((n + 127) << 23);  // n = -127 gives 0
    return y < splat(-126.0f) ? splat(0.0f) : p * scale;
}

// x^y for x >= 0 (negative x and NaN count as 0), with std::pow's values at 0: 0^0 = 1 and
// 0^y = 0 for y > 0. Values below 1e-30 count as 0.
inline F powNonNegative(F x, F y) {
    const I is_zero = ~(x > splat(1e-30f));
    const F result = exp2(y * log2Positive(is_zero ? splat(1.0f) : x));
    const F zero_result = y == splat(0.0f) ? splat(1.0f) : splat(0.0f);
    return is_zero ? zero_result : result;
}

// Cube root of positive normal values, without a division (the divider is the scarcest unit
// in FLIP's per-pixel arithmetic): r = t^(-1/3) from the float's bits (exponent times -1/3,
// the magic constant 0x54a2fa8c, ~4% off), then two third-order Householder steps
// r <- r (1 + d / 3 + 2 d^2 / 9) with d = 1 - t r^3 (the Taylor series of (1 - d)^(-1/3)),
// each cubing the relative error (4e-2 -> ~1e-5 -> float rounding; measured 3.5e-7 over
// [0.0089, 1.2], the range FLIP's Lab conversion feeds it). Then t^(1/3) = t r^2. Zero gives
// 0 and is selected away by callers anyway.
inline F cubeRoot(F t) {
    const F bits_over_three = __builtin_convertvector(bitCast<I>(t), F) * (1.0f / 3.0f);
    F r = bitCast<F>(splatInt(0x54a2fa8c) - __builtin_convertvector(bits_over_three, I));
#pragma GCC unroll 2
    for (int step = 0; step < 2; ++step) {
        const F d = mulAdd(-t, r * r * r, splat(1.0f));
        r = r * mulAdd(d, mulAdd(d, splat(2.0f / 9.0f), splat(1.0f / 3.0f)), splat(1.0f));
    }
    return t * r * r;
}

// ---- filter passes -----------------------------------------------------------------------

// Outputs x .. x + lanes * Vectors - 1 of every kernel; weights[i][k] is kernel i's weight at
// offset +k. For each mirrored pair of offsets (-k, +k) both samples are loaded once; their sum
// feeds the even kernels and their difference the odd ones.
template <typename T, int Vectors, bool... Odd>
inline void mirroredBlock(const BasicFilterTaps<T>& taps, int radius, const T* const* weights, T* const* out,
                          int x) {
    using V = typename VectorOf<T>::type;
    constexpr int kStep = VectorOf<T>::lanes;
    constexpr int kKernels = sizeof...(Odd);
    constexpr bool kOdd[kKernels] = {Odd...};
    const T* const base = taps.base + x;
    const int* const mid = taps.offsets + radius;
    const std::ptrdiff_t stride = taps.stride;
    // Two sets of accumulators, for odd and even k, halve the chain of dependent adds.
    V acc[2][kKernels][Vectors];
    const T* centre_row = base + mid[0] * stride;
#pragma GCC unroll 4
    for (int i = 0; i < kKernels; ++i) {
#pragma GCC unroll 4
        for (int v = 0; v < Vectors; ++v) {
            acc[0][i][v] =
                kOdd[i] ? V{} : broadcast<V>(weights[i][0]) * loadVector<V>(centre_row + kStep * v);
            acc[1][i][v] = V{};
        }
    }
    auto step = [&](int k, int set) {
        const T* low = base + mid[-k] * stride;
        const T* high = base + mid[k] * stride;
#pragma GCC unroll 4
        for (int v = 0; v < Vectors; ++v) {
            const V l = loadVector<V>(low + kStep * v);
            const V h = loadVector<V>(high + kStep * v);
            const V sum = h + l;
            const V difference = h - l;
#pragma GCC unroll 4
            for (int i = 0; i < kKernels; ++i) {
                acc[set][i][v] =
                    mulAdd(broadcast<V>(weights[i][k]), kOdd[i] ? difference : sum, acc[set][i][v]);
            }
        }
    };
    int k = 1;
    for (; k + 1 <= radius; k += 2) {
        step(k, 0);
        step(k + 1, 1);
    }
    if (k <= radius) step(k, 0);
#pragma GCC unroll 4
    for (int i = 0; i < kKernels; ++i) {
#pragma GCC unroll 4
        for (int v = 0; v < Vectors; ++v) storeVector(out[i] + x + kStep * v, acc[0][i][v] + acc[1][i][v]);
    }
}

// A lone kernel gets four vectors of accumulators so that the adds do not wait on each other;
// kernels running together are independent already and get two each (registers run out
// otherwise).
template <typename T, bool... Odd>
void mirroredPass(const BasicFilterTaps<T>& taps, int radius, int begin, int end, const T* const* weights,
                  T* const* out) {
    constexpr int kStep = VectorOf<T>::lanes;
    constexpr int kKernels = sizeof...(Odd);
    constexpr bool kOdd[kKernels] = {Odd...};
    constexpr int kVectors = kKernels == 1 ? 4 : (kKernels >= 4 ? 1 : 2);
    int x = begin;
    for (; x + kStep * kVectors <= end; x += kStep * kVectors) {
        mirroredBlock<T, kVectors, Odd...>(taps, radius, weights, out, x);
    }
    for (; x + kStep <= end; x += kStep) mirroredBlock<T, 1, Odd...>(taps, radius, weights, out, x);
    const int* mid = taps.offsets + radius;
    for (; x < end; ++x) {
        for (int i = 0; i < kKernels; ++i) {
            const T* column = taps.base + x;
            T a = kOdd[i] ? T(0) : weights[i][0] * column[mid[0] * taps.stride];
            for (int k = 1; k <= radius; ++k) {
                const T high = column[mid[k] * taps.stride];
                const T low = column[mid[-k] * taps.stride];
                a += weights[i][k] * (kOdd[i] ? high - low : high + low);
            }
            out[i][x] = a;
        }
    }
}

// Vertical passes producing two output rows, y and y + 1, at once: offsets[0 .. 2r + 1] are
// rows y - r .. y + 1 + r. Each input row is loaded once and serves both outputs: per mirrored
// pair, row y + k is the high sample of row y's pair k and of row y + 1's pair k - 1, and row
// y - k the low sample of row y's pair k and of row y + 1's pair k + 1. Half the loads (and
// half the traffic from the L2 cache, where the rings live) of two single-row passes.
template <typename T, int Vectors, bool... Odd>
inline void mirroredRowsBlock(const BasicFilterTaps<T>& taps, int radius, const T* const* weights,
                              T* const* out0, T* const* out1, int x) {
    using V = typename VectorOf<T>::type;
    constexpr int kStep = VectorOf<T>::lanes;
    constexpr int kKernels = sizeof...(Odd);
    constexpr bool kOdd[kKernels] = {Odd...};
    const T* const base = taps.base + x;
    const int* const mid = taps.offsets + radius;  // mid[j]: row y + j, j in [-radius, radius + 1]
    const std::ptrdiff_t stride = taps.stride;
    V acc0[kKernels][Vectors], acc1[kKernels][Vectors];
    V high0[Vectors], low1[Vectors];  // row y + k and row y + 1 - k for the coming k
#pragma GCC unroll 4
    for (int v = 0; v < Vectors; ++v) {
        low1[v] = loadVector<V>(base + mid[0] * stride + kStep * v);   // row y
        high0[v] = loadVector<V>(base + mid[1] * stride + kStep * v);  // row y + 1
#pragma GCC unroll 3
        for (int i = 0; i < kKernels; ++i) {
            acc0[i][v] = kOdd[i] ? V{} : weights[i][0] * low1[v];
            acc1[i][v] = kOdd[i] ? V{} : weights[i][0] * high0[v];
        }
    }
    for (int k = 1; k <= radius; ++k) {
        const T* low_row = base + mid[-k] * stride;      // row y - k
        const T* high_row = base + mid[k + 1] * stride;  // row y + 1 + k
#pragma GCC unroll 4
        for (int v = 0; v < Vectors; ++v) {
            const V low0 = loadVector<V>(low_row + kStep * v);
            const V high1 = loadVector<V>(high_row + kStep * v);
            const V sum0 = high0[v] + low0, difference0 = high0[v] - low0;
            const V sum1 = high1 + low1[v], difference1 = high1 - low1[v];
#pragma GCC unroll 3
            for (int i = 0; i < kKernels; ++i) {
                const V w = broadcast<V>(weights[i][k]);
                acc0[i][v] = mulAdd(w, kOdd[i] ? difference0 : sum0, acc0[i][v]);
                acc1[i][v] = mulAdd(w, kOdd[i] ? difference1 : sum1, acc1[i][v]);
            }
            high0[v] = high1;  // row y + 1 + k is row y's high sample for k + 1
            low1[v] = low0;    // row y - k is row y + 1's low sample for k + 1
        }
    }
#pragma GCC unroll 3
    for (int i = 0; i < kKernels; ++i) {
#pragma GCC unroll 4
        for (int v = 0; v < Vectors; ++v) {
            storeVector(out0[i] + x + kStep * v, acc0[i][v]);
            storeVector(out1[i] + x + kStep * v, acc1[i][v]);
        }
    }
}

template <typename T, bool... Odd>
void mirroredRowsPass(const BasicFilterTaps<T>& taps, int radius, int begin, int end, const T* const* weights,
                      T* const* out0, T* const* out1) {
    constexpr int kStep = VectorOf<T>::lanes;
    constexpr int kKernels = sizeof...(Odd);
    constexpr bool kOdd[kKernels] = {Odd...};
    constexpr int kVectors = kKernels == 1 ? 2 : 1;
    int x = begin;
    for (; x + kStep * kVectors <= end; x += kStep * kVectors) {
        mirroredRowsBlock<T, kVectors, Odd...>(taps, radius, weights, out0, out1, x);
    }
    for (; x + kStep <= end; x += kStep)
        mirroredRowsBlock<T, 1, Odd...>(taps, radius, weights, out0, out1, x);
    const int* mid = taps.offsets + radius;
    for (; x < end; ++x) {
        const T* column = taps.base + x;
        auto row = [&](int j) { return column[mid[j] * taps.stride]; };
        for (int i = 0; i < kKernels; ++i) {
            T a0 = kOdd[i] ? T(0) : weights[i][0] * row(0);
            T a1 = kOdd[i] ? T(0) : weights[i][0] * row(1);
            for (int k = 1; k <= radius; ++k) {
                a0 += weights[i][k] * (kOdd[i] ? row(k) - row(-k) : row(k) + row(-k));
                a1 += weights[i][k] * (kOdd[i] ? row(1 + k) - row(1 - k) : row(1 + k) + row(1 - k));
            }
            out0[i][x] = a0;
            out1[i][x] = a1;
        }
    }
}

void filterEvenRows2(const FilterTaps& taps, int radius, int begin, int end, const float* half, float* out0,
                     float* out1) {
    const float* weights[] = {half};
    float* outputs0[] = {out0};
    float* outputs1[] = {out1};
    mirroredRowsPass<float, false>(taps, radius, begin, end, weights, outputs0, outputs1);
}

void filterOddEvenRows2(const FilterTaps& taps, int radius, int begin, int end, const float* half_odd,
                        const float* half_even, float* out0_odd, float* out0_even, float* out1_odd,
                        float* out1_even) {
    const float* weights[] = {half_odd, half_even};
    float* outputs0[] = {out0_odd, out0_even};
    float* outputs1[] = {out1_odd, out1_even};
    mirroredRowsPass<float, true, false>(taps, radius, begin, end, weights, outputs0, outputs1);
}

void filterEvenRows2F64(const FilterTapsF64& taps, int radius, int begin, int end, const double* half,
                        double* out0, double* out1) {
    const double* weights[] = {half};
    double* outputs0[] = {out0};
    double* outputs1[] = {out1};
    mirroredRowsPass<double, false>(taps, radius, begin, end, weights, outputs0, outputs1);
}

void filterEvenF64(const FilterTapsF64& taps, int radius, int begin, int end, const double* half,
                   double* out) {
    const double* weights[] = {half};
    double* outputs[] = {out};
    mirroredPass<double, false>(taps, radius, begin, end, weights, outputs);
}

void filterEven(const FilterTaps& taps, int radius, int begin, int end, const float* half, float* out) {
    const float* weights[] = {half};
    float* outputs[] = {out};
    mirroredPass<float, false>(taps, radius, begin, end, weights, outputs);
}

void filterEvenEven(const FilterTaps& taps, int radius, int begin, int end, const float* half_a,
                    const float* half_b, float* out_a, float* out_b) {
    const float* weights[] = {half_a, half_b};
    float* outputs[] = {out_a, out_b};
    mirroredPass<float, false, false>(taps, radius, begin, end, weights, outputs);
}

void filterOddEven(const FilterTaps& taps, int radius, int begin, int end, const float* half_odd,
                   const float* half_even, float* out_odd, float* out_even) {
    const float* weights[] = {half_odd, half_even};
    float* outputs[] = {out_odd, out_even};
    mirroredPass<float, true, false>(taps, radius, begin, end, weights, outputs);
}

void filterEvenOddEven(const FilterTaps& taps, int radius, int begin, int end, const float* half_a,
                       const float* half_odd, const float* half_c, float* out_a, float* out_odd,
                       float* out_c) {
    const float* weights[] = {half_a, half_odd, half_c};
    float* outputs[] = {out_a, out_odd, out_c};
    mirroredPass<float, false, true, false>(taps, radius, begin, end, weights, outputs);
}

void filterEvenEvenOddEven(const FilterTaps& taps, int radius, int begin, int end, const float* half_a,
                           const float* half_b, const float* half_odd, const float* half_d, float* out_a,
                           float* out_b, float* out_odd, float* out_d) {
    const float* weights[] = {half_a, half_b, half_odd, half_d};
    float* outputs[] = {out_a, out_b, out_odd, out_d};
    mirroredPass<float, false, false, true, false>(taps, radius, begin, end, weights, outputs);
}

// ---- row helpers -------------------------------------------------------------------------

double maskedSumMax(const float* values, const unsigned char* mask, int begin, int end, float* max) {
    // Float lanes per row (a row holds at most a few thousand values), double across rows.
    F sum = splat(0.0f);
    F high = splat(*max);
    int x = begin;
    for (; x + kLanes <= end; x += kLanes) {
        F v = load(values + x);
        if (mask != nullptr) {
            I keep = splatInt(0);
            for (int lane = 0; lane < kLanes; ++lane) keep[lane] = mask[x + lane] != 0 ? -1 : 0;
            v = keep ? v : splat(0.0f);
            high = (keep & (v > high)) ? v : high;
        } else {
            high = v > high ? v : high;
        }
        sum += v;
    }
    double total = 0.0;
    for (int lane = 0; lane < kLanes; ++lane) total += sum[lane];
    float best = *max;
    for (int lane = 0; lane < kLanes; ++lane) best = high[lane] > best ? high[lane] : best;
    for (; x < end; ++x) {
        if (mask != nullptr && mask[x] == 0) continue;
        total += values[x];
        best = values[x] > best ? values[x] : best;
    }
    *max = best;
    return total;
}

void deinterleaveRgb(const float* pixels, int channels, int width, float* r, float* g, float* b) {
    int x = 0;
#if defined(__AVX2__)
    // Eight pixels per step, shuffled in registers instead of 24 scalar loads and stores.
    if (channels == 4) {
        const __m256i order = _mm256_setr_epi32(0, 4, 1, 5, 2, 6, 3, 7);
        for (; x + 8 <= width; x += 8) {
            const float* p = pixels + static_cast<std::ptrdiff_t>(x) * 4;
            const __m256 v0 = _mm256_loadu_ps(p), v1 = _mm256_loadu_ps(p + 8);
            const __m256 v2 = _mm256_loadu_ps(p + 16), v3 = _mm256_loadu_ps(p + 24);
            // Within each 128-bit half: r0 r2 g0 g2 / b0 b2 a0 a2 (and pixels 1 3, 4 6, 5 7).
            const __m256 rg01 = _mm256_unpacklo_ps(v0, v1), ba01 = _mm256_unpackhi_ps(v0, v1);
            const __m256 rg23 = _mm256_unpacklo_ps(v2, v3), ba23 = _mm256_unpackhi_ps(v2, v3);
            const __m256 reds =
                _mm256_castpd_ps(_mm256_unpacklo_pd(_mm256_castps_pd(rg01), _mm256_castps_pd(rg23)));
            const __m256 greens =
                _mm256_castpd_ps(_mm256_unpackhi_pd(_mm256_castps_pd(rg01), _mm256_castps_pd(rg23)));
            const __m256 blues =
                _mm256_castpd_ps(_mm256_unpacklo_pd(_mm256_castps_pd(ba01), _mm256_castps_pd(ba23)));
            // Each is now pixels 0 2 4 6 | 1 3 5 7.
            _mm256_storeu_ps(r + x, _mm256_permutevar8x32_ps(reds, order));
            _mm256_storeu_ps(g + x, _mm256_permutevar8x32_ps(greens, order));
            _mm256_storeu_ps(b + x, _mm256_permutevar8x32_ps(blues, order));
        }
    } else if (channels == 3) {
        // v0 = r0 g0 b0 r1 g1 b1 r2 g2, v1 = b2 r3 g3 b3 r4 g4 b4 r5, v2 = g5 b5 r6 g6 b6 r7 g7 b7:
        // each colour sits in lanes of v0, v1, v2 that do not overlap, so two blends gather it
        // and one permutation puts it in order.
        const __m256i red_order = _mm256_setr_epi32(0, 3, 6, 1, 4, 7, 2, 5);
        const __m256i green_order = _mm256_setr_epi32(1, 4, 7, 2, 5, 0, 3, 6);
        const __m256i blue_order = _mm256_setr_epi32(2, 5, 0, 3, 6, 1, 4, 7);
        for (; x + 8 <= width; x += 8) {
            const float* p = pixels + static_cast<std::ptrdiff_t>(x) * 3;
            const __m256 v0 = _mm256_loadu_ps(p), v1 = _mm256_loadu_ps(p + 8), v2 = _mm256_loadu_ps(p + 16);
            const __m256 reds =
                _mm256_blend_ps(_mm256_blend_ps(v0, v1, 0x92), v2, 0x24);  // v1: 1 4 7, v2: 2 5
            const __m256 greens =
                _mm256_blend_ps(_mm256_blend_ps(v0, v1, 0x24), v2, 0x49);  // v1: 2 5, v2: 0 3 6
            const __m256 blues =
                _mm256_blend_ps(_mm256_blend_ps(v0, v1, 0x49), v2, 0x92);  // v1: 0 3 6, v2: 1 4 7
            _mm256_storeu_ps(r + x, _mm256_permutevar8x32_ps(reds, red_order));
            _mm256_storeu_ps(g + x, _mm256_permutevar8x32_ps(greens, green_order));
            _mm256_storeu_ps(b + x, _mm256_permutevar8x32_ps(blues, blue_order));
        }
    }
#endif
    const int step = channels;
    const int green = channels >= 3 ? 1 : 0, blue = channels >= 3 ? 2 : 0;
    for (; x < width; ++x) {
        const float* pixel = pixels + static_cast<std::ptrdiff_t>(x) * step;
        r[x] = pixel[0];
        g[x] = pixel[green];
        b[x] = pixel[blue];
    }
}

double squaredErrorRgb(const float* a, const float* b, int channels, int count) {
    // In double: the difference of two floats and its square are exact there, so the result
    // is the exact sum up to the final additions.
    constexpr int kPatterns = 4 / kDoubleLanes;  // alpha recurs every 4 values
    D weights[kPatterns];
    for (int p = 0; p < kPatterns; ++p) {
        for (int lane = 0; lane < kDoubleLanes; ++lane) {
            weights[p][lane] = (channels == 4 && (p * kDoubleLanes + lane) % 4 == 3) ? 0.0 : 1.0;
        }
    }
    const int n = count * channels;
    D sum0{}, sum1{};
    int i = 0;
    // Steps of 4 values keep the alpha pattern aligned with `weights`.
    for (; i + 4 <= n; i += 4) {
        for (int p = 0; p < kPatterns; ++p) {
            const int at = i + p * kDoubleLanes;
            const D d = __builtin_convertvector(loadVector<HalfF>(a + at), D) -
                        __builtin_convertvector(loadVector<HalfF>(b + at), D);
            if (p % 2 == 0) {
                sum0 += weights[p] * d * d;
            } else {
                sum1 += weights[p] * d * d;
            }
        }
    }
    const D sum = sum0 + sum1;
    double total = 0.0;
    for (int lane = 0; lane < kDoubleLanes; ++lane) total += sum[lane];
    for (; i < n; ++i) {
        if (channels == 4 && i % 4 == 3) continue;
        const double d = static_cast<double>(a[i]) - b[i];
        total += d * d;
    }
    return total;
}

int addToBins(const float* values, const unsigned char* mask, int n, int bin_count, double* bins) {
    // The bin numbers eight at a time; the additions one by one (a scatter with repeated
    // indices would lose some). Lane i lands in copy i % 4, so neighbouring pixels, which tend
    // to share a bin, do not wait on each other's additions.
    alignas(32) std::int32_t index[kLanes];
    const F scale = splat(static_cast<float>(bin_count));
    const I last = splatInt(bin_count - 1);
    I offset;
    for (int lane = 0; lane < kLanes; ++lane) offset[lane] = (lane % 4) * bin_count;
    int added = 0;
    int x = 0;
    for (; x + kLanes <= n; x += kLanes) {
        const F v = load(values + x);
        I bin = __builtin_convertvector(v * scale, I);
        bin = bin < splatInt(0) ? splatInt(0) : bin;
        bin = bin > last ? last : bin;
        storeVector(index, bin + offset);
        if (mask == nullptr) {
#pragma GCC unroll 8
            for (int lane = 0; lane < kLanes; ++lane) bins[index[lane]] += values[x + lane];
            added += kLanes;
        } else {
            for (int lane = 0; lane < kLanes; ++lane) {
                if (mask[x + lane] == 0) continue;
                bins[index[lane]] += values[x + lane];
                ++added;
            }
        }
    }
    for (; x < n; ++x) {
        if (mask != nullptr && mask[x] == 0) continue;
        const float scaled = values[x] * static_cast<float>(bin_count);
        int bin = scaled > 0.0f ? static_cast<int>(scaled) : 0;  // NaN -> 0
        bin = bin < bin_count - 1 ? bin : bin_count - 1;
        bins[(x % 4) * bin_count + bin] += values[x];
        ++added;
    }
    return added;
}

int collectRange(const float* values, const unsigned char* mask, int begin, int end, float low, float high,
                 float* out) {
    // Mostly nothing matches: test a whole group at once, look at lanes only when one does.
    int count = 0;
    int x = begin;
    for (; x + kLanes <= end; x += kLanes) {
        const F v = load(values + x);
        const I inside = (v >= splat(low)) & (v < splat(high));
        if (!anyLane(inside)) continue;
        for (int lane = 0; lane < kLanes; ++lane) {
            if (inside[lane] && (mask == nullptr || mask[x + lane])) out[count++] = v[lane];
        }
    }
    for (; x < end; ++x) {
        if (values[x] >= low && values[x] < high && (mask == nullptr || mask[x])) out[count++] = values[x];
    }
    return count;
}

// ---- SSIM --------------------------------------------------------------------------------

void ssimInputsRow(const float* x, const float* y, int width, bool difference, double* v, double* vv) {
    const double sign = difference ? -1.0 : 1.0;
    int i = 0;
    for (; i + kDoubleLanes <= width; i += kDoubleLanes) {
        const D a = __builtin_convertvector(loadVector<HalfF>(x + i), D);
        const D b = __builtin_convertvector(loadVector<HalfF>(y + i), D);
        const D value = a + sign * b;  // exact: two floats' sum or difference fits a double
        storeVector(v + i, value);
        storeVector(vv + i, value * value);
    }
    for (; i < width; ++i) {
        const double value = static_cast<double>(x[i]) + sign * y[i];
        v[i] = value;
        vv[i] = value * value;
    }
}

bool ssimSmallDifferencesRow(const float* x, const float* y, int width, float limit, float* d, float* dd) {
    I large = splatInt(0);
    int i = 0;
    for (; i + kLanes <= width; i += kLanes) {
        const F difference = load(x + i) - load(y + i);
        store(d + i, difference);
        store(dd + i, difference * difference);
        large |= ~(vabs(difference) <= splat(limit));  // NaN counts as large
    }
    bool small = !anyLane(large);
    for (; i < width; ++i) {
        const float difference = x[i] - y[i];
        d[i] = difference;
        dd[i] = difference * difference;
        small = small && (difference <= limit && -difference <= limit);
    }
    return small;
}

void widenRow(const float* in, int n, double* out) {
    int i = 0;
    for (; i + kDoubleLanes <= n; i += kDoubleLanes)
        storeVector(out + i, __builtin_convertvector(loadVector<HalfF>(in + i), D));
    for (; i < n; ++i) out[i] = in[i];
}

void ssimRow(const double* const* s_moments, const double* const* d_moments, int begin, int end, double c1,
             double c2, float* out) {
    for (int x = begin; x < end; x += kDoubleLanes) {
        const D ms = loadVector<D>(s_moments[0] + x);
        const D md = loadVector<D>(d_moments[0] + x);
        const D var_s = loadVector<D>(s_moments[1] + x) - ms * ms;
        const D var_d = loadVector<D>(d_moments[1] + x) - md * md;
        const D ms2 = ms * ms, md2 = md * md;
        // (2 mu_x mu_y + C1)(2 sigma_xy + C2) / ((mu_x^2 + mu_y^2 + C1)(sigma_x^2 + sigma_y^2 + C2))
        // The differences above needed double; the quotient, stored as float, does not (a
        // float division is also several times cheaper).
        const D numerator = (0.5 * (ms2 - md2) + c1) * (0.5 * (var_s - var_d) + c2);
        const D denominator = (0.5 * (ms2 + md2) + c1) * (0.5 * (var_s + var_d) + c2);
        storeVector(out + x,
                    __builtin_convertvector(numerator, HalfF) / __builtin_convertvector(denominator, HalfF));
    }
}

// One vector from two halves (in registers: storing the halves and loading the whole would
// stall on store forwarding).
inline F joinHalves(HalfF low, HalfF high) {
#if !defined(__clang__) && __GNUC__ < 12
    // GCC before 12 (Debian 11's GCC 10 builds the portable binary) has no __builtin_shufflevector.
    F out;
    std::memcpy(&out, &low, sizeof low);
    std::memcpy(reinterpret_cast<char*>(&out) + sizeof low, &high, sizeof high);
    return out;
#elif defined(__AVX__)
    return __builtin_shufflevector(low, high, 0, 1, 2, 3, 4, 5, 6, 7);
#else
    return __builtin_shufflevector(low, high, 0, 1, 2, 3);
#endif
}

// With the moments of d in float (all |d| small, see ssim.cpp), only the variance of s needs
// double: mu_s^2 and var_s are formed there and rounded to float, and the rest runs in float,
// eight lanes at a time (rounding both adds ~1e-7 of the terms they enter, far below the float
// moments' own error).
void ssimRowSmallDifferences(const double* const* s_moments, const float* const* d_moments, int begin,
                             int end, double c1, double c2, float* out) {
    const F c1f = splat(static_cast<float>(c1)), c2f = splat(static_cast<float>(c2));
    for (int x = begin; x < end; x += kLanes) {
        const D ms_low = loadVector<D>(s_moments[0] + x),
                ms_high = loadVector<D>(s_moments[0] + x + kDoubleLanes);
        const D ms2_low = ms_low * ms_low, ms2_high = ms_high * ms_high;
        const D var_s_low = loadVector<D>(s_moments[1] + x) - ms2_low;
        const D var_s_high = loadVector<D>(s_moments[1] + x + kDoubleLanes) - ms2_high;
        const F ms2 =
            joinHalves(__builtin_convertvector(ms2_low, HalfF), __builtin_convertvector(ms2_high, HalfF));
        const F var_s =
            joinHalves(__builtin_convertvector(var_s_low, HalfF), __builtin_convertvector(var_s_high, HalfF));
        const F md = load(d_moments[0] + x);
        const F md2 = md * md;
        const F var_d = load(d_moments[1] + x) - md2;
        const F numerator = (0.5f * (ms2 - md2) + c1f) * (0.5f * (var_s - var_d) + c2f);
        const F denominator = (0.5f * (ms2 + md2) + c1f) * (0.5f * (var_s + var_d) + c2f);
        store(out + x, numerator / denominator);
    }
}

// ---- FLIP --------------------------------------------------------------------------------

using namespace flip_constants;

// sRGB decoding (IEC 61966-2-1): v / 12.92 up to 0.04045, u^2.4 with u = (v + 0.055) / 1.055
// above. Input clamped to [0, 1] first, NaN to 0, as the FLIP reference clamps its inputs.
// The power without pow() or a table (whose two gathers per value made this the slowest part
// of the colour conversion): u = m 2^e with m in [1, 2), u^2.4 = m^2.4 2^(2.4 e). m^2.4 is a
// degree-7 polynomial in m - 1.5 (interpolation at Chebyshev nodes; relative error 6e-9 in
// exact arithmetic, 1.8e-7 evaluated in float), and 2^(2.4 e) comes from eight constants for
// e in [-7, 0]: u >= 0.052, so e >= -5, and the permutation needs no memory access.
inline F srgbToLinear(F v) {
    const F clamped = clamp01(v);
    const F u = mulAdd(clamped, splat(1.0f / 1.055f), splat(0.055f / 1.055f));
    const I bits = bitCast<I>(u);
    const I octave = ((bits >> 23) & splatInt(0xff)) - splatInt(127 - 7);  // e + 7, in [2, 7]
    const F t = bitCast<F>((bits & splatInt(0x007fffff)) | splatInt(0x3f800000)) - 1.5f;
    constexpr float kCoefficients[] = {-1.158289961e-03f, 3.741660854e-03f, -1.755068265e-02f,
                                       1.756280512e-01f,  1.975812197e+00f, 4.233884335e+00f,
                                       2.646177769e+00f};
    F power = splat(4.028187541e-04f);
#pragma GCC unroll 8
    for (float c : kCoefficients) power = mulAdd(power, t, splat(c));
    // 2^(2.4 e) for e = -7 .. 0.
    constexpr float kScale[8] = {8.763872948e-06f, 4.625599873e-05f, 2.441406250e-04f, 1.288581944e-03f,
                                 6.801176276e-03f, 3.589682359e-02f, 1.894645708e-01f, 1.000000000e+00f};
    F scale;
#if defined(__AVX2__)
    scale = bitCast<F>(_mm256_permutevar8x32_ps(_mm256_loadu_ps(kScale), bitCast<__m256i>(octave)));
#else
    for (int lane = 0; lane < kLanes; ++lane) scale[lane] = kScale[octave[lane] & 7];
#endif
    return clamped <= splat(kSrgbLinearLimit) ? clamped * (1.0f / 12.92f) : power * scale;
}

void flipColourRow(const float* const* srgb, int width, float* cx, float* cz, float* luminance) {
    for (int x = 0; x < width; x += kLanes) {
        const F linear[3] = {srgbToLinear(load(srgb[0] + x)), srgbToLinear(load(srgb[1] + x)),
                             srgbToLinear(load(srgb[2] + x))};
        F n[3];  // XYZ relative to the white point
#pragma GCC unroll 3
        for (int i = 0; i < 3; ++i) {
            n[i] = mulAdd(splat(kRgbToXyz[i][0]), linear[0],
                          mulAdd(splat(kRgbToXyz[i][1]), linear[1], splat(kRgbToXyz[i][2]) * linear[2])) *
                   kInvWhite[i];
        }
        // YCxCz (FLIP paper, colour pipeline): CIELab without the cube root, linear in XYZ and so
        // fit for linear filtering. Its Y channel, 116 n[1] - 16, is affine in the luminance
        // n[1] = Y / Y_white, which the feature detectors see: the luminance is filtered for both.
        store(cx + x, 500.0f * (n[0] - n[1]));
        store(cz + x, 200.0f * (n[1] - n[2]));
        store(luminance + x, n[1]);
    }
}

inline F labF(F t) { return t > splat(kLabDeltaCube) ? cubeRoot(t) : t * kLabLinearSlope + kLabLinearOffset; }

struct HuntLab {
    F l, a, b;
};

// Filtered YCxCz (its Y as the luminance (Y + 16) / 116) -> XYZ -> linear RGB, clamped to the gamut
// (filtering can leave it) -> XYZ -> CIELab -> Hunt-adjusted a, b (colourfulness falls with lightness: a, b
// scaled by 0.01 L).
inline HuntLab filteredToHuntLab(F ny, F cx, F cz) {
    const F xyz[3] = {(ny + cx * (1.0f / 500.0f)) * kWhite[0], ny, (ny - cz * (1.0f / 200.0f)) * kWhite[2]};
    F rgb[3];
#pragma GCC unroll 3
    for (int i = 0; i < 3; ++i) {
        rgb[i] = clamp01(mulAdd(splat(kXyzToRgb[i][0]), xyz[0],
                                mulAdd(splat(kXyzToRgb[i][1]), xyz[1], splat(kXyzToRgb[i][2]) * xyz[2])));
    }
    F f[3];
#pragma GCC unroll 3
    for (int i = 0; i < 3; ++i) {
        f[i] = labF(mulAdd(splat(kRgbToXyz[i][0]), rgb[0],
                           mulAdd(splat(kRgbToXyz[i][1]), rgb[1], splat(kRgbToXyz[i][2]) * rgb[2])) *
                    kInvWhite[i]);
    }
    const F l = 116.0f * f[1] - 16.0f;
    const F hunt = 0.01f * l;
    return {l, hunt * (500.0f * (f[0] - f[1])), hunt * (200.0f * (f[1] - f[2]))};
}

// Two loops over chunks of a row rather than one: the whole per-pixel computation is one long
// dependency chain (cube roots, then HyAB, then two powers: ~250 cycles), longer than the
// processor's reordering window, so a single loop would run at the chain's latency. Split in
// two, each loop's iterations overlap; the values passed between them stay in the L1 cache.
void flipErrorRow(const float* const* reference, const float* const* test, int begin, int end,
                  const FlipColourConstants& constants, float* error) {
    enum { kY, kCx, kCz1, kCz2, kDx, kDdx, kDy, kDdy };
    constexpr int kChunk = 256;
    alignas(32) float distance_row[kChunk];
    alignas(32) float feature[kChunk];
    const float* const* images[2] = {reference, test};
    const F pccmax = splat(constants.pccmax);
    const F log_pccmax = log2Positive(pccmax);
    const F log_below_scale = log2Positive(splat(constants.below_scale));
    for (int chunk = begin; chunk < end; chunk += kChunk) {
        const int chunk_end = end - chunk < kChunk ? end : chunk + kChunk;
        // Colour distance (HyAB) and feature difference (before the exponent qf).
        for (int x = chunk; x < chunk_end; x += kLanes) {
            HuntLab lab[2];
            F edge[2], point[2];
#pragma GCC unroll 2
            for (int which = 0; which < 2; ++which) {
                const float* const* rows = images[which];
                lab[which] = filteredToHuntLab(load(rows[kY] + x), load(rows[kCx] + x),
                                               load(rows[kCz1] + x) + load(rows[kCz2] + x));
                const F dx = load(rows[kDx] + x), dy = load(rows[kDy] + x);
                const F ddx = load(rows[kDdx] + x), ddy = load(rows[kDdy] + x);
                edge[which] = vsqrt(dx * dx + dy * dy);
                point[which] = vsqrt(ddx * ddx + ddy * ddy);
            }
            const F da = lab[0].a - lab[1].a;
            const F db = lab[0].b - lab[1].b;
            store(distance_row + (x - chunk), vabs(lab[0].l - lab[1].l) + vsqrt(da * da + db * db));
            store(feature + (x - chunk), vmax(vabs(edge[0] - edge[1]), vabs(point[0] - point[1])));
        }
        // Colour error: the distance compressed by qc = 0.7 and redistributed so that
        // pc * cmax lands at pt; feature error with qf = 0.5, a square root; combined error
        // colour^(1 - feature). Below the bend the colour error is a constant times
        // distance^0.7, so its logarithm is 0.7 log2(distance) + log2(below_scale) and the
        // power needs one log2 and one exp2 instead of two of each; a group with a lane above
        // the bend (rare: pc * cmax is a large colour distance) takes the long way.
        for (int x = chunk; x < chunk_end; x += kLanes) {
            const F distance = load(distance_row + (x - chunk));
            const I positive = distance > splat(1e-30f);
            const F log_distance = log2Positive(positive ? distance : splat(1.0f));
            const I above = positive & (log_distance * 0.7f >= log_pccmax);
            F log_colour;
            if (!anyLane(above)) {
                log_colour = mulAdd(splat(0.7f), log_distance, log_below_scale);
            } else {
                const F compressed = exp2(log_distance * 0.7f);
                const F colour = above ? constants.pt + (compressed - pccmax) * constants.above_scale
                                       : compressed * constants.below_scale;
                log_colour = log2Positive(positive ? colour : splat(1.0f));
            }
            const F exponent = 1.0f - vsqrt(load(feature + (x - chunk)) * 0.70710678f);
            // No distance, no colour error: 0^exponent, which is 1 only for exponent 0.
            const F zero_distance = exponent == splat(0.0f) ? splat(1.0f) : splat(0.0f);
            store(error + x, positive ? exp2(exponent * log_colour) : zero_distance);
        }
    }
}

KernelTable makeTable() {
    KernelTable table{};
    table.name = GRADER_KERNELS_NAME;
    table.filter_even = filterEven;
    table.filter_even_even = filterEvenEven;
    table.filter_odd_even = filterOddEven;
    table.filter_even_odd_even = filterEvenOddEven;
    table.filter_even_even_odd_even = filterEvenEvenOddEven;
    table.filter_even_f64 = filterEvenF64;
    table.filter_even_rows2 = filterEvenRows2;
    table.filter_odd_even_rows2 = filterOddEvenRows2;
    table.filter_even_rows2_f64 = filterEvenRows2F64;
    table.deinterleave_rgb = deinterleaveRgb;
    table.squared_error_rgb = squaredErrorRgb;
    table.ssim_inputs_row = ssimInputsRow;
    table.ssim_small_differences_row = ssimSmallDifferencesRow;
    table.widen_row = widenRow;
    table.ssim_row = ssimRow;
    table.ssim_row_small_differences = ssimRowSmallDifferences;
    table.masked_sum_max = maskedSumMax;
    table.add_to_bins = addToBins;
    table.collect_range = collectRange;
    table.flip_colour_row = flipColourRow;
    table.flip_error_row = flipErrorRow;
    return table;
}

}  // namespace

const KernelTable& table() {
    static const KernelTable kTable = makeTable();
    return kTable;
}

}  // namespace grader::detail::GRADER_KERNELS_NAMESPACE
