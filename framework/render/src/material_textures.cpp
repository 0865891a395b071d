// Material textures of glTF scenes; see material_textures.h and docs/scenes.md ("Materials").
//
// Colour spaces follow the glTF 2.0 specification (section "Metallic-Roughness Material" and
// "Additional Textures"): base colour and emissive textures hold sRGB-encoded values and are
// uploaded as GL_SRGB8_ALPHA8, so sampling returns linear values; metallic-roughness, normal and
// occlusion textures are linear data (GL_RGBA8). Samplers follow the file's sampler; what it
// leaves unset (section "Textures": no sampler means repeat wrapping and auto filtering) is read
// as GL_REPEAT, GL_LINEAR magnification and GL_LINEAR_MIPMAP_LINEAR minification.
#include "material_textures.h"

#include <stb_image.h>

#include <algorithm>
#include <climits>
#include <cstring>

#include "grader/metrics/image.h"
#include "input_textures.h"

namespace shaderlab {

namespace {

constexpr const char* kSamplerNames[kMaterialSlotCount] = {"u_base_color_texture",
                                                           "u_metallic_roughness_texture", "u_normal_texture",
                                                           "u_occlusion_texture", "u_emissive_texture"};
constexpr const char* kHasNames[kMaterialSlotCount] = {
    "u_has_base_color_texture", "u_has_metallic_roughness_texture", "u_has_normal_texture",
    "u_has_occlusion_texture", "u_has_emissive_texture"};
constexpr const char* kTexcoordNames[kMaterialSlotCount] = {
    "u_base_color_texcoord", "u_metallic_roughness_texcoord", "u_normal_texcoord", "u_occlusion_texcoord",
    "u_emissive_texcoord"};
constexpr bool kSrgb[kMaterialSlotCount] = {true, false, false, false, true};
constexpr int kNormalSlot = 2;

const TextureRef& slotOf(const Material& m, int slot) {
    switch (slot) {
        case 0:
            return m.base_color_texture;
        case 1:
            return m.metallic_roughness_texture;
        case 2:
            return m.normal_texture;
        case 3:
            return m.occlusion_texture;
        default:
            return m.emissive_texture;
    }
}

GLint magFilter(int f) { return f == GL_NEAREST ? GL_NEAREST : GL_LINEAR; }

GLint minFilter(int f) {
    switch (f) {
        case GL_NEAREST:
        case GL_LINEAR:
        case GL_NEAREST_MIPMAP_NEAREST:
        case GL_LINEAR_MIPMAP_NEAREST:
        case GL_NEAREST_MIPMAP_LINEAR:
            return f;
        default:
            return GL_LINEAR_MIPMAP_LINEAR;
    }
}

GLint wrapMode(int w) { return w == GL_CLAMP_TO_EDGE || w == GL_MIRRORED_REPEAT ? w : GL_REPEAT; }

bool needsMipmaps(GLint min) { return min != GL_NEAREST && min != GL_LINEAR; }

// Makes a 2D texture of `w` x `h` RGBA8 texels on the scratch unit.
GLuint upload(int w, int h, const std::uint8_t* texels, bool srgb, bool mipmaps) {
    GLuint tex = 0;
    glActiveTexture(GL_TEXTURE0 + kScratchTextureUnit);
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                 texels);
    if (mipmaps)
        glGenerateMipmap(GL_TEXTURE_2D);
    else
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
    glBindTexture(GL_TEXTURE_2D, 0);
    glActiveTexture(GL_TEXTURE0);
    return tex;
}

}  // namespace

const char* materialSamplerName(int slot) {
    return slot >= 0 && slot < kMaterialSlotCount ? kSamplerNames[slot] : "";
}

bool isMaterialSampler(const std::string& name) {
    return std::any_of(std::begin(kSamplerNames), std::end(kSamplerNames),
                       [&](const char* n) { return name == n; });
}

