// The textures of glTF materials (docs/scenes.md, "Materials") for the programs that sample them.
// An image is decoded and uploaded the first time a program declaring its slot's sampler draws
// with it, once per loaded scene; a slot without a usable image reads a 1x1 stand-in (white, or
// a flat normal), so sampling is always defined. Programs that declare none of the names cost
// nothing: no image of theirs is ever decoded. Needs a current GL context (decodeTextureImage
// does not).
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "shaderlab/gl/gl.h"
#include "shaderlab/render/shader_program.h"
#include "shaderlab/scene/scene.h"

namespace shaderlab {

// Base colour, metallic-roughness, normal, occlusion, emissive: the order of the names below.
constexpr int kMaterialSlotCount = 5;
// Units above the lab's inputs (0..15) and the scratch unit (16, input_textures.h).
constexpr unsigned kFirstMaterialTextureUnit = 17;
// The texels uploaded for one scene in all, past which images are refused (4 x 4096x4096).
constexpr std::size_t kMaxSceneTexels = std::size_t{4} * 4096 * 4096;

// "u_base_color_texture", ... for slot 0..4.
const char* materialSamplerName(int slot);
bool isMaterialSampler(const std::string& name);

// RGBA8 texels, rows bottom first (OpenGL's order: t = 0 is the image's last row).
struct DecodedImage {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgba;
};

// Decodes PNG or JPEG bytes (the formats glTF 2.0 allows) with stb_image after reading the header
// alone: an image over grader::kMaxImagePixels is refused before a pixel is decoded. Returns ""
// or the problem ("is neither PNG nor JPEG", "cannot decode (...)").
std::string decodeTextureImage(const std::vector<std::uint8_t>& bytes, DecodedImage* out);

using MaterialWarning = std::function<void(const std::string&)>;

class MaterialTextures {
  public:
    MaterialTextures() = default;
    MaterialTextures(const MaterialTextures&) = delete;
    MaterialTextures& operator=(const MaterialTextures&) = delete;
    ~MaterialTextures();

    // Before a pass: finds the material uniforms `prog` declares (those the lab feeds itself,
    // `fed_by_lab`, stay the lab's) and points its samplers at their units. A name declared with
    // another type is reported through `warn` and left alone.
    void beginPass(const ShaderProgram& prog, const std::set<std::string>& fed_by_lab,
                   const MaterialWarning& warn);
    // Before a draw: binds `material`'s textures of `scene` (decoding and uploading them on first
    // use) and sets the u_has_*, u_*_texcoord, u_normal_scale and u_occlusion_strength uniforms.
    // An image that cannot be used is reported once through `warn`.
    void bindMaterial(const Scene& scene, const Material& material, const MaterialWarning& warn);

  private:
    struct Locations {
        GLint sampler = -1, has = -1, texcoord = -1;
    };
    struct Uploaded {
        GLuint texture = 0;  // 0: unusable, the stand-in is bound
        GLuint sampler = 0;
    };
    const Uploaded& texture(const Scene& scene, int index, bool srgb, const char* slot,
                            const MaterialWarning& warn);
    GLuint sampler(GLint mag, GLint min, GLint wrap_s, GLint wrap_t);
    GLuint standIn(bool normal);
    void unbind();

    bool any_ = false;  // the current program declares a material uniform
    Locations slots_[kMaterialSlotCount];
    GLint normal_scale_ = -1, occlusion_strength_ = -1;
    bool units_checked_ = false, units_ok_ = false;
    std::map<std::tuple<const Scene*, int, bool>, Uploaded> textures_;
    std::map<const Scene*, std::size_t> scene_texels_;
    std::map<std::tuple<GLint, GLint, GLint, GLint>, GLuint> samplers_;
    GLuint white_ = 0, flat_normal_ = 0;
    bool bound_ = false;
};

}  // namespace shaderlab
