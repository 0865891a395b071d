// GLSL source as tokens for the similarity report: a small lexer (identifiers, keywords and
// built-ins, numbers, operators, preprocessor directives, the strings of #include), comments and
// whitespace dropped, and each token's normalised hash, so that renaming a variable, reformatting
// or rewriting the comments changes nothing.
//
// It does not parse or preprocess: a macro is not expanded, a directive's rest of line is lexed
// like code, and any byte the language has no use for is one "other" token (a run of them, one).
// It never fails: any bytes in, tokens out.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace shaderlab::similarity {

enum class TokenKind {
    Identifier,    // a name the student chose: normalised to one class
    Keyword,       // a GLSL keyword, type, qualifier, built-in function or gl_ variable: kept
    Number,        // normalised to its value: 1.0, 1. and 1.0f are one token
    Operator,      // punctuation and operators, the longest match (<<=, ++, &&, ...)
    Preprocessor,  // '#' and the directive's name ("#define"): the rest of the line is lexed as code
    String,        // "..." (only #include has them)
    Other,         // a run of bytes GLSL has no use for
};

struct Token {
    TokenKind kind = TokenKind::Other;
    std::uint32_t begin = 0, end = 0;  // byte offsets into the text
    std::uint32_t line = 1;            // 1-based line of the first byte
};

// The tokens of `text`, comments and whitespace dropped. A line continuation (backslash, newline)
// is whitespace; a comment left open runs to the end of the text.
std::vector<Token> lexGlsl(std::string_view text);

// True for the words kept as themselves: GLSL 4.60 and ES 3.20 keywords, types and qualifiers, the
// built-in functions (normalize, dot, texture, ...) and every gl_ name.
bool isGlslKeywordOrBuiltin(std::string_view word);

// The normalised form of one token, as hashed: "$id" for every identifier, "#n:<value>" for a
// number (value printed with %.9g), the text itself otherwise ("#define" for a directive,
// whatever spacing stood between '#' and the name).
std::string normalisedToken(std::string_view text, const Token& token);

// 64-bit hashes (xxHash XXH3) of the normalised tokens, one per token.
std::vector<std::uint64_t> normalisedHashes(std::string_view text, const std::vector<Token>& tokens);

}  // namespace shaderlab::similarity
