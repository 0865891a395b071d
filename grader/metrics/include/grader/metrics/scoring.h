// Judges one rendered image against its reference with a lab's thresholds, and turns scene
// verdicts into points. Images in, verdict structs out: no rendering, no files, no JSON.
//
// What is compared (docs/grading.md): both images are first quantised to the 8 bits per channel
// that the PNG files hold, so a reference rendered now and a golden PNG stored earlier grade a
// submission identically. NaN and Inf are looked for before that, in the float image. Metrics are
// computed over the covered pixels (the union of what the reference and the student drew) and,
// for information, over the whole frame.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "grader/metrics/compare.h"
#include "grader/metrics/image.h"
#include "grader/metrics/mask.h"
#include "grader/metrics/metrics.h"

namespace grader {

struct Thresholds {
    double psnr_min_db = 30.0;
    double ssim_min = 0.95;
    double flip_mean_max = 0.05;
    double mismatch_max = 0.01;
    float pixel_tolerance = 0.05f;
};

// How pixel values are brought into the 0..1 range the metrics expect.
//   Display: as the PNG shows them: clamped to 0..1 and rounded to 8 bits.
//   Hdr:     values above 1 kept (an intermediate float pass, such as a bloom's bright pass):
//            both images are rounded as Radiance RGBE stores them (Ward, "Real Pixels",
//            Graphics Gems II, 1991; 8-bit mantissas, shared exponent), then divided by the
//            reference's largest value when that exceeds 1. Negative values count as 0.
enum class ImageRange { Display, Hdr };

struct MetricSet {
    double psnr_db = 0.0;      // +infinity for identical images
    bool ssim_defined = true;  // false when the image is smaller than SSIM's 11x11 window
    double ssim = 0.0;
    double flip_mean = 0.0;
    double flip_weighted_median = 0.0;
    double mismatch_fraction = 0.0;
    std::size_t pixel_count = 0;
};

// The verdict on one image (one graded pass of one scene).
struct ImageVerdict {
    bool passed = false;
    std::vector<std::string> reasons;  // every threshold that failed, readable
    std::size_t nan_count = 0;         // pixels with a NaN in the student's float image
    std::size_t inf_count = 0;
    PixelBox non_finite_box;
    std::vector<PixelPosition> non_finite_first;
    MetricSet covered;  // what the verdict uses
    MetricSet frame;    // whole frame, reported for information
    std::size_t covered_pixels = 0;
    WorstRegion worst;                     // of the shift-tolerant comparison over covered pixels
    int checks_met = 0, checks_total = 4;  // of psnr, ssim (when defined), flip, mismatch
    double hdr_scale = 1.0;                // Hdr: what both images were divided by
    // For the diff picture: FLIP error per pixel (whole frame) and the mismatching pixels.
    std::vector<float> flip_map;
    Mask mismatches;
    Mask graded;  // the pixels the verdict counts (covered, or the whole frame)
};

// `value` and `limit` printed with `digits` decimals, or with more (at most 6) until the two read
// differently, so that a failing value never prints equal to its threshold ("0.950 is below
// 0.950"). Equal numbers stay equal.
std::pair<std::string, std::string> formatDistinct(double value, double limit, int digits);

// Rounds every channel to the nearest of 256 levels in [0, 1] (NaN becomes 0), as writePng.
Image quantise8(const Image& image);
// RGB as an RGBE file stores it (NaN, Inf and negative values become 0); alpha is kept. The
// result reads back unchanged from writeHdr/readHdr.
Image rgbeRoundTrip(const Image& image);

// `reference_coverage` / `test_coverage`: 1 where geometry was drawn (empty: everything).
ImageVerdict judgeImage(const Image& reference, const std::vector<std::uint8_t>& reference_coverage,
                        const Image& test, const std::vector<std::uint8_t>& test_coverage,
                        const Thresholds& thresholds, ImageRange range = ImageRange::Display);

}  // namespace grader
