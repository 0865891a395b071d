// Mesa's ways of pointing and naming, turned into the student's: a column of the preprocessor's
// output mapped back to the source line, and parser token names (BASIC_TYPE_TOK) in words. It
// reads no log line itself; the explainers and the link log call it.
#include <cctype>
#include <cstring>
#include <map>
#include <regex>

#include "glsl_explain_detail.h"

namespace shaderlab {

using glsl_detail::isBlank;

int sourceColumnOfMesa(const std::string& line, int mesa_column) {
    if (mesa_column <= 0) return 0;
    int count = 0;
    std::size_t p = 0;
    while (p < line.size()) {
        const bool gap = isBlank(line[p]) || line.compare(p, 2, "/*") == 0 || line.compare(p, 2, "//") == 0;
        if (!gap) {
            if (++count == mesa_column) return static_cast<int>(p) + 1;
            ++p;
            continue;
        }
        while (p < line.size()) {
            if (isBlank(line[p])) {
                ++p;
            } else if (line.compare(p, 2, "/*") == 0) {
                const auto end = line.find("*/", p + 2);
                p = end == std::string::npos ? line.size() : end + 2;
            } else if (line.compare(p, 2, "//") == 0) {
                p = line.size();
            } else {
                break;
            }
        }
        if (++count == mesa_column) return 0;
    }
    return 0;
}

namespace glsl_detail {

std::string tokenWords(const std::string& token) {
    if (token.size() >= 3 && token.front() == '\'' && token.back() == '\'')
        return "`" + token.substr(1, token.size() - 2) + "`";
    if (token == "end of file" || token == "$end") return "the end of the file";
    if (token == "NEWLINE") return "the end of the line";  // the preprocessor's
    if (token == "HASH_TOKEN") return "`#`";
    static const std::map<std::string, std::string> ops = {
        {"INC_OP", "++"},       {"DEC_OP", "--"},        {"LE_OP", "<="},      {"GE_OP", ">="},
        {"EQ_OP", "=="},        {"NE_OP", "!="},         {"AND_OP", "&&"},     {"OR_OP", "||"},
        {"XOR_OP", "^^"},       {"LEFT_OP", "<<"},       {"RIGHT_OP", ">>"},   {"MUL_ASSIGN", "*="},
        {"DIV_ASSIGN", "/="},   {"ADD_ASSIGN", "+="},    {"SUB_ASSIGN", "-="}, {"MOD_ASSIGN", "%="},
        {"LEFT_ASSIGN", "<<="}, {"RIGHT_ASSIGN", ">>="}, {"AND_ASSIGN", "&="}, {"XOR_ASSIGN", "^="},
        {"OR_ASSIGN", "|="}};
    const auto op = ops.find(token);
    if (op != ops.end()) return "`" + op->second + "`";
    if (token == "BASIC_TYPE_TOK") return "a type name";
    if (token.find("IDENTIFIER") != std::string::npos) return "a name";
    if (token == "FIELD_SELECTION") return "a field name";
    if (token == "BOOLCONSTANT") return "`true` or `false`";
    if (token.find("CONSTANT") != std::string::npos) return "a number";
    std::string word = token;
    for (const char* suffix : {"_TOKEN", "_TOK"}) {
        const std::size_t n = std::strlen(suffix);
        if (word.size() > n && word.compare(word.size() - n, n, suffix) == 0) word.resize(word.size() - n);
    }
    for (char& c : word) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return "`" + word + "`";
}

std::string scrubJargon(const std::string& s) {
    static const std::regex jargon(
        R"(\b(?:[A-Z][A-Z0-9]*_TOK(?:EN)?|(?:NEW_|TYPE_|FUNC_|OBJ_)?IDENTIFIER|[A-Z0-9]*CONSTANT|FIELD_SELECTION|[A-Z]+_(?:OP|ASSIGN))\b)");
    std::string out;
    auto begin = std::sregex_iterator(s.begin(), s.end(), jargon);
    std::size_t last = 0;
    for (auto it = begin; it != std::sregex_iterator(); ++it) {
        out += s.substr(last, static_cast<std::size_t>(it->position()) - last) + tokenWords(it->str());
        last = static_cast<std::size_t>(it->position() + it->length());
    }
    return out + s.substr(last);
}

}  // namespace glsl_detail

}  // namespace shaderlab