std::string decodeTextureImage(const std::vector<std::uint8_t>& bytes, DecodedImage* out) {
    static const std::uint8_t kPng[8] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
    const bool png = bytes.size() >= 8 && std::memcmp(bytes.data(), kPng, 8) == 0;
    const bool jpeg = bytes.size() >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF;
    if (bytes.empty()) return "has no bytes";
    // stb_image reads more formats; glTF allows these two, and fewer decoders see untrusted bytes.
    if (!png && !jpeg) return "is neither PNG nor JPEG (the formats glTF 2.0 allows)";
    if (bytes.size() > static_cast<std::size_t>(INT_MAX)) return "is larger than 2 GiB";
    const int size = static_cast<int>(bytes.size());
    int w = 0, h = 0, c = 0;
    if (!stbi_info_from_memory(bytes.data(), size, &w, &h, &c) || w <= 0 || h <= 0)
        return std::string("cannot be read: its header is malformed (") + stbi_failure_reason() + ")";
    if (static_cast<std::size_t>(w) * static_cast<std::size_t>(h) > grader::kMaxImagePixels)
        return std::to_string(w) + "x" + std::to_string(h) + " pixels is more than the limit of " +
               std::to_string(grader::kMaxImagePixels) + " (4096x4096)";
    int dw = 0, dh = 0;
    stbi_uc* data = stbi_load_from_memory(bytes.data(), size, &dw, &dh, &c, 4);
    if (!data) return std::string("cannot be decoded (") + stbi_failure_reason() + ")";
    if (dw != w || dh != h) {
        stbi_image_free(data);
        return "decodes to another size than its header says";
    }
    out->width = w;
    out->height = h;
    const std::size_t row = static_cast<std::size_t>(w) * 4;
    out->rgba.resize(row * static_cast<std::size_t>(h));
    for (int y = 0; y < h; ++y)
        std::memcpy(out->rgba.data() + static_cast<std::size_t>(h - 1 - y) * row,
                    data + static_cast<std::size_t>(y) * row, row);
    stbi_image_free(data);
    return "";
}

MaterialTextures::~MaterialTextures() {
    unbind();
    for (auto& [key, t] : textures_)
        if (t.texture) glDeleteTextures(1, &t.texture);
    for (auto& [key, s] : samplers_) glDeleteSamplers(1, &s);
    if (white_) glDeleteTextures(1, &white_);
    if (flat_normal_) glDeleteTextures(1, &flat_normal_);
}

void MaterialTextures::unbind() {
    if (!bound_) return;
    for (int k = 0; k < kMaterialSlotCount; ++k) {
        const GLuint unit = kFirstMaterialTextureUnit + static_cast<GLuint>(k);
        glActiveTexture(GL_TEXTURE0 + unit);
        glBindTexture(GL_TEXTURE_2D, 0);
        glBindSampler(unit, 0);
    }
    glActiveTexture(GL_TEXTURE0);
    bound_ = false;
}

void MaterialTextures::beginPass(const ShaderProgram& prog, const std::set<std::string>& fed_by_lab,
                                 const MaterialWarning& warn) {
    unbind();
    any_ = false;
    const auto find = [&](const char* name, GLenum type) -> GLint {
        const UniformSlot* s = prog.uniform(name);
        if (!s) return -1;
        if (s->type != type || s->size != 1) {
            warn(std::string(name) + " is provided by the framework as " + glslTypeName(type) +
                 "; it is declared " + glslTypeName(s->type) + (s->size != 1 ? "[]" : "") +
                 " (see docs/scenes.md, \"Materials\")");
            return -1;
        }
        any_ = true;
        return s->location;
    };
    for (int k = 0; k < kMaterialSlotCount; ++k) {
        slots_[k] = Locations{};
        if (!fed_by_lab.count(kSamplerNames[k])) slots_[k].sampler = find(kSamplerNames[k], GL_SAMPLER_2D);
        slots_[k].has = find(kHasNames[k], GL_BOOL);
        slots_[k].texcoord = find(kTexcoordNames[k], GL_INT);
    }
    normal_scale_ = find("u_normal_scale", GL_FLOAT);
    occlusion_strength_ = find("u_occlusion_strength", GL_FLOAT);
    if (!any_) return;
    if (!units_checked_) {
        GLint units = 0;
        glGetIntegerv(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, &units);
        units_ok_ = units >= static_cast<GLint>(kFirstMaterialTextureUnit) + kMaterialSlotCount;
        units_checked_ = true;
        if (!units_ok_)
            warn("this driver has " + std::to_string(units) + " texture units; material textures need " +
                 std::to_string(kFirstMaterialTextureUnit + kMaterialSlotCount) + " and are not bound");
    }
    for (int k = 0; k < kMaterialSlotCount; ++k) {
        if (slots_[k].sampler < 0) continue;
        if (!units_ok_) {
            slots_[k].sampler = -1;
            continue;
        }
        glUniform1i(slots_[k].sampler, static_cast<GLint>(kFirstMaterialTextureUnit) + k);
    }
}

GLuint MaterialTextures::sampler(GLint mag, GLint min, GLint wrap_s, GLint wrap_t) {
    const auto key = std::make_tuple(mag, min, wrap_s, wrap_t);
    if (const auto it = samplers_.find(key); it != samplers_.end()) return it->second;
    GLuint s = 0;
    glGenSamplers(1, &s);
    glSamplerParameteri(s, GL_TEXTURE_MAG_FILTER, mag);
    glSamplerParameteri(s, GL_TEXTURE_MIN_FILTER, min);
    glSamplerParameteri(s, GL_TEXTURE_WRAP_S, wrap_s);
    glSamplerParameteri(s, GL_TEXTURE_WRAP_T, wrap_t);
    samplers_[key] = s;
    return s;
}

