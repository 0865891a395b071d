// Heat map: colour map values at the control points, monotone lightness, NaN colour, the
// outline ring, size checks.
#include "grader/metrics/heatmap.h"

#include <gtest/gtest.h>

#include <limits>
#include <vector>

namespace grader {
namespace {

float luminance(const float rgb[3]) { return 0.2126f * rgb[0] + 0.7152f * rgb[1] + 0.0722f * rgb[2]; }

TEST(Heatmap, MagmaAtItsControlPoints) {
    float rgb[3];
    colormapLookup(Colormap::Magma, 0.0f, rgb);  // matplotlib's magma(0)
    EXPECT_NEAR(rgb[0], 0.001462f, 1e-6f);
    EXPECT_NEAR(rgb[2], 0.013866f, 1e-6f);
    colormapLookup(Colormap::Magma, 0.5f, rgb);  // magma(0.5)
    EXPECT_NEAR(rgb[0], 0.716387f, 1e-6f);
    EXPECT_NEAR(rgb[1], 0.214982f, 1e-6f);
    EXPECT_NEAR(rgb[2], 0.475290f, 1e-6f);
    colormapLookup(Colormap::Magma, 1.0f, rgb);  // magma(1)
    EXPECT_NEAR(rgb[0], 0.987053f, 1e-6f);
    EXPECT_NEAR(rgb[1], 0.991438f, 1e-6f);
    EXPECT_NEAR(rgb[2], 0.749504f, 1e-6f);
    // Halfway between magma(0.5) and magma(0.5625): the average of the two.
    colormapLookup(Colormap::Magma, 0.53125f, rgb);
    EXPECT_NEAR(rgb[0], 0.5f * (0.716387f + 0.816914f), 1e-6f);
    // Out of range clamps; NaN takes the bottom colour.
    float clamped[3];
    colormapLookup(Colormap::Magma, 7.0f, clamped);
    EXPECT_NEAR(clamped[1], 0.991438f, 1e-6f);
    colormapLookup(Colormap::Magma, std::numeric_limits<float>::quiet_NaN(), clamped);
    EXPECT_NEAR(clamped[0], 0.001462f, 1e-6f);
}

TEST(Heatmap, ViridisEnds) {
    float rgb[3];
    colormapLookup(Colormap::Viridis, 0.0f, rgb);
    EXPECT_NEAR(rgb[0], 0.267004f, 1e-6f);
    colormapLookup(Colormap::Viridis, 1.0f, rgb);
    EXPECT_NEAR(rgb[1], 0.906157f, 1e-6f);
}

TEST(Heatmap, LightnessRisesMonotonically) {
    // What makes the maps readable in grey too: more error, brighter.
    for (Colormap map : {Colormap::Magma, Colormap::Viridis}) {
        float previous = -1.0f;
        for (int i = 0; i <= 100; ++i) {
            float rgb[3];
            colormapLookup(map, i / 100.0f, rgb);
            EXPECT_GT(luminance(rgb), previous) << i;
            previous = luminance(rgb);
        }
    }
}

TEST(Heatmap, PaintsErrorsNaNAndOutline) {
    const int width = 9, height = 7;
    std::vector<float> errors(width * height, 0.0f);
    errors[3 * width + 4] = 1.0f;  // the mismatching pixel (4, 3)
    errors[0] = std::numeric_limits<float>::quiet_NaN();
    Mask mismatches(width, height, 0);
    mismatches.at(4, 3) = 1;
    HeatmapConfig config;
    config.outline = &mismatches;
    const Image picture = diffHeatmap(errors, width, height, config);
    ASSERT_EQ(picture.width, width);
    ASSERT_EQ(picture.height, height);
    ASSERT_EQ(picture.channels, 3);

    float top[3], bottom[3];
    colormapLookup(Colormap::Magma, 1.0f, top);
    colormapLookup(Colormap::Magma, 0.0f, bottom);
    // The mismatching pixel keeps its error colour; its 8 neighbours form the ring.
    for (int c = 0; c < 3; ++c) EXPECT_EQ(picture.at(4, 3, c), top[c]);
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            if (dx == 0 && dy == 0) continue;
            for (int c = 0; c < 3; ++c) EXPECT_EQ(picture.at(4 + dx, 3 + dy, c), config.outline_color[c]);
        }
    }
    // Farther away: the colour of zero error. NaN: the NaN colour.
    for (int c = 0; c < 3; ++c) EXPECT_EQ(picture.at(8, 6, c), bottom[c]);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(picture.at(0, 0, c), config.nan_color[c]);
}

TEST(Heatmap, MaxErrorScalesTheMap) {
    const std::vector<float> errors = {0.25f};
    HeatmapConfig config;
    config.max_error = 0.25f;
    float top[3];
    colormapLookup(Colormap::Magma, 1.0f, top);
    const Image picture = diffHeatmap(errors, 1, 1, config);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(picture.at(0, 0, c), top[c], 1e-6f);
}

TEST(Heatmap, FromFlipResultAndSizeChecks) {
    FlipResult flip;
    flip.width = 2;
    flip.height = 2;
    flip.error_map = {0.0f, 0.5f, 1.0f, 0.25f};
    EXPECT_EQ(diffHeatmap(flip).pixels.size(), 12u);
    EXPECT_TRUE(diffHeatmap(std::vector<float>(3, 0.0f), 2, 2).empty());
    Mask wrong(3, 3, 0);
    HeatmapConfig config;
    config.outline = &wrong;
    EXPECT_TRUE(diffHeatmap(flip, config).empty());
}

}  // namespace
}  // namespace grader
