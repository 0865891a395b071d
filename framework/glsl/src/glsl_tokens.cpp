// The GLSL lexer; see glsl_tokens.h.
#include "shaderlab/glsl/glsl_tokens.h"

#include <algorithm>
#include <unordered_set>

namespace shaderlab::glsl {

namespace {

// The words an author cannot choose: they are the structure of a shader ("The OpenGL Shading
// Language 4.60", sections 3.6 and 8, and ES 3.20's additions). `main` is here too: every shader
// has one, and naming it like a variable would hide where it is. (Filled to the line by hand.)
// clang-format off
const char* const kKeywords[] = {
    // qualifiers and control flow
    "const", "uniform", "buffer", "shared", "attribute", "varying", "coherent", "volatile", "restrict",
    "readonly", "writeonly", "atomic_uint", "layout", "centroid", "flat", "smooth", "noperspective", "patch",
    "sample", "invariant", "precise", "break", "continue", "do", "for", "while", "switch", "case", "default",
    "if", "else", "subroutine", "in", "out", "inout", "true", "false", "discard", "return", "lowp", "mediump",
    "highp", "precision", "struct", "main",
    // scalar, vector and matrix types
    "int", "void", "bool", "float", "double", "uint", "vec2", "vec3", "vec4", "ivec2", "ivec3", "ivec4",
    "bvec2", "bvec3", "bvec4", "uvec2", "uvec3", "uvec4", "dvec2", "dvec3", "dvec4", "mat2", "mat3", "mat4",
    "mat2x2", "mat2x3", "mat2x4", "mat3x2", "mat3x3", "mat3x4", "mat4x2", "mat4x3", "mat4x4", "dmat2",
    "dmat3", "dmat4", "dmat2x2", "dmat2x3", "dmat2x4", "dmat3x2", "dmat3x3", "dmat3x4", "dmat4x2", "dmat4x3",
    "dmat4x4",
    // opaque types
    "sampler1D", "sampler1DShadow", "sampler1DArray", "sampler1DArrayShadow", "isampler1D", "isampler1DArray",
    "usampler1D", "usampler1DArray", "sampler2D", "sampler2DShadow", "sampler2DArray", "sampler2DArrayShadow",
    "isampler2D", "isampler2DArray", "usampler2D", "usampler2DArray", "sampler2DRect", "sampler2DRectShadow",
    "isampler2DRect", "usampler2DRect", "sampler2DMS", "isampler2DMS", "usampler2DMS", "sampler2DMSArray",
    "isampler2DMSArray", "usampler2DMSArray", "sampler3D", "isampler3D", "usampler3D", "samplerCube",
    "samplerCubeShadow", "isamplerCube", "usamplerCube", "samplerCubeArray", "samplerCubeArrayShadow",
    "isamplerCubeArray", "usamplerCubeArray", "samplerBuffer", "isamplerBuffer", "usamplerBuffer", "image1D",
    "iimage1D", "uimage1D", "image2D", "iimage2D", "uimage2D", "image3D", "iimage3D", "uimage3D",
    "image2DRect", "iimage2DRect", "uimage2DRect", "imageCube", "iimageCube", "uimageCube", "imageBuffer",
    "iimageBuffer", "uimageBuffer", "image1DArray", "iimage1DArray", "uimage1DArray", "image2DArray",
    "iimage2DArray", "uimage2DArray", "imageCubeArray", "iimageCubeArray", "uimageCubeArray", "image2DMS",
    "iimage2DMS", "uimage2DMS", "image2DMSArray", "iimage2DMSArray", "uimage2DMSArray", "samplerExternalOES",
    // built-in functions: angles, exponentials, common, geometric, matrix, vector relational
    "radians", "degrees", "sin", "cos", "tan", "asin", "acos", "atan", "sinh", "cosh", "tanh", "asinh",
    "acosh", "atanh", "pow", "exp", "log", "exp2", "log2", "sqrt", "inversesqrt", "abs", "sign", "floor",
    "trunc", "round", "roundEven", "ceil", "fract", "mod", "modf", "min", "max", "clamp", "mix", "step",
    "smoothstep", "isnan", "isinf", "floatBitsToInt", "floatBitsToUint", "intBitsToFloat", "uintBitsToFloat",
    "fma", "frexp", "ldexp", "length", "distance", "dot", "cross", "normalize", "faceforward", "reflect",
    "refract", "matrixCompMult", "outerProduct", "transpose", "determinant", "inverse", "lessThan",
    "lessThanEqual", "greaterThan", "greaterThanEqual", "equal", "notEqual", "any", "all", "not",
    // packing and integer functions
    "packUnorm2x16", "packSnorm2x16", "packUnorm4x8", "packSnorm4x8", "unpackUnorm2x16", "unpackSnorm2x16",
    "unpackUnorm4x8", "unpackSnorm4x8", "packHalf2x16", "unpackHalf2x16", "packDouble2x32",
    "unpackDouble2x32", "uaddCarry", "usubBorrow", "umulExtended", "imulExtended", "bitfieldExtract",
    "bitfieldInsert", "bitfieldReverse", "bitCount", "findLSB", "findMSB",
    // texture functions, old and new
    "textureSize", "textureQueryLod", "textureQueryLevels", "textureSamples", "texture", "textureProj",
    "textureLod", "textureOffset", "texelFetch", "texelFetchOffset", "textureProjOffset", "textureLodOffset",
    "textureProjLod", "textureProjLodOffset", "textureGrad", "textureGradOffset", "textureProjGrad",
    "textureProjGradOffset", "textureGather", "textureGatherOffset", "textureGatherOffsets", "texture1D",
    "texture2D", "texture3D", "textureCube", "shadow2D", "texture2DLod", "texture2DProj", "textureCubeLod",
    // atomics, images, derivatives, interpolation, geometry, barriers
    "atomicCounterIncrement", "atomicCounterDecrement", "atomicCounter", "atomicAdd", "atomicMin",
    "atomicMax", "atomicAnd", "atomicOr", "atomicXor", "atomicExchange", "atomicCompSwap", "imageSize",
    "imageSamples", "imageLoad", "imageStore", "imageAtomicAdd", "imageAtomicMin", "imageAtomicMax",
    "imageAtomicAnd", "imageAtomicOr", "imageAtomicXor", "imageAtomicExchange", "imageAtomicCompSwap", "dFdx",
    "dFdy", "dFdxFine", "dFdyFine", "dFdxCoarse", "dFdyCoarse", "fwidth", "fwidthFine", "fwidthCoarse",
    "interpolateAtCentroid", "interpolateAtSample", "interpolateAtOffset", "EmitStreamVertex",
    "EndStreamPrimitive", "EmitVertex", "EndPrimitive", "barrier", "memoryBarrier",
    "memoryBarrierAtomicCounter", "memoryBarrierBuffer", "memoryBarrierShared", "memoryBarrierImage",
    "groupMemoryBarrier", "anyInvocation", "allInvocations", "allInvocationsEqual",
};
// clang-format on

// The operators of GLSL (section 5.1), longest first so that the longest match wins.
const char* const kOperators[] = {
    "<<=", ">>=", "++", "--", "&&", "||", "^^", "==", "!=", "<=", ">=",
    "+=",  "-=",  "*=", "/=", "%=", "&=", "|=", "^=", "<<", ">>",
};
const std::string_view kSingleCharOperators = "+-*/%<>=!&|^~?:;,.(){}[]";

bool isIdentStart(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; }
bool isDigit(char c) { return c >= '0' && c <= '9'; }
bool isIdentChar(char c) { return isIdentStart(c) || isDigit(c); }
bool isHexDigit(char c) { return isDigit(c) || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F'); }
bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

class Lexer {
  public:
    explicit Lexer(std::string_view text) : s_(text) {}

    std::vector<Token> run() {
        std::vector<Token> out;
        out.reserve(s_.size() / 4);
        bool line_start = true;  // only blanks since the last newline: a '#' begins a directive
        while (i_ < s_.size()) {
            const char c = s_[i_];
            if (c == '\n') {
                ++line_;
                ++i_;
                line_start = true;
            } else if (isBlank(c)) {
                ++i_;
            } else if (c == '\\' && i_ + 1 < s_.size() && (s_[i_ + 1] == '\n' || s_[i_ + 1] == '\r')) {
                skipContinuation();
            } else if (c == '/' && peek(1) == '/') {
                skipLineComment();
            } else if (c == '/' && peek(1) == '*') {
                skipBlockComment();
            } else {
                out.push_back(next(line_start));
                line_start = false;
            }
        }
        return out;
    }

  private:
    char peek(std::size_t ahead) const { return i_ + ahead < s_.size() ? s_[i_ + ahead] : '\0'; }

    void skipContinuation() {
        ++i_;
        if (s_[i_] == '\r') ++i_;
        if (i_ < s_.size() && s_[i_] == '\n') ++i_;
        ++line_;
    }

    // To the end of the line; a backslash just before the newline continues the comment.
    void skipLineComment() {
        while (i_ < s_.size() && s_[i_] != '\n') {
            if (s_[i_] == '\\' && (peek(1) == '\n' || (peek(1) == '\r' && peek(2) == '\n'))) {
                skipContinuation();
                continue;
            }
            ++i_;
        }
    }

    void skipBlockComment() {
        i_ += 2;
        while (i_ < s_.size() && !(s_[i_] == '*' && peek(1) == '/')) {
            if (s_[i_] == '\n') ++line_;
            ++i_;
        }
        i_ = std::min(i_ + 2, s_.size());
    }

    Token make(TokenKind kind, std::size_t begin) const {
        return Token{kind, static_cast<std::uint32_t>(begin), static_cast<std::uint32_t>(i_), line_};
    }

    Token next(bool line_start) {
        const std::size_t begin = i_;
        const char c = s_[i_];
        if (c == '#' && line_start) {
            ++i_;
            while (i_ < s_.size() && isBlank(s_[i_])) ++i_;
            while (i_ < s_.size() && isIdentChar(s_[i_])) ++i_;
            return make(TokenKind::Preprocessor, begin);
        }
        if (isIdentStart(c)) {
            while (i_ < s_.size() && isIdentChar(s_[i_])) ++i_;
            const bool kept = isGlslKeywordOrBuiltin(s_.substr(begin, i_ - begin));
            return make(kept ? TokenKind::Keyword : TokenKind::Identifier, begin);
        }
        if (isDigit(c) || (c == '.' && isDigit(peek(1)))) return number(begin);
        if (c == '"') {
            ++i_;
            while (i_ < s_.size() && s_[i_] != '"' && s_[i_] != '\n') ++i_;
            if (i_ < s_.size() && s_[i_] == '"') ++i_;
            return make(TokenKind::String, begin);
        }
        for (const char* op : kOperators) {
            const std::string_view o(op);
            if (s_.compare(i_, o.size(), o) == 0) {
                i_ += o.size();
                return make(TokenKind::Operator, begin);
            }
        }
        if (kSingleCharOperators.find(c) != std::string_view::npos) {
            ++i_;
            return make(TokenKind::Operator, begin);
        }
        // Anything else (a stray '@', '$', '`', a byte of UTF-8): one token for the whole run.
        while (i_ < s_.size() && !isIdentChar(s_[i_]) && !isBlank(s_[i_]) && s_[i_] != '\n' &&
               s_[i_] != '"' && s_[i_] != '#' && s_[i_] != '\\' &&
               kSingleCharOperators.find(s_[i_]) == std::string_view::npos)
            ++i_;
        if (i_ == begin) ++i_;  // '#' in the middle of a line, a lone backslash
        return make(TokenKind::Other, begin);
    }

    // Decimal, octal and hexadecimal integers, floats with fraction and exponent, and the u, f and
    // lf suffixes (section 4.1.3 and 4.1.4).
    Token number(std::size_t begin) {
        if (s_[i_] == '0' && (peek(1) == 'x' || peek(1) == 'X')) {
            i_ += 2;
            while (i_ < s_.size() && isHexDigit(s_[i_])) ++i_;
        } else {
            while (i_ < s_.size() && isDigit(s_[i_])) ++i_;
            if (i_ < s_.size() && s_[i_] == '.') {
                ++i_;
                while (i_ < s_.size() && isDigit(s_[i_])) ++i_;
            }
            if (i_ < s_.size() && (s_[i_] == 'e' || s_[i_] == 'E')) {
                const std::size_t mark = i_;
                ++i_;
                if (i_ < s_.size() && (s_[i_] == '+' || s_[i_] == '-')) ++i_;
                if (i_ < s_.size() && isDigit(s_[i_])) {
                    while (i_ < s_.size() && isDigit(s_[i_])) ++i_;
                } else {
                    i_ = mark;  // "1e" followed by a name: the number ends before the e
                }
            }
        }
        while (i_ < s_.size() && (s_[i_] == 'u' || s_[i_] == 'U' || s_[i_] == 'f' || s_[i_] == 'F' ||
                                  s_[i_] == 'l' || s_[i_] == 'L'))
            ++i_;
        return make(TokenKind::Number, begin);
    }

    std::string_view s_;
    std::size_t i_ = 0;
    std::uint32_t line_ = 1;
};

}  // namespace

std::vector<Token> lexGlsl(std::string_view text) { return Lexer(text).run(); }

bool isGlslKeywordOrBuiltin(std::string_view word) {
    static const std::unordered_set<std::string_view> words(std::begin(kKeywords), std::end(kKeywords));
    return word.substr(0, 3) == "gl_" || words.count(word) != 0;
}

bool isGlslBlank(char c) { return isBlank(c); }

}  // namespace shaderlab::glsl
