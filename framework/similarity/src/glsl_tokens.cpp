// The similarity report's normalised tokens; see glsl_tokens.h.
#include "shaderlab/similarity/glsl_tokens.h"

#include <xxhash.h>

#include <cstdio>
#include <cstdlib>

namespace shaderlab::similarity {

namespace {

// The value of a number token, printed so that spellings of one value agree.
std::string numberValue(std::string_view spelled) {
    std::string digits(spelled);
    const bool hex = digits.size() > 1 && (digits[1] == 'x' || digits[1] == 'X');
    // The suffixes u, f, lf (F is a hexadecimal digit, and hexadecimal numbers take only u).
    const std::string_view suffixes = hex ? "uU" : "uUfFlL";
    while (!digits.empty() && suffixes.find(digits.back()) != std::string_view::npos) digits.pop_back();
    double value = 0.0;
    const bool integer = hex || digits.find_first_of(".eE") == std::string::npos;
    if (integer) {
        // strtoull with base 0 reads 0x.. as hexadecimal and 0.. as octal, as GLSL does.
        value = static_cast<double>(std::strtoull(digits.c_str(), nullptr, 0));
    } else {
        value = std::strtod(digits.c_str(), nullptr);
    }
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.9g", value);
    return buf;
}

}  // namespace

std::string normalisedToken(std::string_view text, const Token& token) {
    const std::string_view spelled = text.substr(token.begin, token.end - token.begin);
    switch (token.kind) {
        case TokenKind::Identifier:
            return "$id";
        case TokenKind::Number:
            return "#n:" + numberValue(spelled);
        case TokenKind::Preprocessor: {
            std::string name = "#";
            for (char c : spelled.substr(1))
                if (!glsl::isGlslBlank(c)) name += c;
            return name;
        }
        case TokenKind::Other:
            return "$other";
        default:
            return std::string(spelled);
    }
}

std::vector<std::uint64_t> normalisedHashes(std::string_view text, const std::vector<Token>& tokens) {
    std::vector<std::uint64_t> out;
    out.reserve(tokens.size());
    // Identifiers are most tokens: their one hash is computed once.
    static const std::uint64_t identifier_hash = XXH3_64bits("$id", 3);
    for (const Token& t : tokens) {
        if (t.kind == TokenKind::Identifier) {
            out.push_back(identifier_hash);
            continue;
        }
        const std::string n = normalisedToken(text, t);
        out.push_back(XXH3_64bits(n.data(), n.size()));
    }
    return out;
}

}  // namespace shaderlab::similarity
