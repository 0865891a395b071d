// File, cube and generated textures by sampler type; see input_textures.h.
#include "input_textures.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "gl_types.h"
#include "grader/metrics/image.h"
#include "shaderlab/base/paths.h"
#include "shaderlab/render/shader_program.h"

namespace shaderlab {

namespace {

constexpr std::size_t kMaxTextureTexels = std::size_t{16} << 20;

// splitmix64 (Steele, Lea, Flood, "Fast splittable pseudorandom number generators",
// OOPSLA 2014): a fixed, documented hash so generated noise is the same everywhere.
std::uint64_t splitmix64(std::uint64_t x) {
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

// An image file as RGBA floats with GL's row order (row 0 is the bottom row of the picture),
// unless `keep_rows` (cube faces are stored top row first by convention).
bool loadRgba(const LabSpec& spec, const std::string& file, bool keep_rows, grader::Image* out,
              std::string* error) {
    const bool shared = file.rfind("shared/", 0) == 0;
    const PathResult p = resolveInside(shared ? spec.labs_root : spec.lab_dir, file);
    grader::Image img;
    if (!p.ok) {
        *error = p.error;
        return false;
    }
    if (!grader::readPng(p.path, &img, error)) return false;
    if (static_cast<std::size_t>(img.width) * img.height > kMaxTextureTexels) {
        *error =
            p.path + ": " + std::to_string(img.width) + "x" + std::to_string(img.height) + " is too large";
        return false;
    }
    grader::Image rgba(img.width, img.height, 4, 1.0f);
    for (int y = 0; y < img.height; ++y) {
        const int dst_y = keep_rows ? y : img.height - 1 - y;
        for (int x = 0; x < img.width; ++x) {
            for (int c = 0; c < 4; ++c) {
                float v = 1.0f;
                if (img.channels == 1 && c < 3) v = img.at(x, y, 0);
                if (img.channels == 2) v = c < 3 ? img.at(x, y, 0) : img.at(x, y, 1);
                if (img.channels >= 3 && c < img.channels) v = img.at(x, y, c);
                rgba.at(x, dst_y, c) = v;
            }
        }
    }
    *out = std::move(rgba);
    return true;
}

void upload(GLenum target, GLenum image_target, int w, int h, int d, bool srgb,
            const std::vector<float>& texels) {
    if (srgb) {
        std::vector<std::uint8_t> bytes(texels.size());
        for (std::size_t i = 0; i < texels.size(); ++i)
            bytes[i] = static_cast<std::uint8_t>(std::lround(std::clamp(texels[i], 0.0f, 1.0f) * 255.0f));
        if (target == GL_TEXTURE_1D)
            glTexImage1D(image_target, 0, GL_SRGB8_ALPHA8, w, 0, GL_RGBA, GL_UNSIGNED_BYTE, bytes.data());
        else if (target == GL_TEXTURE_3D)
            glTexImage3D(image_target, 0, GL_SRGB8_ALPHA8, w, h, d, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                         bytes.data());
        else
            glTexImage2D(image_target, 0, GL_SRGB8_ALPHA8, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, bytes.data());
        return;
    }
    if (target == GL_TEXTURE_1D)
        glTexImage1D(image_target, 0, GL_RGBA32F, w, 0, GL_RGBA, GL_FLOAT, texels.data());
    else if (target == GL_TEXTURE_3D)
        glTexImage3D(image_target, 0, GL_RGBA32F, w, h, d, 0, GL_RGBA, GL_FLOAT, texels.data());
    else
        glTexImage2D(image_target, 0, GL_RGBA32F, w, h, 0, GL_RGBA, GL_FLOAT, texels.data());
}

std::string sizeText(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

}  // namespace

std::vector<float> generateTexels(const GeneratedTexture& g) {
    const std::size_t n = static_cast<std::size_t>(g.width) * g.height * g.depth;
    std::vector<float> out(n * 4);
    for (int z = 0; z < g.depth; ++z) {
        for (int y = 0; y < g.height; ++y) {
            for (int x = 0; x < g.width; ++x) {
                const std::size_t i = (static_cast<std::size_t>(z) * g.height + y) * g.width + x;
                glm::vec4 c(0.0f);
                if (g.pattern == "checker") {
                    const int cx = x * g.cells / g.width, cy = y * g.cells / g.height;
                    const int cz = g.depth > 1 ? z * g.cells / g.depth : 0;
                    c = g.colors[static_cast<std::size_t>((cx + cy + cz) % 2)];
                } else if (g.pattern == "gradient") {
                    // Stops evenly spaced along s, sampled at texel centres.
                    const float s = (static_cast<float>(x) + 0.5f) / static_cast<float>(g.width);
                    const float f = s * static_cast<float>(g.colors.size() - 1);
                    const std::size_t k = std::min(static_cast<std::size_t>(f), g.colors.size() - 2);
                    c = glm::mix(g.colors[k], g.colors[k + 1], f - static_cast<float>(k));
                } else if (g.pattern == "noise") {
                    for (int ch = 0; ch < 4; ++ch) {
                        const std::uint64_t h = splitmix64((static_cast<std::uint64_t>(g.seed) << 40) ^
                                                           (i * 4 + static_cast<std::uint64_t>(ch)));
                        c[ch] = static_cast<float>(h >> 40) / static_cast<float>(1ull << 24);  // [0, 1)
                    }
                } else {
                    c = g.colors.front();
                }
                for (int ch = 0; ch < 4; ++ch) out[i * 4 + static_cast<std::size_t>(ch)] = c[ch];
            }
        }
    }
    return out;
}

std::string createInputTexture(const LabSpec& spec, const PassInput& in, unsigned sampler_type, bool mipmaps,
                               InputTexture* out) {
    const unsigned target = samplerTextureTarget(sampler_type);
    const std::string declared = std::string(glslTypeName(sampler_type)) + " " + in.sampler;
    if (target == 0 || isShadowSampler(sampler_type))
        return "the program declares `" + declared + "`; a " +
               (in.source == InputSource::Cube ? "cube map" : "texture") + " input needs " +
               (in.source == InputSource::Cube ? "samplerCube" : "sampler1D, sampler2D or sampler3D");
    std::vector<float> texels;
    int w = 0, h = 0, d = 1;
    std::vector<std::vector<float>> faces;
    std::string error;

    if (in.source == InputSource::Cube) {
        if (target != GL_TEXTURE_CUBE_MAP)
            return "a cube map needs a samplerCube; the program declares `" + declared + "`";
        for (const std::string& f : in.cube_files) {
            grader::Image img;
            if (!loadRgba(spec, f, true, &img, &error)) return error;
            if (img.width != img.height)
                return f + " is " + sizeText(img.width, img.height) + "; cube faces are square";
            if (w && img.width != w)
                return f + " is " + sizeText(img.width, img.height) + ", the first face " + sizeText(w, w);
            w = h = img.width;
            faces.push_back(std::move(img.pixels));
        }
    } else if (target == GL_TEXTURE_CUBE_MAP) {
        return "the program declares `" + declared + "`, which needs \"cube\": six face images";
    } else if (in.source == InputSource::File) {
        grader::Image img;
        if (!loadRgba(spec, in.file, false, &img, &error)) return error;
        w = img.width;
        h = img.height;
        texels = std::move(img.pixels);
        if (target == GL_TEXTURE_1D && h != 1)
            return in.file + " is " + sizeText(w, h) + "; a sampler1D needs an Nx1 image (`" + declared +
                   "`)";
        if (target == GL_TEXTURE_3D) {
            if (in.layers <= 0 || h % in.layers != 0)
                return "`" + declared + "` needs \"layers\": the number of slices stacked in " + in.file +
                       " (its height " + std::to_string(h) + " must divide evenly)";
            // Slices run top to bottom in the picture; rows were flipped for GL, so slice k of
            // the picture is the block (layers - 1 - k) of rows now. Reorder into slice order.
            const int slice_h = h / in.layers;
            std::vector<float> reordered(texels.size());
            const std::size_t slice_floats = static_cast<std::size_t>(w) * slice_h * 4;
            for (int k = 0; k < in.layers; ++k)
                std::copy_n(texels.begin() + static_cast<std::ptrdiff_t>(slice_floats) * (in.layers - 1 - k),
                            slice_floats, reordered.begin() + static_cast<std::ptrdiff_t>(slice_floats) * k);
            texels = std::move(reordered);
            h = slice_h;
            d = in.layers;
        } else if (in.layers > 0) {
            return "\"layers\" cuts a picture into the slices of a sampler3D; the program declares `" +
                   declared + "`";
        }
    } else {
        const GeneratedTexture& g = in.generated;
        if (target == GL_TEXTURE_1D && (g.height != 1 || g.depth != 1))
            return "a generated " + sizeText(g.width, g.height) + " texture cannot feed `" + declared +
                   "`; give \"size\": [width]";
        if (target == GL_TEXTURE_2D && g.depth != 1)
            return "a generated 3D texture cannot feed `" + declared + "`";
        w = g.width;
        h = g.height;
        d = g.depth;
        texels = generateTexels(g);
    }

    out->target = target;
    // A unit no pass uses, so making a texture never disturbs the bindings of the pass being set up.
    glActiveTexture(GL_TEXTURE0 + kScratchTextureUnit);
    out->width = w;
    out->height = h;
    out->depth = d;
    glGenTextures(1, &out->id);
    glBindTexture(target, out->id);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    if (target == GL_TEXTURE_CUBE_MAP) {
        for (int f = 0; f < 6; ++f)
            upload(GL_TEXTURE_2D, GL_TEXTURE_CUBE_MAP_POSITIVE_X + static_cast<GLenum>(f), w, h, 1, in.srgb,
                   faces[static_cast<std::size_t>(f)]);
    } else {
        upload(target, target, w, h, d, in.srgb, texels);
    }
    if (mipmaps) glGenerateMipmap(target);
    glBindTexture(target, 0);
    glActiveTexture(GL_TEXTURE0);
    return {};
}

}  // namespace shaderlab
