// Error map -> colour picture (see grader/heatmap.h). The colour maps are piecewise linear
// through 17 evenly spaced control points sampled from matplotlib's magma and viridis
// (van der Walt & Smith, 2015), which are perceptually uniform: equal steps in error look like
// equal steps in colour, and lightness rises monotonically, so the picture also reads in grey.
#include "grader/metrics/heatmap.h"

#include <algorithm>
#include <cmath>

namespace grader {
namespace {

constexpr int kControlPoints = 17;

// magma(i / 16), i = 0..16 (sRGB values, display-referred).
constexpr float kMagma[kControlPoints][3] = {
    {0.001462f, 0.000466f, 0.013866f}, {0.039608f, 0.031090f, 0.133515f}, {0.113094f, 0.065492f, 0.276784f},
    {0.211718f, 0.061992f, 0.418647f}, {0.316654f, 0.071690f, 0.485380f}, {0.414709f, 0.110431f, 0.504662f},
    {0.512831f, 0.148179f, 0.507648f}, {0.613617f, 0.181811f, 0.498536f}, {0.716387f, 0.214982f, 0.475290f},
    {0.816914f, 0.255895f, 0.436461f}, {0.904281f, 0.319610f, 0.388137f}, {0.960949f, 0.418323f, 0.359630f},
    {0.986700f, 0.535582f, 0.382210f}, {0.996096f, 0.653659f, 0.446213f}, {0.996898f, 0.769591f, 0.534892f},
    {0.992440f, 0.884330f, 0.640099f}, {0.987053f, 0.991438f, 0.749504f},
};

// viridis(i / 16), i = 0..16.
constexpr float kViridis[kControlPoints][3] = {
    {0.267004f, 0.004874f, 0.329415f}, {0.282327f, 0.094955f, 0.417331f}, {0.278826f, 0.175490f, 0.483397f},
    {0.258965f, 0.251537f, 0.524736f}, {0.229739f, 0.322361f, 0.545706f}, {0.199430f, 0.387607f, 0.554642f},
    {0.172719f, 0.448791f, 0.557885f}, {0.149039f, 0.508051f, 0.557250f}, {0.127568f, 0.566949f, 0.550556f},
    {0.120638f, 0.625828f, 0.533488f}, {0.157851f, 0.683765f, 0.501686f}, {0.246070f, 0.738910f, 0.452024f},
    {0.369214f, 0.788888f, 0.382914f}, {0.515992f, 0.831158f, 0.294279f}, {0.678489f, 0.863742f, 0.189503f},
    {0.845561f, 0.887322f, 0.099702f}, {0.993248f, 0.906157f, 0.143936f},
};

}  // namespace

void colormapLookup(Colormap colormap, float t, float rgb[3]) {
    const float(*table)[3] = colormap == Colormap::Viridis ? kViridis : kMagma;
    const float clamped = t > 0.0f ? std::min(t, 1.0f) : 0.0f;  // NaN -> 0
    const float position = clamped * (kControlPoints - 1);
    const int lower = std::min(static_cast<int>(position), kControlPoints - 2);
    const float blend = position - static_cast<float>(lower);
    for (int c = 0; c < 3; ++c) rgb[c] = table[lower][c] + blend * (table[lower + 1][c] - table[lower][c]);
}

Image diffHeatmap(const std::vector<float>& error_map, int width, int height, const HeatmapConfig& config) {
    if (width <= 0 || height <= 0 || error_map.size() != static_cast<std::size_t>(width) * height) return {};
    const Mask* outline = config.outline;
    if (outline != nullptr && (outline->width != width || outline->height != height ||
                               outline->values.size() != error_map.size())) {
        return {};
    }
    const float scale = config.max_error > 0.0f ? 1.0f / config.max_error : 1.0f;

    Image picture(width, height, 3);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const float e = error_map[static_cast<std::size_t>(y) * width + x];
            float* out = &picture.at(x, y, 0);
            if (std::isnan(e)) {
                std::copy(config.nan_color, config.nan_color + 3, out);
            } else {
                colormapLookup(config.colormap, e * scale, out);
            }
        }
    }
    if (outline == nullptr) return picture;

    // Ring: pixels that are not mismatches but touch one (8-neighbourhood), so the outline
    // hugs each region from outside and leaves the region's own error colours visible.
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            if (outline->at(x, y)) continue;
            bool touches = false;
            for (int dy = -1; dy <= 1 && !touches; ++dy) {
                for (int dx = -1; dx <= 1 && !touches; ++dx) {
                    const int nx = x + dx, ny = y + dy;
                    touches = nx >= 0 && ny >= 0 && nx < width && ny < height && outline->at(nx, ny);
                }
            }
            if (touches) std::copy(config.outline_color, config.outline_color + 3, &picture.at(x, y, 0));
        }
    }
    return picture;
}

Image diffHeatmap(const FlipResult& flip, const HeatmapConfig& config) {
    return diffHeatmap(flip.error_map, flip.width, flip.height, config);
}

}  // namespace grader
