// Synthetic images for the grader tests: constants, discs, gradients and deterministic noise.
// Only generators; no expectations live here.
#pragma once

#include <cmath>
#include <cstdint>

#include "grader/metrics/image.h"

namespace grader::test {

// Every pixel (r, g, b[, a]).
inline Image constantImage(int width, int height, float r, float g, float b, int channels = 3,
                           float a = 1.0f) {
    Image image(width, height, channels);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const float values[4] = {r, g, b, a};
            if (channels == 1) {
                image.at(x, y, 0) = r;
                continue;
            }
            for (int c = 0; c < channels; ++c) image.at(x, y, c) = values[c];
        }
    }
    return image;
}

inline Image greyImage(int width, int height, float value, int channels = 3) {
    return constantImage(width, height, value, value, value, channels);
}

// A disc of `inside` colour (radius r, centre (cx, cy), pixel centres tested) on `outside`.
inline Image discImage(int width, int height, float cx, float cy, float r, const float inside[3],
                       const float outside[3]) {
    Image image(width, height, 3);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const float dx = x + 0.5f - cx, dy = y + 0.5f - cy;
            const float* colour = dx * dx + dy * dy <= r * r ? inside : outside;
            for (int c = 0; c < 3; ++c) image.at(x, y, c) = colour[c];
        }
    }
    return image;
}

// Deterministic uniform numbers in [0, 1), the same on every platform.
class Lcg {
  public:
    explicit Lcg(std::uint32_t seed) : state_(seed) {}
    float next() {
        state_ = state_ * 1664525u + 1013904223u;
        return static_cast<float>(state_ >> 8) / 16777216.0f;
    }

  private:
    std::uint32_t state_;
};

// `image` plus uniform noise in [-amplitude, amplitude] on R, G, B, clamped to [0, 1].
inline Image withNoise(const Image& image, float amplitude, std::uint32_t seed) {
    Image out = image;
    Lcg random(seed);
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            for (int c = 0; c < (image.channels >= 3 ? 3 : 1); ++c) {
                const float v = image.at(x, y, c) + amplitude * (2.0f * random.next() - 1.0f);
                out.at(x, y, c) = v < 0.0f ? 0.0f : (v > 1.0f ? 1.0f : v);
            }
        }
    }
    return out;
}

// A smooth colour pattern with some structure (used where a "natural" image is wanted).
inline Image patternImage(int width, int height, double phase = 0.0) {
    Image image(width, height, 3);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            for (int c = 0; c < 3; ++c) {
                const double v = 0.5 + 0.3 * std::sin(0.37 * x + 0.11 * y * (c + 1) + phase) +
                                 0.1 * std::cos(0.05 * x * y + c);
                image.at(x, y, c) = static_cast<float>(v);
            }
        }
    }
    return image;
}

}  // namespace grader::test
