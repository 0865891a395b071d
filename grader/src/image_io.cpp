// PNG input/output for grader::Image through stb_image / stb_image_write (Debian's libstb).
#include <stb_image.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "grader/image.h"

namespace grader {

bool writePng(const Image& image, const std::string& path, std::string* error) {
    if (image.width <= 0 || image.height <= 0 || image.channels < 1 || image.channels > 4 ||
        image.pixels.size() != static_cast<std::size_t>(image.width) * image.height * image.channels) {
        if (error) *error = path + ": image has inconsistent size, not written";
        return false;
    }
    std::vector<std::uint8_t> bytes(image.pixels.size());
    for (std::size_t i = 0; i < bytes.size(); ++i) {
        float v = image.pixels[i];
        if (std::isnan(v)) v = 0.0f;
        v = std::clamp(v, 0.0f, 1.0f);
        bytes[i] = static_cast<std::uint8_t>(std::lround(v * 255.0f));
    }
    if (!stbi_write_png(path.c_str(), image.width, image.height, image.channels, bytes.data(),
                        image.width * image.channels)) {
        if (error) *error = path + ": cannot write PNG (folder missing or not writable?)";
        return false;
    }
    return true;
}

bool readPng(const std::string& path, Image* image, std::string* error) {
    int w = 0, h = 0, c = 0;
    const bool sixteen = stbi_is_16_bit(path.c_str());
    if (!stbi_info(path.c_str(), &w, &h, &c)) {
        if (error) *error = path + ": not a readable image (" + stbi_failure_reason() + ")";
        return false;
    }
    const int want = (c == 2) ? 4 : c;  // grey+alpha is expanded to RGBA
    Image out(w, h, want);
    if (sixteen) {
        stbi_us* data = stbi_load_16(path.c_str(), &w, &h, &c, want);
        if (!data) {
            if (error) *error = path + ": cannot decode (" + stbi_failure_reason() + ")";
            return false;
        }
        for (std::size_t i = 0; i < out.pixels.size(); ++i) out.pixels[i] = data[i] / 65535.0f;
        stbi_image_free(data);
    } else {
        stbi_uc* data = stbi_load(path.c_str(), &w, &h, &c, want);
        if (!data) {
            if (error) *error = path + ": cannot decode (" + stbi_failure_reason() + ")";
            return false;
        }
        for (std::size_t i = 0; i < out.pixels.size(); ++i) out.pixels[i] = data[i] / 255.0f;
        stbi_image_free(data);
    }
    *image = std::move(out);
    return true;
}

}  // namespace grader
