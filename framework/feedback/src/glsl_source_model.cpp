// The student's source read the way the explanations need it: GLSL tokens without comments and
// preprocessor lines, the declarations a type and a name make, and lookups by line, column and
// name. It is no parser: it finds declarations and knows what stands at a column, nothing more.
#include <algorithm>
#include <cctype>
#include <regex>
#include <sstream>

#include "glsl_explain_detail.h"

namespace shaderlab::glsl_detail {

namespace {

constexpr std::size_t kMaxSourceLine = 240;  // a longer line is cut in a diagnostic

bool isNameStart(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool isNameChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }
bool isDigit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }

std::vector<std::string> splitLines(const std::string& text) {
    std::vector<std::string> lines;
    std::string line;
    std::istringstream in(text);
    while (std::getline(in, line)) {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        lines.push_back(line);
    }
    return lines;
}

// GLSL tokens of a file, without comments and preprocessor lines; enough to find declarations
// and to know what stands at a column, not a parser.
std::vector<Token> tokenize(const std::vector<std::string>& lines) {
    static const char* const kPairs[] = {"==", "!=", "<=", ">=", "&&", "||", "^^", "++", "--", "+=",
                                         "-=", "*=", "/=", "%=", "<<", ">>", "&=", "|=", "^="};
    std::vector<Token> out;
    bool in_block = false;
    for (std::size_t li = 0; li < lines.size(); ++li) {
        const std::string& s = lines[li];
        std::size_t p = 0;
        if (!in_block) {
            while (p < s.size() && isBlank(s[p])) ++p;
            if (p < s.size() && s[p] == '#') continue;
            p = 0;
        }
        while (p < s.size()) {
            if (in_block) {
                const auto end = s.find("*/", p);
                if (end == std::string::npos) break;
                in_block = false;
                p = end + 2;
                continue;
            }
            const char c = s[p];
            if (isBlank(c)) {
                ++p;
                continue;
            }
            if (s.compare(p, 2, "//") == 0) break;
            if (s.compare(p, 2, "/*") == 0) {
                in_block = true;
                p += 2;
                continue;
            }
            Token t;
            t.line = static_cast<int>(li) + 1;
            t.column = static_cast<int>(p) + 1;
            const std::size_t start = p;
            if (isNameStart(c)) {
                t.kind = Token::Name;
                while (p < s.size() && isNameChar(s[p])) ++p;
            } else if (isDigit(c) || (c == '.' && p + 1 < s.size() && isDigit(s[p + 1]))) {
                t.kind = Token::Number;
                const bool hex = s.compare(p, 2, "0x") == 0 || s.compare(p, 2, "0X") == 0;
                while (p < s.size()) {
                    const char d = s[p];
                    const bool exponent_sign =
                        (d == '+' || d == '-') && !hex && (s[p - 1] == 'e' || s[p - 1] == 'E');
                    if (!isNameChar(d) && d != '.' && !exponent_sign) break;
                    ++p;
                }
            } else {
                p = start + 1;
                for (const char* pair : kPairs)
                    if (s.compare(start, 2, pair) == 0) p = start + 2;
            }
            t.text = s.substr(start, p - start);
            out.push_back(std::move(t));
        }
    }
    return out;
}

// Past `[ ... ]` groups starting at i (array sizes after a type).
std::size_t skipArray(const std::vector<Token>& ts, std::size_t i) {
    while (i < ts.size() && ts[i].text == "[") {
        while (i < ts.size() && ts[i].text != "]") ++i;
        if (i < ts.size()) ++i;
    }
    return i;
}

// Declarations: a type (built-in or a struct of the file) followed by a name. Functions are
// names followed by '(' at global scope; their parameters are "param".
void collectDeclarations(StageModel& m) {
    std::set<std::string> structs;
    const std::size_t none = static_cast<std::size_t>(-1);
    for (std::size_t f = 0; f < m.tokens.size(); ++f) {
        const std::vector<Token>& ts = m.tokens[f];
        std::vector<bool> declares(ts.size(), false);
        int depth = 0, paren = 0;
        std::string storage;
        std::size_t header = none;  // the function whose parameters are being read
        auto declare = [&](std::size_t k, const std::string& type, const std::string& how, bool global) {
            m.decls.push_back({ts[k].text, type, how, f, ts[k].line, ts[k].column, global, false});
            declares[k] = true;
        };
        for (std::size_t i = 0; i < ts.size(); ++i) {
            const Token& t = ts[i];
            if (t.kind == Token::Symbol) {
                if (t.text == "{") {
                    if (depth == 0 && paren == 0 && header != none) m.decls[header].defined = true;
                    header = none;
                    ++depth;
                    storage.clear();
                } else if (t.text == "}") {
                    depth = std::max(0, depth - 1);
                    storage.clear();
                } else if (t.text == ";") {
                    storage.clear();
                    if (depth == 0) header = none;
                } else if (t.text == "(") {
                    ++paren;
                } else if (t.text == ")") {
                    paren = std::max(0, paren - 1);
                }
                continue;
            }
            if (t.kind != Token::Name) continue;
            if (isStorageWord(t.text)) {
                storage = t.text;
                continue;
            }
            if (t.text == "struct") {
                if (i + 1 < ts.size() && ts[i + 1].kind == Token::Name) {
                    structs.insert(ts[i + 1].text);
                    declare(i + 1, "struct", "struct", depth == 0);
                    ++i;
                }
                continue;
            }
            if (!builtinTypes().count(t.text) && !structs.count(t.text)) continue;
            if (i > 0 && ts[i - 1].text == ".") continue;
            const std::size_t j = skipArray(ts, i + 1);
            if (j >= ts.size() || ts[j].kind != Token::Name || isKeyword(ts[j].text) ||
                builtinTypes().count(ts[j].text))
                continue;
            if (j + 1 < ts.size() && ts[j + 1].text == "(" && depth == 0 && paren == 0) {
                header = m.decls.size();
                declare(j, t.text, "function", true);
                i = j;
                continue;
            }
            const bool param = depth == 0 && paren > 0;
            declare(j, t.text, param ? "param" : storage, depth == 0 && !param);
            if (!param) {  // more names after commas: `float a, b = 1.0;`
                int level = 0;
                for (std::size_t k = j + 1; k < ts.size(); ++k) {
                    const std::string& s = ts[k].text;
                    if (s == "(" || s == "[") {
                        ++level;
                    } else if (s == ")" || s == "]") {
                        if (--level < 0) break;
                    } else if (s == ";" || s == "{" || s == "}") {
                        break;
                    } else if (s == "," && level == 0 && k + 1 < ts.size() && ts[k + 1].kind == Token::Name &&
                               !isKeyword(ts[k + 1].text)) {
                        declare(k + 1, t.text, storage, depth == 0);
                    }
                }
            }
            i = j;
        }
        for (std::size_t i = 0; i < ts.size(); ++i)
            if (ts[i].kind == Token::Name && !declares[i] && !(i > 0 && ts[i - 1].text == "."))
                ++m.uses[ts[i].text];
    }
}

// The one token `text` on the line, or null when there is none or more than one.
const Token* onlyTokenOnLine(const StageModel& m, std::size_t file, int line, const std::string& text) {
    if (file >= m.tokens.size()) return nullptr;
    const Token* found = nullptr;
    for (const Token& t : m.tokens[file]) {
        if (t.line != line || t.text != text) continue;
        if (found) return nullptr;
        found = &t;
    }
    return found;
}

}  // namespace