GLuint MaterialTextures::standIn(bool normal) {
    GLuint& tex = normal ? flat_normal_ : white_;
    if (!tex) {
        // A flat tangent-space normal (0, 0, 1) encoded as n * 0.5 + 0.5; white leaves every
        // factor it multiplies unchanged, as a material without the texture means.
        const std::uint8_t texel[4] = {static_cast<std::uint8_t>(normal ? 128 : 255),
                                       static_cast<std::uint8_t>(normal ? 128 : 255), 255, 255};
        tex = upload(1, 1, texel, false, false);
    }
    return tex;
}

const MaterialTextures::Uploaded& MaterialTextures::texture(const Scene& scene, int index, bool srgb,
                                                            const char* slot, const MaterialWarning& warn) {
    const auto key = std::make_tuple(&scene, index, srgb);
    if (const auto it = textures_.find(key); it != textures_.end()) return it->second;
    Uploaded& u = textures_[key];
    const Texture& t = scene.textures.at(static_cast<std::size_t>(index));
    const bool has_image = t.image >= 0 && static_cast<std::size_t>(t.image) < scene.images.size();
    const std::string image_name =
        has_image ? scene.images[static_cast<std::size_t>(t.image)].name : std::string("(none)");
    const auto refuse = [&](const std::string& problem) {
        warn(scene.source_path + ": image '" + image_name + "' (texture " + std::to_string(index) + ", " +
             slot + ") " + problem + "; the shader reads a white stand-in instead");
    };
    if (!has_image) {
        refuse("does not exist");
        return u;
    }
    const TextureImage& image = scene.images[static_cast<std::size_t>(t.image)];
    if (image.bytes.empty()) {
        refuse("could not be read from the file (see the loader's warnings)");
        return u;
    }
    DecodedImage decoded;
    const std::string problem = decodeTextureImage(image.bytes, &decoded);
    if (!problem.empty()) {
        refuse(problem);
        return u;
    }
    std::size_t& texels = scene_texels_[&scene];
    const std::size_t n = static_cast<std::size_t>(decoded.width) * static_cast<std::size_t>(decoded.height);
    if (texels + n > kMaxSceneTexels) {
        refuse("would take the scene's textures past " + std::to_string(kMaxSceneTexels) +
               " texels (four 4096x4096 images)");
        return u;
    }
    texels += n;
    const GLint min = minFilter(t.min_filter);
    u.sampler = sampler(magFilter(t.mag_filter), min, wrapMode(t.wrap_s), wrapMode(t.wrap_t));
    u.texture = upload(decoded.width, decoded.height, decoded.rgba.data(), srgb, needsMipmaps(min));
    return u;
}

void MaterialTextures::bindMaterial(const Scene& scene, const Material& material,
                                    const MaterialWarning& warn) {
    if (!any_) return;
    for (int k = 0; k < kMaterialSlotCount; ++k) {
        const Locations& loc = slots_[k];
        const TextureRef& ref = slotOf(material, k);
        const bool named = ref.texture >= 0 && static_cast<std::size_t>(ref.texture) < scene.textures.size();
        bool usable = false;
        if (loc.sampler >= 0) {
            GLuint tex = 0, smp = 0;
            if (named) {
                const Uploaded& u = texture(scene, ref.texture, kSrgb[k], kSamplerNames[k], warn);
                tex = u.texture;
                smp = u.sampler;
            }
            usable = tex != 0;
            if (!usable) {
                tex = standIn(k == kNormalSlot);
                smp = sampler(GL_NEAREST, GL_NEAREST, GL_REPEAT, GL_REPEAT);
            }
            const GLuint unit = kFirstMaterialTextureUnit + static_cast<GLuint>(k);
            glActiveTexture(GL_TEXTURE0 + unit);
            glBindTexture(GL_TEXTURE_2D, tex);
            glBindSampler(unit, smp);
            bound_ = true;
        } else {
            // Without the sampler the flag says what the material names.
            usable = named;
        }
        if (loc.has >= 0) glUniform1i(loc.has, usable ? 1 : 0);
        if (loc.texcoord >= 0) glUniform1i(loc.texcoord, named ? ref.texcoord : 0);
    }
    glActiveTexture(GL_TEXTURE0);
    if (normal_scale_ >= 0)
        glUniform1f(normal_scale_,
                    material.normal_texture.texture >= 0 ? material.normal_texture.scale : 1.0f);
    if (occlusion_strength_ >= 0)
        glUniform1f(occlusion_strength_,
                    material.occlusion_texture.texture >= 0 ? material.occlusion_texture.scale : 1.0f);
}

}  // namespace shaderlab
