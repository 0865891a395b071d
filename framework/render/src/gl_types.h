// What a GL uniform type enum means: its scalar kind, component count and matrix shape, and its
// GLSL name. Used to read lab.json values into uniforms by the type the program declares.
#pragma once

#include "shaderlab/gl/gl.h"

namespace shaderlab {

enum class ScalarKind { Float, Int, Uint, Bool, Double, Sampler, Other };

struct GlTypeInfo {
    ScalarKind kind = ScalarKind::Other;
    int components = 0;  // scalars per element: 1 (float), 3 (vec3), 16 (mat4)
    int columns = 1;     // matrices: columns; vectors and scalars: 1
    int rows = 1;        // matrices: rows; vectors: components
};

GlTypeInfo glTypeInfo(unsigned type);

// The texture target a sampler type reads (GL_TEXTURE_2D for sampler2D and sampler2DShadow), or 0
// for sampler types the framework does not bind.
unsigned samplerTextureTarget(unsigned sampler_type);
bool isShadowSampler(unsigned sampler_type);

}  // namespace shaderlab
