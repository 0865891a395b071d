// Full-reference image metrics: PSNR, SSIM, LDR-FLIP, and a scan for NaN/Inf values.
// Every metric has the same call shape: reference image, test image, a config struct in, a
// result struct out (the NaN/Inf scan looks at one image). Nothing here renders, reads files,
// decides pass/fail or formats a report: thresholds live in the lab spec, JSON in the report
// layer. Inputs are grader::Image values (display-referred, sRGB-encoded, nominally [0,1]).
//
// Channels: images with 3 or 4 channels are compared on RGB (alpha is ignored: coverage is the
// mask's job); a 1-channel image is treated as grey (R = G = B). Reference and test must have
// the same width and height, otherwise `ok` is false and `error` says why.
//
// Cost: all three metrics together take ~17 ms for a 512x512 pair on one core of an AVX2
// machine (bench/bench_metrics.cpp); the inner loops pick AVX2 + FMA at run time and fall back
// to a portable build (~31 ms) elsewhere. No global state: calls may run on several threads.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "grader/metrics/image.h"
#include "grader/metrics/mask.h"

namespace grader {

// ---------------------------------------------------------------------------------------------
// PSNR
//
// Formula: MSE = mean over counted pixels and over R, G, B of (test - reference)^2;
//          PSNR = 10 * log10(peak^2 / MSE) dB, peak = 1.0 for [0,1] data.
// Source:  the standard definition (e.g. Gonzalez & Woods, Digital Image Processing).
// Typical: identical images -> +infinity (returned as std::numeric_limits<double>::infinity();
//          the report layer decides how to write it). A lossless 8-bit round trip of a float
//          image stays above ~55 dB; > 40 dB is visually identical; 30-40 dB small differences
//          (the lab default threshold is 30 dB); < 25 dB clearly different.
// NaN/Inf in the inputs propagate into a NaN or infinite MSE; run scanNonFinite() first.
// ---------------------------------------------------------------------------------------------
struct PsnrConfig {
    const Mask* mask = nullptr;  // nullptr: every pixel counts
    double peak = 1.0;           // largest possible value of the data
};

struct PsnrResult {
    bool ok = false;
    std::string error;            // why ok is false
    double psnr_db = 0.0;         // +infinity when MSE == 0
    double mse = 0.0;             // over R, G, B of the counted pixels
    std::size_t pixel_count = 0;  // pixels that counted
};

PsnrResult computePsnr(const Image& reference, const Image& test, const PsnrConfig& config = {});

// ---------------------------------------------------------------------------------------------
// SSIM
//
// Formula: per pixel and channel, with Gaussian-weighted local statistics (11x11 window,
//          sigma 1.5, weights normalised to sum 1, population (co)variances):
//            SSIM = (2 mu_x mu_y + C1)(2 sigma_xy + C2) / ((mu_x^2 + mu_y^2 + C1)(sigma_x^2 + sigma_y^2 +
//            C2))
//          with C1 = (K1 L)^2, C2 = (K2 L)^2, K1 = 0.01, K2 = 0.03, L = 1 (data range).
// Source:  Z. Wang, A. C. Bovik, H. R. Sheikh, E. P. Simoncelli, "Image quality assessment:
//          from error visibility to structural similarity", IEEE TIP 13(4):600-612, 2004.
// Convention: scikit-image's structural_similarity(gaussian_weights=True, sigma=1.5,
//          use_sample_covariance=False, data_range=1, channel_axis=-1): SSIM is computed per
//          colour channel and the channel means are averaged; the window is applied as a
//          separable Gaussian (truncate 3.5 -> radius 5) with 'reflect' (half-sample symmetric)
//          borders, and the mean leaves out a border of 5 pixels on every side, where the
//          window would reach outside the image. The local moments are computed in double;
//          values agree with scikit-image 0.19.3 to ~1e-8 (tests/ssim_test.cpp).
// Mask:    the mean runs over pixels that are in the mask AND inside that border.
// Typical: identical -> 1; > 0.98 near-identical; the lab default threshold is 0.95; < 0.8
//          visibly different structure. Range [-1, 1].
// Images must be at least 11 x 11 pixels (so that some pixel lies inside the border).
// ---------------------------------------------------------------------------------------------
struct SsimConfig {
    const Mask* mask = nullptr;  // nullptr: every pixel (inside the border) counts
    double k1 = 0.01;
    double k2 = 0.03;
    double data_range = 1.0;  // L
    double sigma = 1.5;       // window radius = int(3.5 * sigma + 0.5), as scipy.ndimage
    bool want_map = false;    // fill SsimResult::map
};

struct SsimResult {
    bool ok = false;
    std::string error;
    double ssim = 0.0;                         // mean over counted pixels of the channel-averaged SSIM
    int channel_count = 0;                     // 1 (grey) or 3 (RGB)
    double channel_ssim[3] = {0.0, 0.0, 0.0};  // per-channel means (first channel_count valid)
    std::size_t pixel_count = 0;
    // Channel-averaged SSIM per pixel, width * height, row-major; also defined on the border
    // (with reflected statistics) for display. Empty unless SsimConfig::want_map.
    std::vector<float> map;
};

SsimResult computeSsim(const Image& reference, const Image& test, const SsimConfig& config = {});
// The window's radius for `sigma`, int(3.5 * sigma + 0.5): an image narrower or lower than
// 2 * radius + 1 has no SSIM.
int ssimWindowRadius(double sigma);

// ---------------------------------------------------------------------------------------------
// FLIP (LDR)
//
// Formula: per pixel, error = colour_error ^ (1 - feature_error), in [0, 1], where
//   colour:  sRGB -> linear RGB -> XYZ -> YCxCz; spatial filtering with the contrast
//            sensitivity filters of the paper (Gaussians in cycles/degree: achromatic
//            a=1, b=0.0047; red-green a=1, b=0.0053; blue-yellow the sum a1=34.1, b1=0.04,
//            a2=13.5, b2=0.025; radius ceil(3 sqrt(b_max / (2 pi^2)) ppd), weights
//            normalised); back to linear RGB clamped to [0,1]; CIELab (D65); Hunt adjustment
//            (a, b scaled by 0.01 L); HyAB distance |dL| + sqrt(da^2 + db^2); raised to
//            qc = 0.7; redistributed: below pc * cmax (pc = 0.4) linearly onto [0, pt]
//            (pt = 0.95), above onto [pt, 1], cmax = HyAB(Hunt(green), Hunt(blue))^qc.
//   feature: on the normalised luminance (Y of XYZ), first and second Gaussian-derivative
//            filters with sigma = 0.5 * 0.082 * ppd pixels (radius ceil(3 sigma)), each
//            normalised (Gaussian to sum 1; positive and negative derivative weights to +1 and
//            -1); edge = |gradient|, point = |second derivatives|; feature_error =
//            (max(|edge_ref - edge_test|, |point_ref - point_test|) / sqrt(2)) ^ qf, qf = 0.5.
// Source:  P. Andersson, J. Nilsson, T. Akenine-Moller, M. Oskarsson, K. Astrom,
//          M. D. Fairchild, "FLIP: A Difference Evaluator for Alternating Images",
//          Proc. ACM Comput. Graph. Interact. Tech. (HPG) 3(2), 2020; constants, separable
//          filters and edge handling as in the authors' reference implementation
//          (github.com/NVlabs/flip): filters clamp to the edge pixel, inputs are clamped to
//          [0,1] first (NaN becomes 0), the default 67.02 pixels per degree is a 0.7 m wide
//          3840-pixel monitor seen from 0.7 m. Checked against an independent double-precision
//          implementation (tests/reference/flip_reference.py) to ~1e-5 in the mean; float
//          arithmetic with fast log2/exp2/cube root, per-pixel differences up to ~5e-5.
// Pooling: mean of the map; weighted percentiles as the FLIP tool's "weighted median" and
//          "weighted quartiles": sort the errors, the p-th weighted percentile is the first
//          error e_i at which the running sum of errors exceeds p * (sum of all errors);
//          0 when every error is 0.
// Mask:    filters always see the whole image; mean and percentiles run over masked pixels.
// Typical: identical -> 0; < 0.01 practically invisible; ~0.05 small visible differences (the
//          lab default threshold); > 0.2 obvious. Black versus white is ~0.967.
// ---------------------------------------------------------------------------------------------
struct FlipConfig {
    const Mask* mask = nullptr;
    float pixels_per_degree = 67.0206432f;  // 0.7 m * (3840 px / 0.7 m) * pi / 180
    bool want_map = true;                   // fill FlipResult::error_map
};

struct FlipResult {
    bool ok = false;
    std::string error;
    double mean = 0.0;
    double weighted_p25 = 0.0;     // "1st weighted quartile"
    double weighted_median = 0.0;  // "weighted median"
    double weighted_p75 = 0.0;     // "3rd weighted quartile"
    float max_error = 0.0f;
    std::size_t pixel_count = 0;
    int width = 0;
    int height = 0;
    std::vector<float> error_map;  // width * height, row-major; whole frame, mask or not
};

FlipResult computeFlip(const Image& reference, const Image& test, const FlipConfig& config = {});

// Pixels per degree of visual angle for a monitor `monitor_width_m` wide showing
// `resolution_x` pixels, seen from `distance_m` (the FLIP paper's viewing model).
double flipPixelsPerDegree(double distance_m, double resolution_x, double monitor_width_m);

// ---------------------------------------------------------------------------------------------
// NaN / Inf scan
//
// Counts pixels with a NaN in any channel and pixels with +Inf or -Inf in any channel (a pixel
// with both counts in both). Alpha is scanned too: a NaN alpha breaks blending downstream.
// Positions: the first `max_positions` non-finite pixels in row-major order, and the bounding
// box of all of them. Typical: a correct shader produces none; any is a failure to report.
// ---------------------------------------------------------------------------------------------
struct NonFiniteConfig {
    int max_positions = 10;
};

struct NonFiniteResult {
    std::size_t nan_pixels = 0;
    std::size_t inf_pixels = 0;
    std::size_t non_finite_pixels = 0;  // pixels with a NaN or an Inf
    std::vector<PixelPosition> first_positions;
    PixelBox bounding_box;  // empty when there are none

    bool any() const { return non_finite_pixels != 0; }
};

NonFiniteResult scanNonFinite(const Image& image, const NonFiniteConfig& config = {});

}  // namespace grader
