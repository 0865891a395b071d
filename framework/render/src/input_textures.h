// Textures a pass samples that do not come from a target: image files, cube maps of six files,
// and textures the framework generates. Each is made for the sampler type the program declares:
// an Nx1 PNG bound to a sampler1D becomes a 1D texture, the same file bound to a sampler2D a 2D
// one; a PNG cut into `layers` slices feeds a sampler3D. Needs a current GL context.
#pragma once

#include <string>

#include "shaderlab/gl/gl.h"
#include "shaderlab/lab/lab_spec.h"

namespace shaderlab {

// The texture unit the framework uses to create and update textures; passes use units 0..15.
constexpr unsigned kScratchTextureUnit = 16;

struct InputTexture {
    GLuint id = 0;
    GLenum target = 0;  // GL_TEXTURE_1D, _2D, _3D or _CUBE_MAP
    int width = 0, height = 0, depth = 0;
};

// Creates the texture for `in` (a File, Cube or Generated input) as `sampler_type` needs it,
// with mipmaps when asked. Returns "" or a problem worded for lab.json's author.
std::string createInputTexture(const LabSpec& spec, const PassInput& in, unsigned sampler_type, bool mipmaps,
                               InputTexture* out);

// The texel values of a generated texture, RGBA floats, GL order (row 0 is t = 0, slices last).
std::vector<float> generateTexels(const GeneratedTexture& g);

}  // namespace shaderlab
