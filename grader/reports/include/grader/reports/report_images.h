// The report's pictures besides the FLIP heat map (heatmap.h): where the student's image is too
// bright or too dark, which pixels are NaN or Inf, and a close-up of one region. Also the small
// pictures and the comparison behind known-mistake hints. Pure image-to-image: nothing here
// judges a submission, reads or writes files, or knows about HTML.
#pragma once

#include <vector>

#include "grader/metrics/image.h"
#include "grader/metrics/mask.h"

namespace grader {

// NaN and Inf are painted in this colour in every picture of the report: no shader output can be
// told apart from it by eye in a lit scene, and it is far from every magma and diverging colour.
constexpr float kNonFiniteColor[3] = {1.0f, 0.0f, 1.0f};

struct SignedDifferenceConfig {
    // Difference of luminance (test - reference, display values 0..1) that gets the full colour;
    // smaller ones blend linearly toward the neutral ghost. 0.25 is 64 of 255 levels, five times
    // the default per-pixel tolerance: small tolerated differences stay faint.
    float full_scale = 0.25f;
    float brighter_color[3] = {0.90f, 0.38f, 0.00f};  // orange: the student's pixel is too bright
    float darker_color[3] = {0.05f, 0.35f, 0.85f};    // blue: too dark (the pair reads for red-green
                                                      // colour blindness too)
};

// Where the test image is brighter or darker than the reference: each pixel is a light grey
// ghost of the reference's luminance (so the shapes stay recognisable), tinted toward
// brighter_color or darker_color by |luminance difference| / full_scale (clamped to 1).
// Luminance is Rec. 709 (0.2126 R + 0.7152 G + 0.0722 B) of values clamped to 0..1 (a
// 1-channel image is grey). Pixels that are NaN or Inf in the test image are kNonFiniteColor.
// RGB; empty when the sizes differ.
Image signedDifference(const Image& reference, const Image& test, const SignedDifferenceConfig& config = {});

// `image` as a picture (values clamped to 0..1, the channel count kept), with every pixel that is
// NaN or Inf in a colour channel painted kNonFiniteColor (alpha 1). `painted`, when given,
// receives how many pixels were painted.
Image markNonFinite(const Image& image, std::size_t* painted = nullptr);

// A `size` x `size` window (smaller when the image is) centred on (cx, cy), moved inside the image.
PixelBox windowAround(int cx, int cy, int size, int width, int height);

// The pixels of `box` (clipped to the image) enlarged `factor` times by repeating each pixel
// (nearest neighbour, so single wrong pixels stay sharp), RGB (grey repeated for 1 channel).
// Empty when the box misses the image or factor < 1.
Image cropZoom(const Image& image, const PixelBox& box, int factor);

// Images next to each other, top-aligned, with `gap` columns of grey `gap_value` between them
// (and below a shorter one), RGB.
Image sideBySide(const std::vector<Image>& images, int gap = 4, float gap_value = 0.5f);

// Every `factor` x `factor` block averaged into one pixel (the last partial row and column are
// averaged over what they have), channels kept. NaN and Inf are averaged as 0 so that one broken
// pixel does not erase a block; factor 1 returns the image.
Image downsample(const Image& image, int factor);

// A mask brought to a downsampled image's size: a block counts when any pixel of it counts.
Mask downsample(const Mask& mask, int factor);

// How close a student's picture is to a known mistake's picture of the same scene, compared to
// how close it is to the reference. All three are pictures as the report shows them (display
// values); the hint is stored `factor` times smaller in 8 bits, and the other two are brought to
// its size with downsample() and rounded to 8 bits first (so the same picture compares as
// identical). PSNR over the RGB of the blocks where `graded` (full size; empty: all) counts a
// pixel. A hint matches when psnr_to_hint_db >= min_psnr_db and it is above psnr_to_reference_db:
// the student's image is near the mistake, and nearer to it than to the right answer.
struct HintComparison {
    bool comparable = false;  // sizes agree
    double psnr_to_hint_db = 0.0;
    double psnr_to_reference_db = 0.0;
    bool matches = false;
};
HintComparison compareWithHint(const Image& test, const Image& reference, const Image& hint,
                               const Mask& graded, int factor, double min_psnr_db = 40.0);

}  // namespace grader
