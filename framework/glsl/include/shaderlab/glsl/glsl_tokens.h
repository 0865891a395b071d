// GLSL source as tokens: a small lexer (identifiers, keywords and built-ins, numbers, operators,
// preprocessor directives, the strings of #include), comments and whitespace dropped. Used by the
// similarity report (which normalises the tokens) and by goal isolation (which reads a shader's
// top-level declarations, glsl_outline.h).
//
// It does not parse or preprocess: a macro is not expanded, a directive's rest of line is lexed
// like code, and any byte the language has no use for is one "other" token (a run of them, one).
// It never fails: any bytes in, tokens out.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace shaderlab::glsl {

enum class TokenKind {
    Identifier,    // a name the author chose
    Keyword,       // a GLSL keyword, type, qualifier, built-in function or gl_ variable
    Number,        // an integer or floating-point literal, suffix included
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
// built-in functions (normalize, dot, texture, ...) and every gl_ name. `main` is one too.
bool isGlslKeywordOrBuiltin(std::string_view word);

// The text of one token.
inline std::string_view tokenText(std::string_view text, const Token& t) {
    return text.substr(t.begin, t.end - t.begin);
}

// True for a blank other than a newline (what the lexer skips between tokens on one line).
bool isGlslBlank(char c);

}  // namespace shaderlab::glsl
