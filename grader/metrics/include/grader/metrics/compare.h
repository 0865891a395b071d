// Shift-tolerant per-pixel comparison of a test image against a reference, and the coverage
// masks that restrict grading to the pixels an object covers. This answers "which pixels are
// wrong, and where is it worst"; it does not compute perceptual metrics (metrics.h) or draw
// anything (heatmap.h).
//
// The idea is the one behind dEQP's position-deviation and bilinear compares (VK-GL-CTS,
// framework/common/tcuImageCompare.cpp, e.g. intThresholdPositionDeviationCompare): two
// correct rasterisers may place an edge one pixel apart, so a pixel is only an error when no
// pixel near it in the other image has a close enough colour.
#pragma once

#include <cstddef>
#include <string>

#include "grader/metrics/image.h"
#include "grader/metrics/mask.h"

namespace grader {

struct ToleranceCompareConfig {
    // A pixel p of image A is matched by image B when some pixel q of B with
    // |q.x - p.x| <= search_radius and |q.y - p.y| <= search_radius satisfies
    // max over R, G, B of |A(p) - B(q)| <= tolerance. Radius 1 is a 3x3 neighbourhood.
    float tolerance = 0.05f;
    int search_radius = 1;
    // Pixels counted (nullptr: all). Neighbours are searched in the whole image regardless:
    // an edge shifted out of the mask still matches.
    const Mask* mask = nullptr;
    // Side of the square window used to find the worst region.
    int tile_size = 16;
};

// Where mismatches concentrate most: the tile_size x tile_size window holding the most
// mismatching pixels, moved so that it is centred on those mismatches.
struct WorstRegion {
    PixelBox tile;                   // the window, clipped to the image (empty if no mismatch)
    PixelPosition centre;            // centre of the window
    PixelBox mismatch_bounds;        // bounding box of the mismatching pixels inside the window
    std::size_t mismatch_count = 0;  // mismatching pixels inside the window
};

struct ToleranceCompareResult {
    bool ok = false;
    std::string error;
    std::size_t compared_count = 0;  // pixels counted (mask size, or width * height)
    std::size_t mismatch_count = 0;
    double mismatch_fraction = 0.0;  // mismatch_count / compared_count (0 if none compared)
    // 1 where a counted pixel mismatches. A pixel mismatches when it fails in either
    // direction: the reference pixel has no match in the test image, or the test pixel has no
    // match in the reference. Checking both catches a missing object as well as an extra one.
    // Pixels with NaN in R, G or B never match.
    Mask mismatches;
    PixelBox mismatch_bounds;  // bounding box of all mismatches (empty if none)
    WorstRegion worst;
};

ToleranceCompareResult compareShiftTolerant(const Image& reference, const Image& test,
                                            const ToleranceCompareConfig& config = {});

// Coverage from alpha: a pixel is covered when its alpha is > threshold in either image (the
// reference draws it or the student draws it; both kinds of pixel must be graded). Alpha is
// channel 4 of a 4-channel image; an image without alpha covers every pixel. NaN alpha counts
// as covered, so that the comparison sees the broken pixel. Images must be the same size;
// otherwise the result is an empty Mask.
Mask coverageFromAlpha(const Image& reference, const Image& test, float threshold = 0.0f);

// Coverage from separate coverage renders (e.g. the object drawn flat white on black): a pixel
// is covered when the largest colour channel (R, G, B; alpha is ignored, an opaque render has
// alpha 1 everywhere) of either coverage image is > threshold (NaN counts as covered). Images must be the
// same size; otherwise the result is an empty Mask.
Mask coverageFromImages(const Image& reference_coverage, const Image& test_coverage, float threshold = 0.0f);

}  // namespace grader
