// A float image in memory and its PNG input/output. No OpenGL here: the grader library takes
// images in and gives result structs out.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace grader {

// Row-major, top row first (as in PNG), channels interleaved. Values are display-referred:
// 0..1 maps to PNG 0..255 with no transfer function applied (docs/grading.md, colour space).
// Values may be NaN, Inf or out of range when they come from a float render target.
struct Image {
    int width = 0;
    int height = 0;
    int channels = 4;  // 1, 3 or 4
    std::vector<float> pixels;

    Image() = default;
    Image(int w, int h, int c, float fill = 0.0f)
        : width(w), height(h), channels(c), pixels(static_cast<std::size_t>(w) * h * c, fill) {}

    bool empty() const { return pixels.empty(); }
    std::size_t index(int x, int y, int c = 0) const {
        return (static_cast<std::size_t>(y) * width + x) * channels + c;
    }
    float& at(int x, int y, int c = 0) { return pixels[index(x, y, c)]; }
    float at(int x, int y, int c = 0) const { return pixels[index(x, y, c)]; }
};

// Images larger than this are refused before any pixel is decoded (a 74-byte PNG can claim
// 16000x16000 pixels).
constexpr std::size_t kMaxImagePixels = std::size_t{4096} * 4096;

// Writes 8-bit PNG: each channel clamped to [0,1], NaN written as 0, scaled by 255 and rounded.
bool writePng(const Image& image, const std::string& path, std::string* error);
// The same PNG, in memory (for pictures served over HTTP).
bool encodePng(const Image& image, std::vector<std::uint8_t>* out, std::string* error);
// Reads an 8-bit or 16-bit PNG into [0,1] floats, keeping its channel count (grey+alpha becomes 4).
bool readPng(const std::string& path, Image* image, std::string* error);
// Radiance RGBE (.hdr), for float images with values above 1: RGB kept to 8-bit mantissas with a
// shared exponent; NaN, Inf and negative values are written as 0. Read back as RGBA, alpha 1.
bool writeHdr(const Image& image, const std::string& path, std::string* error);
bool readHdr(const std::string& path, Image* image, std::string* error);

// The image as it would read back from its stored golden: writePng then readPng (display range),
// or writeHdr then readHdr (hdr range), without a file. Pass isolation gives a pass the reference's
// images this way, so a grade that renders the reference and one that reads the goldens feed it
// the same values.
void quantizeAsStored(Image* image, bool hdr);

}  // namespace grader
