// Turns a per-pixel error map (FLIP's) into an RGB picture a student can read: the error goes
// through a perceptually uniform colour map, and mismatching pixels from the shift-tolerant
// comparison can be outlined. Pure image-to-image; writing the PNG is writePng's job.
#pragma once

#include <vector>

#include "grader/metrics/image.h"
#include "grader/metrics/mask.h"
#include "grader/metrics/metrics.h"

namespace grader {

enum class Colormap {
    Magma,    // black -> purple -> orange -> pale yellow (what the FLIP tool shows)
    Viridis,  // dark blue -> green -> yellow
};

struct HeatmapConfig {
    Colormap colormap = Colormap::Magma;
    // Error that maps to the top of the colour map; errors above it saturate. FLIP errors are
    // already in [0, 1].
    float max_error = 1.0f;
    // When set (same size as the map), pixels next to a mismatching pixel (8-neighbourhood),
    // but not mismatching themselves, are painted outline_color: a 1-pixel ring around each
    // mismatching region, whose own pixels keep their error colour. Typically
    // ToleranceCompareResult::mismatches.
    const Mask* outline = nullptr;
    float outline_color[3] = {0.0f, 1.0f, 1.0f};  // cyan: far from every magma colour
    // Colour of NaN errors, which have no place on the scale.
    float nan_color[3] = {0.0f, 1.0f, 0.0f};
};

// RGB image (3 channels, display-referred like every grader::Image) of `error_map`
// (width * height values, row-major). Returns an empty Image if the sizes disagree.
Image diffHeatmap(const std::vector<float>& error_map, int width, int height,
                  const HeatmapConfig& config = {});

// Same, from a FLIP result's error map.
Image diffHeatmap(const FlipResult& flip, const HeatmapConfig& config = {});

// Colour of `t` in [0, 1] (clamped; NaN counts as 0) under `colormap`, display-referred RGB:
// linear interpolation between 17 evenly spaced samples of matplotlib's map.
void colormapLookup(Colormap colormap, float t, float rgb[3]);

}  // namespace grader
