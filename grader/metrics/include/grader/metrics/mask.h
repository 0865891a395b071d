// Pixel masks and pixel rectangles shared by the metrics and the comparator. A mask says which
// pixels a metric counts (e.g. only the pixels an object covers); it holds no image data.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace grader {

// One flag per pixel, row-major, top row first (same order as grader::Image): 1 = the pixel
// counts, 0 = it is ignored. Any non-zero value counts as 1.
struct Mask {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> values;

    Mask() = default;
    Mask(int w, int h, std::uint8_t fill = 1)
        : width(w), height(h), values(static_cast<std::size_t>(w) * h, fill) {}

    bool empty() const { return values.empty(); }
    std::size_t index(int x, int y) const { return static_cast<std::size_t>(y) * width + x; }
    std::uint8_t& at(int x, int y) { return values[index(x, y)]; }
    std::uint8_t at(int x, int y) const { return values[index(x, y)]; }
    // Number of pixels that count.
    std::size_t count() const {
        std::size_t n = 0;
        for (std::uint8_t v : values) n += (v != 0);
        return n;
    }
};

struct PixelPosition {
    int x = 0;
    int y = 0;
};

// Inclusive pixel rectangle [x0, x1] x [y0, y1]; empty when x1 < x0 (the default).
struct PixelBox {
    int x0 = 0;
    int y0 = 0;
    int x1 = -1;
    int y1 = -1;

    bool empty() const { return x1 < x0 || y1 < y0; }
    int width() const { return empty() ? 0 : x1 - x0 + 1; }
    int height() const { return empty() ? 0 : y1 - y0 + 1; }
    // Grows the box so that it contains (x, y).
    void include(int x, int y) {
        if (empty()) {
            x0 = x1 = x;
            y0 = y1 = y;
            return;
        }
        if (x < x0) x0 = x;
        if (x > x1) x1 = x;
        if (y < y0) y0 = y;
        if (y > y1) y1 = y;
    }
};

}  // namespace grader
