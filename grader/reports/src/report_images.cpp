// The report's pictures and the known-mistake comparison; see grader/report_images.h.
#include "grader/reports/report_images.h"

#include <algorithm>
#include <cmath>

#include "grader/metrics/metrics.h"
#include "grader/metrics/scoring.h"

namespace grader {

namespace {

float clamp01(float v) { return std::isnan(v) ? 0.0f : std::fmin(std::fmax(v, 0.0f), 1.0f); }

// Colour channel c of pixel (x, y); a grey image answers every colour from its one channel.
float colour(const Image& image, int x, int y, int c) { return image.at(x, y, image.channels >= 3 ? c : 0); }

bool nonFinite(const Image& image, int x, int y) {
    for (int c = 0; c < std::min(image.channels, 3); ++c)
        if (!std::isfinite(image.at(x, y, c))) return true;
    return false;
}

float luminance(const Image& image, int x, int y) {
    return 0.2126f * clamp01(colour(image, x, y, 0)) + 0.7152f * clamp01(colour(image, x, y, 1)) +
           0.0722f * clamp01(colour(image, x, y, 2));
}

bool usable(const Image& image) {
    return image.width > 0 && image.height > 0 && image.channels >= 1 &&
           image.pixels.size() == static_cast<std::size_t>(image.width) * image.height * image.channels;
}

}  // namespace

Image signedDifference(const Image& reference, const Image& test, const SignedDifferenceConfig& config) {
    if (!usable(reference) || !usable(test) || reference.width != test.width ||
        reference.height != test.height)
        return {};
    const float scale = config.full_scale > 0.0f ? 1.0f / config.full_scale : 1.0f;
    Image out(test.width, test.height, 3);
    for (int y = 0; y < test.height; ++y) {
        for (int x = 0; x < test.width; ++x) {
            float* o = &out.at(x, y, 0);
            if (nonFinite(test, x, y)) {
                std::copy(kNonFiniteColor, kNonFiniteColor + 3, o);
                continue;
            }
            const float ref = luminance(reference, x, y);
            const float d = luminance(test, x, y) - ref;
            // A light ghost (0.78..0.96) keeps the objects recognisable without competing with
            // the colours.
            const float ghost = 0.78f + 0.18f * ref;
            const float t = std::fmin(std::fabs(d) * scale, 1.0f);
            const float* tint = d > 0.0f ? config.brighter_color : config.darker_color;
            for (int c = 0; c < 3; ++c) o[c] = ghost + t * (tint[c] - ghost);
        }
    }
    return out;
}

Image markNonFinite(const Image& image, std::size_t* painted) {
    Image out = image;
    std::size_t n = 0;
    if (!usable(image)) {
        if (painted) *painted = 0;
        return out;
    }
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            const bool broken = nonFinite(image, x, y);
            n += broken;
            for (int c = 0; c < image.channels; ++c) {
                float& v = out.at(x, y, c);
                if (!broken)
                    v = clamp01(v);
                else if (image.channels == 1)
                    v = 1.0f;  // grey has no magenta: the brightest value
                else
                    v = c < 3 ? kNonFiniteColor[c] : 1.0f;
            }
        }
    }
    if (painted) *painted = n;
    return out;
}

PixelBox windowAround(int cx, int cy, int size, int width, int height) {
    PixelBox b;
    if (width <= 0 || height <= 0 || size <= 0) return b;
    const int w = std::min(size, width), h = std::min(size, height);
    b.x0 = std::clamp(cx - w / 2, 0, width - w);
    b.y0 = std::clamp(cy - h / 2, 0, height - h);
    b.x1 = b.x0 + w - 1;
    b.y1 = b.y0 + h - 1;
    return b;
}

