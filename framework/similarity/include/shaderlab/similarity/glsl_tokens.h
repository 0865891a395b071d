// GLSL tokens as the similarity report compares them (the lexer is shaderlab/glsl/glsl_tokens.h):
// comments and whitespace dropped, and each token's normalised hash, so that renaming a variable,
// reformatting or rewriting the comments changes nothing.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "shaderlab/glsl/glsl_tokens.h"

namespace shaderlab::similarity {

using glsl::isGlslKeywordOrBuiltin;
using glsl::lexGlsl;
using glsl::Token;
using glsl::TokenKind;

// The normalised form of one token, as hashed: "$id" for every identifier (a name the student
// chose: normalised to one class), "#n:<value>" for a number (value printed with %.9g: 1.0, 1. and
// 1.0f are one token), the text itself otherwise ("#define" for a directive, whatever spacing
// stood between '#' and the name), "$other" for bytes GLSL has no use for.
std::string normalisedToken(std::string_view text, const Token& token);

// 64-bit hashes (xxHash XXH3) of the normalised tokens, one per token.
std::vector<std::uint64_t> normalisedHashes(std::string_view text, const std::vector<Token>& tokens);

}  // namespace shaderlab::similarity