StageModel buildModel(const StageText& t) {
    StageModel m;
    m.text = &t;
    for (const std::string& text : t.texts) {
        m.lines.push_back(splitLines(text));
        m.tokens.push_back(tokenize(m.lines.back()));
    }
    static const std::regex version(R"(^\s*#\s*version\s+(\d{1,6})\s*(\w*))");
    if (!m.lines.empty()) {
        for (const std::string& line : m.lines[0]) {
            std::smatch v;
            const std::string head = line.substr(0, 200);
            if (!std::regex_search(head, v, version)) continue;
            m.legacy_allowed = std::stoi(v[1]) < 130 || v[2] == "compatibility";
            break;
        }
    }
    collectDeclarations(m);
    // Names in preprocessor lines are uses too (`#define N normalize(v_normal)`).
    for (const std::vector<std::string>& lines : m.lines)
        for (const std::string& line : lines) {
            const std::size_t hash = line.find_first_not_of(" \t");
            if (hash == std::string::npos || line[hash] != '#') continue;
            for (std::size_t p = hash + 1; p < line.size();) {
                if (!isNameStart(line[p])) {
                    ++p;
                    continue;
                }
                const std::size_t start = p;
                while (p < line.size() && isNameChar(line[p])) ++p;
                ++m.uses[line.substr(start, p - start)];
            }
        }
    return m;
}

const std::string* lineOf(const StageModel& m, std::size_t file, int line) {
    if (file >= m.lines.size() || line < 1 || static_cast<std::size_t>(line) > m.lines[file].size())
        return nullptr;
    return &m.lines[file][static_cast<std::size_t>(line) - 1];
}

const Token* tokenAt(const StageModel& m, std::size_t file, int line, int column) {
    if (file >= m.tokens.size()) return nullptr;
    for (const Token& t : m.tokens[file])
        if (t.line == line && t.column == column) return &t;
    return nullptr;
}

int caretFor(const StageModel& m, std::size_t file, int line, int mesa_column, const std::string& name) {
    const std::string* text = lineOf(m, file, line);
    if (!text) return 0;
    const int col = sourceColumnOfMesa(*text, mesa_column);
    if (col > 0) {
        const Token* t = tokenAt(m, file, line, col);
        if (t && (name.empty() || t->text == name)) return col;
    }
    if (name.empty()) return 0;
    const Token* only = onlyTokenOnLine(m, file, line, name);
    return only ? only->column : 0;
}

const Decl* findDecl(const StageModel& m, const std::string& name, bool functions) {
    for (const Decl& d : m.decls)
        if (d.name == name && (d.storage == "function") == functions) return &d;
    return nullptr;
}

const Decl* findGlobal(const StageModel& m, const std::string& name,
                       std::initializer_list<const char*> storages) {
    for (const Decl& d : m.decls) {
        if (d.name != name || !d.global) continue;
        for (const char* s : storages)
            if (d.storage == s) return &d;
    }
    return nullptr;
}

void attachSource(Diagnostic& d, const StageModel& m, std::size_t file) {
    const std::string* text = lineOf(m, file, d.line);
    d.source_line = text ? *text : "";
    if (d.source_line.size() > kMaxSourceLine) {
        d.source_line.resize(kMaxSourceLine);
        d.source_line += " ...";
    }
    if (d.source_line.empty() || d.column < 0 ||
        static_cast<std::size_t>(d.column) > std::min(kMaxSourceLine, d.source_line.size() + 1))
        d.column = 0;
}

}  // namespace shaderlab::glsl_detail