Image cropZoom(const Image& image, const PixelBox& box, int factor) {
    if (!usable(image) || factor < 1 || box.empty()) return {};
    const int x0 = std::max(box.x0, 0), y0 = std::max(box.y0, 0);
    const int x1 = std::min(box.x1, image.width - 1), y1 = std::min(box.y1, image.height - 1);
    if (x1 < x0 || y1 < y0) return {};
    Image out((x1 - x0 + 1) * factor, (y1 - y0 + 1) * factor, 3);
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < out.width; ++x)
            for (int c = 0; c < 3; ++c) out.at(x, y, c) = colour(image, x0 + x / factor, y0 + y / factor, c);
    return out;
}

Image sideBySide(const std::vector<Image>& images, int gap, float gap_value) {
    int width = 0, height = 0, placed = 0;
    for (const Image& im : images) {
        if (!usable(im)) continue;
        width += im.width + (placed++ > 0 ? gap : 0);
        height = std::max(height, im.height);
    }
    if (placed == 0) return {};
    Image out(width, height, 3, gap_value);
    int left = 0;
    for (const Image& im : images) {
        if (!usable(im)) continue;
        for (int y = 0; y < im.height; ++y)
            for (int x = 0; x < im.width; ++x)
                for (int c = 0; c < 3; ++c) out.at(left + x, y, c) = colour(im, x, y, c);
        left += im.width + gap;
    }
    return out;
}

Image downsample(const Image& image, int factor) {
    if (factor <= 1 || !usable(image)) return image;
    const int w = (image.width + factor - 1) / factor, h = (image.height + factor - 1) / factor;
    Image out(w, h, image.channels);
    for (int by = 0; by < h; ++by) {
        for (int bx = 0; bx < w; ++bx) {
            const int x1 = std::min((bx + 1) * factor, image.width),
                      y1 = std::min((by + 1) * factor, image.height);
            const int count = (x1 - bx * factor) * (y1 - by * factor);
            for (int c = 0; c < image.channels; ++c) {
                double sum = 0.0;
                for (int y = by * factor; y < y1; ++y)
                    for (int x = bx * factor; x < x1; ++x) {
                        const float v = image.at(x, y, c);
                        sum += std::isfinite(v) ? v : 0.0f;
                    }
                out.at(bx, by, c) = static_cast<float>(sum / count);
            }
        }
    }
    return out;
}

Mask downsample(const Mask& mask, int factor) {
    if (factor <= 1 || mask.empty()) return mask;
    Mask out((mask.width + factor - 1) / factor, (mask.height + factor - 1) / factor, 0);
    for (int y = 0; y < mask.height; ++y)
        for (int x = 0; x < mask.width; ++x)
            if (mask.at(x, y)) out.at(x / factor, y / factor) = 1;
    return out;
}

HintComparison compareWithHint(const Image& test, const Image& reference, const Image& hint,
                               const Mask& graded, int factor, double min_psnr_db) {
    HintComparison r;
    if (!usable(test) || !usable(reference) || !usable(hint) || test.width != reference.width ||
        test.height != reference.height || factor < 1)
        return r;
    // Rounded to the 8 bits the stored hint has, so that the same picture compares as identical.
    const Image small_test = quantise8(downsample(test, factor));
    const Image small_reference = quantise8(downsample(reference, factor));
    if (small_test.width != hint.width || small_test.height != hint.height) return r;
    const Mask small_mask = graded.width == test.width && graded.height == test.height
                                ? downsample(graded, factor)
                                : Mask(hint.width, hint.height, 1);
    PsnrConfig pc;
    pc.mask = small_mask.count() > 0 ? &small_mask : nullptr;
    const PsnrResult to_hint = computePsnr(hint, small_test, pc);
    const PsnrResult to_reference = computePsnr(small_reference, small_test, pc);
    if (!to_hint.ok || !to_reference.ok) return r;
    r.comparable = true;
    r.psnr_to_hint_db = to_hint.psnr_db;
    r.psnr_to_reference_db = to_reference.psnr_db;
    r.matches = r.psnr_to_hint_db >= min_psnr_db && r.psnr_to_hint_db > r.psnr_to_reference_db;
    return r;
}

}  // namespace grader
