// PNG input/output for grader::Image: written with libpng, read with stb_image (Debian's libpng
// and libstb); Radiance .hdr through stb_image / stb_image_write.
#include <png.h>
#include <stb_image.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <csetjmp>
#include <cstdint>
#include <cstdio>
#include <vector>

#include "grader/base/atomic_file.h"
#include "grader/metrics/image.h"

namespace grader {

namespace {

// libpng's own error handler longjmps; this one records the message and does the same.
struct PngWriteState {
    std::jmp_buf jump;
    std::string message;
};

void pngError(png_structp png, png_const_charp message) {
    auto* state = static_cast<PngWriteState*>(png_get_error_ptr(png));
    state->message = message ? message : "libpng error";
    std::longjmp(state->jump, 1);
}

void pngWarning(png_structp, png_const_charp) {}

void pngWriteBytes(png_structp png, png_bytep data, png_size_t n) {
    auto* out = static_cast<std::vector<std::uint8_t>*>(png_get_io_ptr(png));
    out->insert(out->end(), data, data + n);
}

void pngFlush(png_structp) {}

}  // namespace

// libpng with a fast zlib level and the "Sub" row filter: a report writes hundreds of small
// pictures, and stb_image_write's encoder spent more time on them than grading did (perf: 37 %
// of a lab's grade in stbi_zlib_compress). The files are a little larger, the pixels the same.
bool encodePng(const Image& image, std::vector<std::uint8_t>* out, std::string* error) {
    out->clear();
    if (image.width <= 0 || image.height <= 0 || image.channels < 1 || image.channels > 4 ||
        image.pixels.size() != static_cast<std::size_t>(image.width) * image.height * image.channels) {
        if (error) *error = "image has inconsistent size, not encoded";
        return false;
    }
    std::vector<std::uint8_t> bytes(image.pixels.size());
    for (std::size_t i = 0; i < bytes.size(); ++i) {
        float v = image.pixels[i];
        if (std::isnan(v)) v = 0.0f;
        v = std::clamp(v, 0.0f, 1.0f);
        bytes[i] = static_cast<std::uint8_t>(std::lround(v * 255.0f));
    }
    PngWriteState state;
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &state, pngError, pngWarning);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (!png || !info || setjmp(state.jump)) {
        png_destroy_write_struct(&png, &info);
        if (error)
            *error = "cannot encode PNG (" + (state.message.empty() ? "out of memory" : state.message) + ")";
        out->clear();
        return false;
    }
    static const int kColorTypes[5] = {0, PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB,
                                       PNG_COLOR_TYPE_RGB_ALPHA};
    png_set_write_fn(png, out, pngWriteBytes, pngFlush);
    png_set_compression_level(png, 3);
    png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
    png_set_IHDR(png, info, static_cast<png_uint_32>(image.width), static_cast<png_uint_32>(image.height), 8,
                 kColorTypes[image.channels], PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_BASE,
                 PNG_FILTER_TYPE_BASE);
    png_write_info(png, info);
    const std::size_t stride = static_cast<std::size_t>(image.width) * image.channels;
    for (int y = 0; y < image.height; ++y)
        png_write_row(png, bytes.data() + stride * static_cast<std::size_t>(y));
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    return true;
}

bool writePng(const Image& image, const std::string& path, std::string* error) {
    std::vector<std::uint8_t> encoded;
    std::string encode_error;
    if (!encodePng(image, &encoded, &encode_error)) {
        if (error) *error = path + ": " + encode_error;
        return false;
    }
    // Beside the final name, then renamed: a killed grader leaves the old picture or the new one,
    // never half of one, and a link planted at the name is refused (atomic_file.h). Not fsync'ed:
    // a report writes hundreds of pictures, and the rename alone keeps them whole when the
    // process dies; the reports that name them are synced.
    AtomicFile output;
    std::string open_error;
    if (!output.open(path, &open_error)) {
        if (error) *error = open_error + ": cannot write PNG";
        return false;
    }
    std::string commit_error;
    if (std::fwrite(encoded.data(), 1, encoded.size(), output.stream()) != encoded.size() ||
        !output.commit(&commit_error, false)) {
        if (error) *error = (commit_error.empty() ? path : commit_error) + ": cannot write PNG";
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

namespace {

void appendBytes(void* context, void* data, int size) {
    auto* out = static_cast<std::vector<std::uint8_t>*>(context);
    const auto* bytes = static_cast<const std::uint8_t*>(data);
    out->insert(out->end(), bytes, bytes + size);
}

}  // namespace

void quantizeAsStored(Image* image, bool hdr) {
    if (!hdr) {
        for (float& v : image->pixels)
            v = static_cast<float>(std::lround(std::clamp(std::isnan(v) ? 0.0f : v, 0.0f, 1.0f) * 255.0f)) /
                255.0f;
        return;
    }
    const std::size_t n = static_cast<std::size_t>(image->width) * image->height;
    if (image->channels < 3 || n == 0 || image->pixels.size() != n * image->channels) return;
    std::vector<float> rgb(n * 3);
    for (std::size_t p = 0; p < n; ++p)
        for (std::size_t k = 0; k < 3; ++k) {
            const float v = image->pixels[p * image->channels + k];
            rgb[p * 3 + k] = std::isfinite(v) && v > 0.0f ? v : 0.0f;
        }
    std::vector<std::uint8_t> encoded;
    if (!stbi_write_hdr_to_func(appendBytes, &encoded, image->width, image->height, 3, rgb.data())) return;
    int w = 0, h = 0, c = 0;
    float* data = stbi_loadf_from_memory(encoded.data(), static_cast<int>(encoded.size()), &w, &h, &c, 4);
    if (!data) return;
    Image out(w, h, 4);
    std::copy_n(data, out.pixels.size(), out.pixels.begin());
    stbi_image_free(data);
    *image = std::move(out);
}

}  // namespace grader
