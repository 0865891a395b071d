// GL type enums described; see gl_types.h.
#include "gl_types.h"

#include "shaderlab/render/shader_program.h"

namespace shaderlab {

GlTypeInfo glTypeInfo(unsigned type) {
    switch (type) {
        case GL_FLOAT:
            return {ScalarKind::Float, 1, 1, 1};
        case GL_FLOAT_VEC2:
            return {ScalarKind::Float, 2, 1, 2};
        case GL_FLOAT_VEC3:
            return {ScalarKind::Float, 3, 1, 3};
        case GL_FLOAT_VEC4:
            return {ScalarKind::Float, 4, 1, 4};
        case GL_INT:
            return {ScalarKind::Int, 1, 1, 1};
        case GL_INT_VEC2:
            return {ScalarKind::Int, 2, 1, 2};
        case GL_INT_VEC3:
            return {ScalarKind::Int, 3, 1, 3};
        case GL_INT_VEC4:
            return {ScalarKind::Int, 4, 1, 4};
        case GL_UNSIGNED_INT:
            return {ScalarKind::Uint, 1, 1, 1};
        case GL_UNSIGNED_INT_VEC2:
            return {ScalarKind::Uint, 2, 1, 2};
        case GL_UNSIGNED_INT_VEC3:
            return {ScalarKind::Uint, 3, 1, 3};
        case GL_UNSIGNED_INT_VEC4:
            return {ScalarKind::Uint, 4, 1, 4};
        case GL_BOOL:
            return {ScalarKind::Bool, 1, 1, 1};
        case GL_BOOL_VEC2:
            return {ScalarKind::Bool, 2, 1, 2};
        case GL_BOOL_VEC3:
            return {ScalarKind::Bool, 3, 1, 3};
        case GL_BOOL_VEC4:
            return {ScalarKind::Bool, 4, 1, 4};
        case GL_FLOAT_MAT2:
            return {ScalarKind::Float, 4, 2, 2};
        case GL_FLOAT_MAT3:
            return {ScalarKind::Float, 9, 3, 3};
        case GL_FLOAT_MAT4:
            return {ScalarKind::Float, 16, 4, 4};
        case GL_FLOAT_MAT2x3:
            return {ScalarKind::Float, 6, 2, 3};
        case GL_FLOAT_MAT2x4:
            return {ScalarKind::Float, 8, 2, 4};
        case GL_FLOAT_MAT3x2:
            return {ScalarKind::Float, 6, 3, 2};
        case GL_FLOAT_MAT3x4:
            return {ScalarKind::Float, 12, 3, 4};
        case GL_FLOAT_MAT4x2:
            return {ScalarKind::Float, 8, 4, 2};
        case GL_FLOAT_MAT4x3:
            return {ScalarKind::Float, 12, 4, 3};
        case GL_DOUBLE:
        case GL_DOUBLE_VEC2:
        case GL_DOUBLE_VEC3:
        case GL_DOUBLE_VEC4:
            return {ScalarKind::Double, 0, 1, 1};
        default:
            break;
    }
    const char* name = glslTypeName(type);
    const std::string n = name;
    if (n.find("sampler") != std::string::npos) return {ScalarKind::Sampler, 1, 1, 1};
    return {};
}

unsigned samplerTextureTarget(unsigned sampler_type) {
    switch (sampler_type) {
        case GL_SAMPLER_1D:
            return GL_TEXTURE_1D;
        case GL_SAMPLER_2D:
        case GL_SAMPLER_2D_SHADOW:
            return GL_TEXTURE_2D;
        case GL_SAMPLER_3D:
            return GL_TEXTURE_3D;
        case GL_SAMPLER_CUBE:
            return GL_TEXTURE_CUBE_MAP;
        default:
            return 0;
    }
}

bool isShadowSampler(unsigned sampler_type) { return sampler_type == GL_SAMPLER_2D_SHADOW; }

const char* glslTypeName(unsigned type) {
    switch (type) {
        case GL_FLOAT:
            return "float";
        case GL_FLOAT_VEC2:
            return "vec2";
        case GL_FLOAT_VEC3:
            return "vec3";
        case GL_FLOAT_VEC4:
            return "vec4";
        case GL_INT:
            return "int";
        case GL_INT_VEC2:
            return "ivec2";
        case GL_INT_VEC3:
            return "ivec3";
        case GL_INT_VEC4:
            return "ivec4";
        case GL_UNSIGNED_INT:
            return "uint";
        case GL_UNSIGNED_INT_VEC2:
            return "uvec2";
        case GL_UNSIGNED_INT_VEC3:
            return "uvec3";
        case GL_UNSIGNED_INT_VEC4:
            return "uvec4";
        case GL_BOOL:
            return "bool";
        case GL_BOOL_VEC2:
            return "bvec2";
        case GL_BOOL_VEC3:
            return "bvec3";
        case GL_BOOL_VEC4:
            return "bvec4";
        case GL_FLOAT_MAT2:
            return "mat2";
        case GL_FLOAT_MAT3:
            return "mat3";
        case GL_FLOAT_MAT4:
            return "mat4";
        case GL_FLOAT_MAT2x3:
            return "mat2x3";
        case GL_FLOAT_MAT2x4:
            return "mat2x4";
        case GL_FLOAT_MAT3x2:
            return "mat3x2";
        case GL_FLOAT_MAT3x4:
            return "mat3x4";
        case GL_FLOAT_MAT4x2:
            return "mat4x2";
        case GL_FLOAT_MAT4x3:
            return "mat4x3";
        case GL_DOUBLE:
            return "double";
        case GL_SAMPLER_1D:
            return "sampler1D";
        case GL_SAMPLER_2D:
            return "sampler2D";
        case GL_SAMPLER_3D:
            return "sampler3D";
        case GL_SAMPLER_CUBE:
            return "samplerCube";
        case GL_SAMPLER_1D_SHADOW:
            return "sampler1DShadow";
        case GL_SAMPLER_2D_SHADOW:
            return "sampler2DShadow";
        case GL_SAMPLER_CUBE_SHADOW:
            return "samplerCubeShadow";
        case GL_SAMPLER_1D_ARRAY:
            return "sampler1DArray";
        case GL_SAMPLER_2D_ARRAY:
            return "sampler2DArray";
        case GL_SAMPLER_2D_ARRAY_SHADOW:
            return "sampler2DArrayShadow";
        case GL_SAMPLER_2D_RECT:
            return "sampler2DRect";
        case GL_SAMPLER_BUFFER:
            return "samplerBuffer";
        case GL_SAMPLER_2D_MULTISAMPLE:
            return "sampler2DMS";
        case GL_INT_SAMPLER_2D:
            return "isampler2D";
        case GL_UNSIGNED_INT_SAMPLER_2D:
            return "usampler2D";
        case GL_INT_SAMPLER_3D:
            return "isampler3D";
        case GL_UNSIGNED_INT_SAMPLER_3D:
            return "usampler3D";
        case GL_INT_SAMPLER_CUBE:
            return "isamplerCube";
        case GL_UNSIGNED_INT_SAMPLER_CUBE:
            return "usamplerCube";
        case GL_INT_SAMPLER_1D:
            return "isampler1D";
        case GL_UNSIGNED_INT_SAMPLER_1D:
            return "usampler1D";
        default:
            return "another type";
    }
}

}  // namespace shaderlab
