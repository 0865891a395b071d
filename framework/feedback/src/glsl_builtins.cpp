// What GLSL declares by itself: the built-in types, storage words and keywords, functions and
// variables a shader may use without declaring them. Enough to tell a name the student made up
// from one of the language's, and to suggest the one meant; not a full list of GLSL 4.60.
#include <string>

#include "glsl_explain_detail.h"

namespace shaderlab::glsl_detail {

const std::set<std::string>& builtinTypes() {
    static const std::set<std::string> types = [] {
        std::set<std::string> t = {"void", "bool", "int", "uint", "float", "double"};
        for (const char* p : {"vec", "bvec", "ivec", "uvec", "dvec"})
            for (int n = 2; n <= 4; ++n) t.insert(p + std::to_string(n));
        for (const char* p : {"mat", "dmat"})
            for (int c = 2; c <= 4; ++c) {
                t.insert(p + std::to_string(c));
                for (int r = 2; r <= 4; ++r) t.insert(p + std::to_string(c) + "x" + std::to_string(r));
            }
        for (const char* p : {"sampler", "isampler", "usampler"})
            for (const char* s : {"1D", "2D", "3D", "Cube", "2DRect", "1DArray", "2DArray", "CubeArray",
                                  "Buffer", "2DMS", "2DMSArray"})
                t.insert(std::string(p) + s);
        for (const char* s :
             {"sampler1DShadow", "sampler2DShadow", "samplerCubeShadow", "sampler2DRectShadow",
              "sampler1DArrayShadow", "sampler2DArrayShadow", "samplerCubeArrayShadow"})
            t.insert(s);
        return t;
    }();
    return types;
}

bool isStorageWord(const std::string& s) {
    static const std::set<std::string> words = {"in",    "out",       "inout",  "uniform",
                                                "const", "attribute", "varying"};
    return words.count(s) > 0;
}

bool isKeyword(const std::string& s) {
    static const std::set<std::string> words = {
        "in",        "out",           "inout",    "uniform",   "const",   "attribute", "varying",  "flat",
        "smooth",    "noperspective", "centroid", "invariant", "precise", "highp",     "mediump",  "lowp",
        "precision", "layout",        "struct",   "if",        "else",    "for",       "while",    "do",
        "return",    "break",         "continue", "discard",   "switch",  "case",      "default",  "true",
        "false",     "sample",        "patch",    "buffer",    "shared",  "coherent",  "volatile", "restrict",
        "readonly",  "writeonly"};
    return words.count(s) > 0;
}

const std::vector<std::string>& builtinFunctions() {
    static const std::vector<std::string> names = {"radians",
                                                   "degrees",
                                                   "sin",
                                                   "cos",
                                                   "tan",
                                                   "asin",
                                                   "acos",
                                                   "atan",
                                                   "sinh",
                                                   "cosh",
                                                   "tanh",
                                                   "asinh",
                                                   "acosh",
                                                   "atanh",
                                                   "pow",
                                                   "exp",
                                                   "log",
                                                   "exp2",
                                                   "log2",
                                                   "sqrt",
                                                   "inversesqrt",
                                                   "abs",
                                                   "sign",
                                                   "floor",
                                                   "trunc",
                                                   "round",
                                                   "roundEven",
                                                   "ceil",
                                                   "fract",
                                                   "mod",
                                                   "modf",
                                                   "min",
                                                   "max",
                                                   "clamp",
                                                   "mix",
                                                   "step",
                                                   "smoothstep",
                                                   "isnan",
                                                   "isinf",
                                                   "floatBitsToInt",
                                                   "floatBitsToUint",
                                                   "intBitsToFloat",
                                                   "uintBitsToFloat",
                                                   "fma",
                                                   "length",
                                                   "distance",
                                                   "dot",
                                                   "cross",
                                                   "normalize",
                                                   "faceforward",
                                                   "reflect",
                                                   "refract",
                                                   "matrixCompMult",
                                                   "outerProduct",
                                                   "transpose",
                                                   "determinant",
                                                   "inverse",
                                                   "lessThan",
                                                   "lessThanEqual",
                                                   "greaterThan",
                                                   "greaterThanEqual",
                                                   "equal",
                                                   "notEqual",
                                                   "any",
                                                   "all",
                                                   "not",
                                                   "textureSize",
                                                   "texture",
                                                   "textureProj",
                                                   "textureLod",
                                                   "textureOffset",
                                                   "texelFetch",
                                                   "texelFetchOffset",
                                                   "textureProjOffset",
                                                   "textureLodOffset",
                                                   "textureProjLod",
                                                   "textureGrad",
                                                   "textureGradOffset",
                                                   "textureQueryLod",
                                                   "textureQueryLevels",
                                                   "dFdx",
                                                   "dFdy",
                                                   "fwidth",
                                                   "packUnorm2x16",
                                                   "unpackUnorm2x16",
                                                   "packHalf2x16",
                                                   "unpackHalf2x16",
                                                   "bitfieldExtract",
                                                   "bitCount",
                                                   "findLSB",
                                                   "findMSB"};
    return names;
}

const std::vector<std::string>& builtinVariables() {
    static const std::vector<std::string> names = {
        "gl_Position",  "gl_PointSize",   "gl_ClipDistance", "gl_VertexID",  "gl_InstanceID",
        "gl_FragCoord", "gl_FrontFacing", "gl_PointCoord",   "gl_FragDepth", "gl_PrimitiveID"};
    return names;
}

}  // namespace shaderlab::glsl_detail
