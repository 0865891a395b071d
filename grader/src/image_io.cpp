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
    // The header first: a tiny file may claim billions of pixels.
    if (!stbi_info(path.c_str(), &w, &h, &c)) {
        if (error) *error = path + ": not a readable image (" + stbi_failure_reason() + ")";
        return false;
    }
    if (static_cast<std::size_t>(w) * static_cast<std::size_t>(h) > kMaxImagePixels) {
        if (error)
            *error = path + ": " + std::to_string(w) + "x" + std::to_string(h) +
                     " pixels is more than the limit of " + std::to_string(kMaxImagePixels) + " (4096x4096)";
        return false;
    }
    const bool sixteen = stbi_is_16_bit(path.c_str());
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

bool writeHdr(const Image& image, const std::string& path, std::string* error) {
    if (image.width <= 0 || image.height <= 0 || image.channels < 3 ||
        image.pixels.size() != static_cast<std::size_t>(image.width) * image.height * image.channels) {
        if (error) *error = path + ": image has inconsistent size, not written";
        return false;
    }
    std::vector<float> rgb(static_cast<std::size_t>(image.width) * image.height * 3);
    for (std::size_t p = 0, q = 0; q < rgb.size(); p += static_cast<std::size_t>(image.channels), q += 3)
        for (int k = 0; k < 3; ++k) {
            const float v = image.pixels[p + static_cast<std::size_t>(k)];
            rgb[q + static_cast<std::size_t>(k)] = std::isfinite(v) && v > 0.0f ? v : 0.0f;
        }
    if (!stbi_write_hdr(path.c_str(), image.width, image.height, 3, rgb.data())) {
        if (error) *error = path + ": cannot write HDR (folder missing or not writable?)";
        return false;
    }
    return true;
}

bool readHdr(const std::string& path, Image* image, std::string* error) {
    int w = 0, h = 0, c = 0;
    if (!stbi_info(path.c_str(), &w, &h, &c) || !stbi_is_hdr(path.c_str())) {
        if (error) *error = path + ": not a readable Radiance HDR image";
        return false;
    }
    if (static_cast<std::size_t>(w) * static_cast<std::size_t>(h) > kMaxImagePixels) {
        if (error) *error = path + ": " + std::to_string(w) + "x" + std::to_string(h) + " pixels is too many";
        return false;
    }
    float* data = stbi_loadf(path.c_str(), &w, &h, &c, 4);
    if (!data) {
        if (error) *error = path + ": cannot decode (" + stbi_failure_reason() + ")";
        return false;
    }
    Image out(w, h, 4);
    std::copy_n(data, out.pixels.size(), out.pixels.begin());
    stbi_image_free(data);
    *image = std::move(out);
    return true;
}

}  // namespace grader
