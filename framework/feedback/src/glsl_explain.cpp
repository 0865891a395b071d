// GLSL compile and link logs in plain words; see glsl_explain.h. The message patterns are Mesa
// 22.3's (src/compiler/glsl/ast_to_hir.cpp, ast_function.cpp, linker.cpp, link_varyings.cpp).
#include "shaderlab/feedback/glsl_explain.h"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <map>
#include <optional>
#include <regex>
#include <set>
#include <sstream>

#include "shaderlab/base/json_messages.h"

namespace shaderlab {

namespace {

constexpr std::size_t kMaxSourceLine = 240;  // a longer line is cut in a diagnostic
constexpr std::size_t kMaxNameLength = 64;   // names in messages; a student can write any length
constexpr std::size_t kMaxCandidates = 3;    // function signatures shown in an explanation

bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }
bool isNameStart(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool isNameChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }
bool isDigit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }

std::string quote(const std::string& s) {
    return "`" + (s.size() > kMaxNameLength ? s.substr(0, kMaxNameLength) + "..." : s) + "`";
}

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

std::string trim(const std::string& s) {
    std::size_t a = 0, b = s.size();
    while (a < b && isBlank(s[a])) ++a;
    while (b > a && isBlank(s[b - 1])) --b;
    return s.substr(a, b - a);
}

std::string firstLine(const std::string& s) { return s.substr(0, s.find('\n')); }

// "a, b, c" -> {"a", "b", "c"}; "" -> {}.
std::vector<std::string> splitList(const std::string& s) {
    std::vector<std::string> out;
    if (trim(s).empty()) return out;
    std::string item;
    std::istringstream in(s);
    while (std::getline(in, item, ',')) out.push_back(trim(item));
    return out;
}

// ---- the student's source, tokenized ---------------------------------------------------------

struct Token {
    enum Kind { Name, Number, Symbol } kind = Symbol;
    std::string text;
    int line = 0;    // 1-based
    int column = 0;  // 1-based, in the source line
};

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

// Components of a scalar or vector type (0 for anything else) and its scalar kind.
int components(const std::string& type) {
    if (type == "float" || type == "int" || type == "uint" || type == "bool" || type == "double") return 1;
    static const std::regex vec(R"([biud]?vec([234]))");
    std::smatch m;
    return std::regex_match(type, m, vec) ? m[1].str()[0] - '0' : 0;
}

char scalarKind(const std::string& type) {
    if (type == "float" || type.rfind("vec", 0) == 0) return 'f';
    if (type == "int" || type.rfind("ivec", 0) == 0) return 'i';
    if (type == "uint" || type.rfind("uvec", 0) == 0) return 'u';
    if (type == "bool" || type.rfind("bvec", 0) == 0) return 'b';
    if (type == "double" || type.rfind("dvec", 0) == 0) return 'd';
    return '?';
}

struct Decl {
    std::string name, type;
    // in, out, inout, uniform, const, attribute, varying; "param", "function", "struct"; "" for a
    // plain variable
    std::string storage;
    std::size_t file = 0;
    int line = 0, column = 0;
    bool global = false;
    bool defined = false;  // a function with a body
};

struct StageModel {
    const StageText* text = nullptr;
    std::vector<std::vector<std::string>> lines;  // by file
    std::vector<std::vector<Token>> tokens;       // by file
    std::vector<Decl> decls;
    std::map<std::string, int> uses;  // mentions that neither declare the name nor select a field
    bool legacy_allowed = false;      // #version below 130 or a compatibility profile
};

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

std::size_t fileIndex(const StageModel& m, const std::string& file) {
    for (std::size_t i = 0; i < m.text->files.size(); ++i)
        if (m.text->files[i] == file) return i;
    return 0;
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

// Where a diagnostic about `name` belongs on its line: Mesa's column, when a token starts there
// and is `name` (any token when `name` is empty); else the one `name` on the line; else 0.
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

std::vector<std::string> variableNames(const StageModel& m) {
    std::vector<std::string> names;
    for (const Decl& d : m.decls)
        if (d.storage != "function" && d.storage != "struct") names.push_back(d.name);
    names.insert(names.end(), builtinVariables().begin(), builtinVariables().end());
    return names;
}

bool knownName(const StageModel& m, const std::string& name) {
    for (const Decl& d : m.decls)
        if (d.name == name) return true;
    const auto& f = builtinFunctions();
    const auto& v = builtinVariables();
    return builtinTypes().count(name) || isKeyword(name) || std::find(f.begin(), f.end(), name) != f.end() ||
           std::find(v.begin(), v.end(), name) != v.end();
}

// Mesa's parser token names, in words.
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

// Replaces parser token names that slipped into a message (the safety net behind every rewrite).
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

// "did you mean" only for names long enough that a near miss means something (for `v`, every
// one-letter name is one edit away).
std::string suggestion(const std::string& word, const std::vector<std::string>& candidates) {
    return word.size() < 3 ? std::string() : closestMatch(word, candidates);
}

std::string indentOf(const std::string& line) {
    std::size_t n = 0;
    while (n < line.size() && isBlank(line[n])) ++n;
    return line.substr(0, n);
}

// The right-hand side of `x = rhs;` on a line, when short enough to quote in an example.
std::string assignedValue(const std::string& line) {
    for (std::size_t p = 0; p < line.size(); ++p) {
        if (line[p] != '=') continue;
        if (p + 1 < line.size() && line[p + 1] == '=') return "";
        if (p > 0 && std::strchr("=!<>+-*/%&|^", line[p - 1])) return "";
        std::string rhs = line.substr(p + 1);
        const auto end = rhs.find(';');
        if (end == std::string::npos) return "";
        rhs = trim(rhs.substr(0, end));
        return rhs.size() <= 60 ? rhs : "";
    }
    return "";
}

// `value.xyz` (or `(value).xyz` when value is more than one name or call).
std::string swizzled(const std::string& value, int n) {
    const bool colour = value.find("texture") != std::string::npos;
    const std::string mask =
        (colour ? std::string("rgba") : std::string("xyzw")).substr(0, static_cast<std::size_t>(n));
    static const std::regex simple(R"(\w+(\(.*\))?)");
    bool single = std::regex_match(value, simple);
    if (single && value.back() == ')') {  // f(a) + g(b) matches the regex too: check the brackets
        int level = 0;
        for (std::size_t i = value.find('('); i < value.size(); ++i) {
            level += value[i] == '(' ? 1 : value[i] == ')' ? -1 : 0;
            if (level == 0 && i + 1 < value.size()) single = false;
        }
    }
    return (single ? value : "(" + value + ")") + "." + mask;
}

// How to turn a `from` into a `to`, for the type-mismatch explanations.
std::string conversionAdvice(const std::string& from, const std::string& to, const std::string& value) {
    const int a = components(from), b = components(to);
    const char ka = scalarKind(from), kb = scalarKind(to);
    const std::string v = value.empty() ? "value" : value;
    // The most common case of all: a texture() result stored in a vec3.
    const std::string texture = from == "vec4" && value.find("texture") != std::string::npos
                                    ? "texture() always returns a vec4. "
                                    : "";
    if (a > 0 && b > 0 && ka == kb && a > b)
        return texture +
               "GLSL never drops components by itself: keep the ones you need with a swizzle, e.g. " +
               quote(swizzled(v, b)) + ", or make the variable a " + from + " if you need them all.";
    if (a == 1 && b > 1 && ka == kb)
        return "A single value does not become a vector by itself: write " + quote(to + "(" + v + ")") +
               " to repeat it in every component.";
    if (a > 0 && b > 0 && ka == kb && a < b) {
        std::string rest;
        for (int i = a; i < b; ++i) rest += i + 1 == b && b == 4 ? ", 1.0" : ", 0.0";
        return "GLSL never changes a vector's size by itself: build the " + to + " from the " + from +
               " and the missing component" + (b - a > 1 ? "s" : "") + ", e.g. " +
               quote(to + "(" + v + rest + ")") + ".";
    }
    if ((ka == 'f' || ka == 'd') && (kb == 'i' || kb == 'u'))
        return "GLSL turns an int into a float by itself, but never a float into an int: write " +
               quote(to + "(" + v + ")") + " (it drops the fraction), or make the variable a " +
               (b > 1 ? "vec" + std::to_string(b) : std::string("float")) + ".";
    return "The value's type must be the variable's: convert it explicitly, e.g. " +
           quote(to + "(" + v + ")") + ", or change one of the two types.";
}

// ---- compile errors --------------------------------------------------------------------------

struct Ctx {
    const StageModel& m;
    const StageModel* other;
};

// "this `{` is never closed", at the `{` most likely missing its `}`: the first block whose `}`
// is indented differently from its opening line (that `}` was meant for an outer block), else the
// outermost block still open at the end.
bool explainUnclosed(Diagnostic& d, const Ctx& c, std::size_t f, int noticed_line) {
    if (f >= c.m.tokens.size()) return false;
    std::vector<const Token*> open;
    const Token* suspect = nullptr;
    const Token* suspect_close = nullptr;
    for (const Token& t : c.m.tokens[f]) {
        if (t.text == "{") {
            open.push_back(&t);
        } else if (t.text == "}" && !open.empty()) {
            const Token* o = open.back();
            open.pop_back();
            if (!suspect && o->line != t.line &&
                indentOf(*lineOf(c.m, f, o->line)) != indentOf(*lineOf(c.m, f, t.line))) {
                suspect = o;
                suspect_close = &t;
            }
        }
    }
    if (open.empty()) return false;
    const Token* at = suspect ? suspect : open.front();
    d.line = at->line;
    d.column = at->column;
    d.message = "this `{` is never closed: a `}` is missing";
    d.explanation = "The file ends (line " + std::to_string(noticed_line) +
                    ") while the block opened here is still open.";
    if (suspect)
        d.explanation += " The `}` on line " + std::to_string(suspect_close->line) +
                         " closes it, but is indented like an outer block's: it was probably meant for that "
                         "one, and this block lacks its own `}`.";
    else
        d.explanation += " Add its `}` where the block should end.";
    return true;
}

void explainSyntax(Diagnostic& d, const Ctx& c, std::size_t f, const std::string& unexpected,
                   const std::string& expecting) {
    const std::string* text = lineOf(c.m, f, d.line);
    const int col = text ? sourceColumnOfMesa(*text, d.column) : 0;
    const Token* found = col > 0 ? tokenAt(c.m, f, d.line, col) : nullptr;
    const std::string what = found ? quote(found->text) : tokenWords(unexpected);
    const int noticed = d.line;
    d.column = 0;
    if ((unexpected == "end of file" || unexpected == "$end") && explainUnclosed(d, c, f, noticed)) return;
    const bool wants_semicolon = expecting.find("';'") != std::string::npos;
    if (found && wants_semicolon && found != c.m.tokens[f].data()) {
        const Token& prev = *(found - 1);
        if (prev.kind == Token::Name && found->kind == Token::Name && prev.line == found->line &&
            !knownName(c.m, prev.text)) {
            std::vector<std::string> types(builtinTypes().begin(), builtinTypes().end());
            for (const Decl& s : c.m.decls)
                if (s.storage == "struct") types.push_back(s.name);
            const std::string guess = suggestion(prev.text, types);
            d.column = prev.column;
            d.message = quote(prev.text) + " is not a type" +
                        (guess.empty() ? "" : "; did you mean " + quote(guess) + "?");
            d.explanation = "A declaration starts with a type (float, vec3, ...) and then the name; " +
                            quote(prev.text) + " is neither a type nor a name declared before this line.";
            return;
        }
        if (prev.text != ";" && prev.text != "{") {
            d.line = prev.line;
            d.column = prev.column + static_cast<int>(prev.text.size());
            const bool earlier = prev.line < noticed;
            d.message = earlier ? "missing `;` at the end of this line" : "missing `;` before " + what;
            d.explanation = "Every statement ends with `;`.";
            if (earlier)
                d.explanation += " The compiler noticed only on line " + std::to_string(noticed) + ", at " +
                                 what + ", where it expected this statement to go on.";
            return;
        }
    }
    if (found && !wants_semicolon && expecting.find("')'") != std::string::npos) {
        d.column = col;
        d.message = "missing `)` before " + what;
        d.explanation = "Every `(` needs its `)`: the compiler reached " + what +
                        " with a bracket still open. Count the brackets of this statement.";
        return;
    }
    d.column = found ? col : 0;
    d.message = "the compiler did not expect " + what + " here";
    int opens = 0, closes = 0;
    if (f < c.m.tokens.size())
        for (const Token& t : c.m.tokens[f])
            if (t.line == d.line) {
                opens += t.text == "(";
                closes += t.text == ")";
            }
    if (closes > opens)
        d.explanation = "This line closes more brackets than it opens (" + std::to_string(opens) + " `(`, " +
                        std::to_string(closes) + " `)`): a `)` too many ends an expression early.";
    else if (opens > closes)
        d.explanation = "This line opens more brackets than it closes (" + std::to_string(opens) + " `(`, " +
                        std::to_string(closes) + " `)`): a `)` is missing.";
    else
        d.explanation =
            "Look just before it: a missing `;`, `)` or operator, a misspelt keyword or type, or a "
            "bracket too many.";
}

void explainUndeclared(Diagnostic& d, const Ctx& c, std::size_t f, const std::string& name) {
    d.column = caretFor(c.m, f, d.line, d.column, name);
    const Decl* here = findDecl(c.m, name, false);
    if (here && here->file == f && here->line > d.line) {
        d.message = quote(name) + " is used before it is declared";
        d.explanation =
            quote(name) + " is declared on line " + std::to_string(here->line) +
            ", below this use. GLSL reads top to bottom: move the declaration above its first use.";
        return;
    }
    if (here && !here->global) {
        d.message = quote(name) + " is not visible here";
        d.explanation =
            quote(name) + " is declared on line " + std::to_string(here->line) +
            " inside a `{ }` block (a function, an if or a loop) and exists only until that block's "
            "`}`. Declare it where every use can see it.";
        return;
    }
    const Decl* there = c.other ? findDecl(*c.other, name, false) : nullptr;
    if (there && there->global) {
        const std::string& other_file = c.other->text->files[there->file];
        d.message = quote(name) + " is declared in " + other_file + ", not in this stage";
        if (there->storage == "uniform")
            d.explanation = "Each stage declares what it uses: add `uniform " + there->type + " " + name +
                            ";` to this file too (the program sets it for both stages).";
        else
            d.explanation =
                "Each stage has its own variables. To pass a value from the vertex stage to the "
                "fragment stage, declare `out " +
                there->type +
                " v_...;` in the vertex shader, "
                "write it there, and declare the same `in` here.";
        return;
    }
    std::vector<std::string> names = variableNames(c.m);
    names.erase(std::remove(names.begin(), names.end(), name), names.end());
    const std::string guess = suggestion(name, names);
    d.message =
        quote(name) + " is not declared" + (guess.empty() ? "" : "; did you mean " + quote(guess) + "?");
    d.explanation =
        "Every name must be declared before it is used and spelt the same way each time (GLSL is "
        "case-sensitive).";
}

void explainNoFunction(Diagnostic& d, const Ctx& c, std::size_t f, const std::string& name) {
    d.column = caretFor(c.m, f, d.line, d.column, name);
    const Decl* later = findDecl(c.m, name, true);
    if (later) {
        d.message = quote(name) + " is called before it is declared";
        d.explanation = quote(name) + " is defined on line " + std::to_string(later->line) +
                        ", below this call. GLSL reads top to bottom: move the function above its first use, "
                        "or declare it above with a prototype (its first line, ending in `;`).";
        return;
    }
    std::vector<std::string> names = builtinFunctions();
    for (const Decl& decl : c.m.decls)
        if (decl.storage == "function") names.push_back(decl.name);
    const std::string guess = suggestion(name, names);
    d.message =
        "there is no function " + quote(name) + (guess.empty() ? "" : "; did you mean " + quote(guess) + "?");
    d.explanation =
        "A call needs a built-in function (normalize, dot, mix, ...) or one defined above the call, "
        "spelt exactly the same.";
}

std::string argumentCount(std::size_t n) { return std::to_string(n) + (n == 1 ? " argument" : " arguments"); }

void explainNoMatch(Diagnostic& d, const Ctx& c, std::size_t f, const std::string& name,
                    const std::string& args_text) {
    d.column = caretFor(c.m, f, d.line, d.column, name);
    const std::vector<std::string> args = splitList(args_text);
    struct Candidate {
        std::string text;
        std::vector<std::string> params;
        int score = 0;
    };
    std::vector<Candidate> candidates;
    static const std::regex signature(R"(^\s*(\w+)\s+(\w+)\((.*)\)\s*$)");
    std::istringstream lines(d.driver_message);
    std::string line;
    std::getline(lines, line);  // the "no matching function" line itself
    while (std::getline(lines, line)) {
        std::smatch m;
        if (!std::regex_match(line, m, signature)) continue;
        Candidate cand{trim(line), splitList(m[3]), 0};
        for (std::string& p : cand.params)
            for (const char* q : {"in ", "out ", "inout ", "const "})
                if (p.rfind(q, 0) == 0) p = p.substr(std::strlen(q));
        candidates.push_back(std::move(cand));
    }
    std::set<std::size_t> counts;
    for (const Candidate& cand : candidates) counts.insert(cand.params.size());
    const bool count_fits = counts.count(args.size()) > 0;
    for (Candidate& cand : candidates) {
        const int diff = static_cast<int>(cand.params.size()) - static_cast<int>(args.size());
        cand.score = -10 * std::abs(diff);
        for (std::size_t i = 0; i < std::min(args.size(), cand.params.size()); ++i)
            cand.score += cand.params[i] == args[i];
    }
    std::stable_sort(candidates.begin(), candidates.end(),
                     [](const Candidate& a, const Candidate& b) { return a.score > b.score; });
    std::string closest;
    for (std::size_t i = 0; i < std::min(kMaxCandidates, candidates.size()); ++i)
        closest += (i ? ", " : "") + quote(candidates[i].text);
    if (!count_fits && !counts.empty()) {
        std::string list;
        std::size_t i = 0;
        for (std::size_t n : counts)
            list += (i++ == 0 ? "" : i == counts.size() ? " or " : ", ") + std::to_string(n);
        d.message = quote(name) + " takes " + list +
                    (counts.size() == 1 && *counts.begin() == 1 ? " argument" : " arguments") + ", not " +
                    std::to_string(args.size());
        d.explanation =
            "This call passes " + argumentCount(args.size()) + ". The closest forms: " + closest + ".";
        return;
    }
    std::string given;
    for (std::size_t i = 0; i < args.size(); ++i) given += (i ? ", " : "") + args[i];
    d.message = "no form of " + quote(name) + " takes (" + given + ")";
    d.explanation = (closest.empty() ? std::string() : "The closest: " + closest + ". ") +
                    "Check each argument's type: GLSL turns an int into a float by itself, but never changes "
                    "a vector's size.";
}

void explainAssignment(Diagnostic& d, const Ctx& c, std::size_t f, bool initializer, const std::string& from,
                       const std::string& to) {
    const std::string* text = lineOf(c.m, f, d.line);
    const int col = text ? sourceColumnOfMesa(*text, d.column) : 0;
    const Token* at = col > 0 ? tokenAt(c.m, f, d.line, col) : nullptr;
    std::string target;
    if (at && !initializer && at->kind == Token::Name) target = at->text;
    if (at && initializer && at != c.m.tokens[f].data() + c.m.tokens[f].size() - 1 &&
        (at + 1)->kind == Token::Name)
        target = (at + 1)->text;
    d.column = at ? col : 0;
    if (initializer)
        d.message =
            "cannot initialise the " + to + (target.empty() ? "" : " " + quote(target)) + " with a " + from;
    else
        d.message =
            "cannot assign a " + from + " to " + (target.empty() ? "a " + to : quote(target) + ", a " + to);
    d.explanation = conversionAdvice(from, to, text ? assignedValue(*text) : "");
    const Decl* out = target.empty() ? nullptr : findGlobal(c.m, target, {"out"});
    if (out && c.m.text->stage == "fragment")
        d.explanation += " " + quote(target) + " is the " + to +
                         " output the framework stores: its fourth "
                         "component is alpha.";
}

void explainReadOnly(Diagnostic& d, const Ctx& c, std::size_t f, const std::string& name) {
    d.column = caretFor(c.m, f, d.line, d.column, name);
    const Decl* decl = findGlobal(c.m, name, {"in", "varying", "attribute", "uniform", "const"});
    const std::string how = decl ? decl->storage : "";
    const std::string type = decl ? decl->type : "vec3";
    if (how == "in" || how == "varying" || how == "attribute") {
        d.message = quote(name) + " is an input and cannot be changed";
        d.explanation = "Inputs are read-only. Copy it into a local variable and change that, e.g. `" + type +
                        " n = normalize(" + name + ");`.";
    } else if (how == "uniform") {
        d.message = quote(name) + " is a uniform and cannot be changed";
        d.explanation =
            "Uniforms are set by the program and read-only in the shader. Copy it into a local "
            "variable and change that.";
    } else if (how == "const") {
        d.message = quote(name) + " is a constant and cannot be changed";
        d.explanation = "Drop `const` from its declaration, or use a new variable.";
    } else {
        d.message = quote(name) + " cannot be changed here";
        d.explanation = "It is read-only (an input, a uniform or a constant): copy it into a local variable.";
    }
}

void explainRedeclared(Diagnostic& d, const Ctx& c, std::size_t f, const std::string& name) {
    d.column = caretFor(c.m, f, d.line, d.column, name);
    const Decl* first = nullptr;
    for (const Decl& decl : c.m.decls)
        if (decl.name == name && decl.file == f && decl.line < d.line) first = first ? first : &decl;
    d.message = quote(name) + " is declared twice" +
                (first ? " (first on line " + std::to_string(first->line) + ")" : std::string());
    d.explanation =
        "A name is declared once per block. To change the existing variable, assign without the "
        "type (`" +
        name + " = ...;`); otherwise pick another name.";
}

// A column for a diagnostic about the expression Mesa points at: its first token.
int expressionCaret(const Ctx& c, const Diagnostic& d, std::size_t f) {
    return caretFor(c.m, f, d.line, d.column, "");
}

// Rewrites one error or warning of a stage. `d.column` is Mesa's on entry.
void explainOne(Diagnostic& d, const Ctx& c) {
    const std::size_t f = fileIndex(c.m, d.file);
    const std::string msg = firstLine(d.message);
    std::smatch m;
    static const std::regex syntax(R"(^syntax error, unexpected (.+?)(?:, expecting (.+))?$)");
    static const std::regex undeclared(R"(^`(\w+)' undeclared$)");
    static const std::regex no_function(R"(^no function with name '(\w+)'$)");
    static const std::regex no_match(
        R"(^no matching function for call to `(\w+)\((.*)\)'(?:; candidates are:)?$)");
    static const std::regex assign(
        R"(^(initializer|value) of type (\w+) cannot be assigned to variable of type (\w+)$)");
    static const std::regex no_return(
        R"(^function `(\w+)' has non-void return type (\w+), but no return statement$)");
    static const std::regex read_only(R"(^assignment to read-only variable '(\w+)'$)");
    static const std::regex redeclared(R"(^`(\w+)' redeclared$)");
    static const std::regex swizzle(R"(^invalid swizzle / mask `(\w+)'$)");
    static const std::regex field(R"(^cannot access field `(\w+)' of non-structure / non-vector$)");
    static const std::regex too_few(R"(^too few components to construct `(\w+)'$)");
    static const std::regex too_many(
        R"(^too many (?:parameters to `(\w+)' constructor|components to construct `(\w+)')$)");
    static const std::regex wrong_return(
        R"(^`return' with wrong type (\w+), in function `(\w+)' returning (\w+)$)");
    static const std::regex uninitialized(R"(^`(\w+)' used uninitialized$)");
    if (std::regex_match(msg, m, syntax)) return explainSyntax(d, c, f, m[1], m[2]);
    if (std::regex_match(msg, m, undeclared)) return explainUndeclared(d, c, f, m[1]);
    if (std::regex_match(msg, m, no_function)) return explainNoFunction(d, c, f, m[1]);
    if (std::regex_match(msg, m, no_match)) return explainNoMatch(d, c, f, m[1], m[2]);
    if (std::regex_match(msg, m, assign))
        return explainAssignment(d, c, f, m[1] == "initializer", m[2], m[3]);
    if (std::regex_match(msg, m, read_only)) return explainReadOnly(d, c, f, m[1]);
    if (std::regex_match(msg, m, redeclared)) return explainRedeclared(d, c, f, m[1]);
    if (std::regex_match(msg, m, no_return)) {
        d.column = caretFor(c.m, f, d.line, 0, m[1]);
        d.message = quote(m[1]) + " must return a " + m[2].str() + ", but has no `return`";
        d.explanation =
            "A function with a result type ends every path with `return <value>;`: return the value "
            "you computed, or declare the function `void` if it only has effects.";
        return;
    }
    if (std::regex_match(msg, m, wrong_return)) {
        d.column = expressionCaret(c, d, f);
        d.message = quote(m[2]) + " returns a " + m[3].str() + ", but this `return` gives a " + m[1].str();
        d.explanation = conversionAdvice(m[1], m[3], "");
        return;
    }
    if (std::regex_match(msg, m, swizzle) || std::regex_match(msg, m, field)) {
        const bool is_field = msg.rfind("cannot access field", 0) == 0;
        d.column = 0;
        if (f < c.m.tokens.size()) {
            const std::vector<Token>& ts = c.m.tokens[f];
            for (std::size_t i = 1; i < ts.size(); ++i)
                if (ts[i].line == d.line && ts[i].text == m[1] && ts[i - 1].text == ".")
                    d.column = d.column ? -1 : ts[i].column;
            d.column = std::max(0, d.column);
        }
        if (is_field) {
            d.message = quote("." + m[1].str()) +
                        " cannot be taken of this value: it is neither a vector nor a struct";
            d.explanation =
                "Only vectors have components (.x .y ...) and only structs have fields; a float or an int "
                "has neither. Check the type the value was declared with.";
            return;
        }
        d.message = quote("." + m[1].str()) + " is not a component of this value";
        d.explanation =
            "A vec2 has .x .y, a vec3 .x .y .z, a vec4 .x .y .z .w (or .rgba, or .stpq: one set at a "
            "time); a float has no components.";
        return;
    }
    if (std::regex_match(msg, m, too_few)) {
        const std::string type = m[1];
        d.column = caretFor(c.m, f, d.line, d.column, type);
        const int n = components(type);
        d.message = quote(type + "(...)") + " is given too few components";
        d.explanation = "The arguments of a constructor add up to its size" +
                        (n > 1 ? ": a " + type + " needs " + std::to_string(n) : std::string()) +
                        (type == "vec4" ? " (`vec4(v_normal, 1.0)`: 3 from the vec3, 1 more)" : "") +
                        ". One single value fills them all: " + quote(type + "(0.0)") + ".";
        return;
    }
    if (std::regex_match(msg, m, too_many)) {
        const std::string type = m[1].matched ? m[1].str() : m[2].str();
        d.column = caretFor(c.m, f, d.line, d.column, type);
        d.message = quote(type + "(...)") + " is given more components than a " + type + " has";
        d.explanation =
            "Drop the extra arguments, or take part of a vector with a swizzle, e.g. `vec3(v.xy, 1.0)`.";
        return;
    }
    if (std::regex_match(msg, m, uninitialized)) {
        d.column = caretFor(c.m, f, d.line, d.column, m[1]);
        d.message = quote(m[1]) + " is used before it is given a value";
        d.explanation =
            "Its value is undefined: this machine happens to give 0, a GPU may give anything. Give it "
            "a value where it is declared, or on every path before it is read.";
        return;
    }
    if (msg == "Unterminated #if") {
        d.column = 0;
        d.message = "this `#if` has no `#endif`";
        d.explanation = "Every `#if`, `#ifdef` and `#ifndef` needs an `#endif` below it.";
        return;
    }
    if (msg == "vector size mismatch for arithmetic operator") {
        d.column = expressionCaret(c, d, f);
        const std::string* text = lineOf(c.m, f, d.line);
        d.message = "the two sides of this operator are vectors of different sizes";
        d.explanation = std::string(text && text->find("texture") != std::string::npos
                                        ? "texture() always returns a vec4. "
                                        : "") +
                        "GLSL never changes a vector's size by itself: shorten the larger one with a swizzle "
                        "(`v.xyz`, `texture(...).rgb`) or build the smaller one up (`vec4(v, 1.0)`).";
        return;
    }
    if (msg == "if-statement condition must be scalar boolean") {
        d.column = expressionCaret(c, d, f);
        d.message = "an `if` needs one bool";
        d.explanation =
            "Compare to get a bool, e.g. `if (x > 0.0)`; for a vector, compare one component or use "
            "any() or all().";
        return;
    }
    if (msg.find("of operator % must be an integer") != std::string::npos) {
        d.column = expressionCaret(c, d, f);
        d.message = "`%` works on integers only";
        d.explanation = "For floats, use mod(x, y).";
        return;
    }
    if (msg == "could not implicitly convert operands to arithmetic operator") {
        d.column = expressionCaret(c, d, f);
        d.message = "the operands of this operator have types that do not mix";
        d.explanation =
            "GLSL turns an int into a float by itself but converts nothing else: convert explicitly, "
            "e.g. `float(i)`, or use the same type on both sides.";
        return;
    }
    // Not one we know: the driver's words with jargon replaced, and a caret only under the name it
    // quotes.
    static const std::regex quoted(R"([`'](\w+)')");
    d.column = std::regex_search(msg, m, quoted) ? caretFor(c.m, f, d.line, d.column, m[1]) : 0;
}

// Sets `source_line` from the file, and drops a column the line cannot hold.
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

void finish(Diagnostic& d, const StageModel& m, std::size_t file) {
    d.message = scrubJargon(d.message);
    d.explanation = scrubJargon(d.explanation);
    attachSource(d, m, file);
}

}  // namespace

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

std::vector<Diagnostic> explainCompileLog(const std::vector<Diagnostic>& parsed, const StageText& stage,
                                          const StageText* other) {
    const StageModel model = buildModel(stage);
    std::optional<StageModel> other_model;
    if (other) other_model = buildModel(*other);
    const Ctx c{model, other_model ? &*other_model : nullptr};
    static const std::regex undeclared(R"(^`(\w+)' undeclared)");
    static const std::regex error_operand(R"([(,]\s*error\s*[,)])");
    static const std::regex uninitialized(R"(^`(\w+)' used uninitialized$)");

    std::vector<Diagnostic> errors, warnings;
    std::map<std::string, std::size_t> root_of_name;                  // undeclared name -> its error
    std::map<std::pair<std::string, int>, std::size_t> root_of_line;  // (file, driver's line) -> error
    std::map<std::string, std::size_t> root_of_variable;              // declared in a statement with an error
    // The error a later one on `line` follows from: one that broke the declaration of a name used there.
    auto taintedRoot = [&](const std::string& file, int line) -> std::optional<std::size_t> {
        const std::size_t f = fileIndex(model, file);
        if (f >= model.tokens.size()) return std::nullopt;
        for (const Token& t : model.tokens[f]) {
            if (t.line != line || t.kind != Token::Name) continue;
            const auto it = root_of_variable.find(t.text);
            if (it != root_of_variable.end()) return it->second;
        }
        return std::nullopt;
    };
    bool after_syntax_error = false;
    for (const Diagnostic& raw : parsed) {
        if (raw.severity != "error") continue;
        const std::string msg = firstLine(raw.message);
        std::smatch m;
        const bool is_undeclared = std::regex_search(msg, m, undeclared);
        const std::string name = is_undeclared ? m[1].str() : "";
        std::optional<std::size_t> root;
        const auto same_line = root_of_line.find({raw.file, raw.line});
        if (after_syntax_error)
            root = errors.size() - 1;
        else if (is_undeclared && root_of_name.count(name))
            root = root_of_name[name];
        else if (same_line != root_of_line.end())
            root = same_line->second;
        else if (!errors.empty() && std::regex_search(msg, error_operand))
            root = errors.size() - 1;
        else
            root = taintedRoot(raw.file, raw.line);
        if (root) {
            ++errors[*root].follow_on;
            root_of_line.emplace(std::make_pair(raw.file, raw.line), *root);
            continue;
        }
        Diagnostic d = raw;
        d.driver_message = raw.message;
        if (raw.line > 0) explainOne(d, c);
        finish(d, model, fileIndex(model, d.file));
        errors.push_back(std::move(d));
        root_of_line[{raw.file, raw.line}] = errors.size() - 1;
        if (is_undeclared) root_of_name[name] = errors.size() - 1;
        for (const Decl& decl : model.decls)
            if (stage.files[decl.file] == raw.file && decl.line == raw.line && decl.storage != "function" &&
                decl.storage != "param" && decl.storage != "struct")
                root_of_variable.emplace(decl.name, errors.size() - 1);
        after_syntax_error = msg.rfind("syntax error", 0) == 0;
    }
    for (const Diagnostic& raw : parsed) {
        if (raw.severity == "error") continue;
        std::smatch m;
        const std::string msg = firstLine(raw.message);
        if (std::regex_match(msg, m, uninitialized)) {
            // "used uninitialized" after the declaration's own initialiser failed: a consequence.
            const Decl* decl = findDecl(model, m[1], false);
            if (decl && root_of_line.count({stage.files[decl->file], decl->line})) continue;
        }
        Diagnostic d = raw;
        d.driver_message = raw.message;
        if (raw.line > 0) explainOne(d, c);
        finish(d, model, fileIndex(model, d.file));
        warnings.push_back(std::move(d));
    }
    errors.insert(errors.end(), warnings.begin(), warnings.end());
    return errors;
}

std::vector<Diagnostic> scanStage(const StageText& stage) {
    const StageModel m = buildModel(stage);
    std::vector<Diagnostic> out;
    auto warn = [&](std::size_t file, const Token& t, const std::string& message,
                    const std::string& explanation) {
        Diagnostic d;
        d.file = stage.files[file];
        d.line = t.line;
        d.column = t.column;
        d.severity = "warning";
        d.message = message;
        d.explanation = explanation;
        attachSource(d, m, file);
        out.push_back(std::move(d));
    };
    static const std::map<std::string, std::string> legacy_calls = {
        {"texture2D", "texture"}, {"texture2DLod", "textureLod"}, {"texture2DProj", "textureProj"},
        {"texture3D", "texture"}, {"textureCube", "texture"},     {"textureCubeLod", "textureLod"},
        {"texture1D", "texture"}, {"shadow2D", "texture"},        {"shadow2DProj", "textureProj"}};
    const bool fragment = stage.stage == "fragment";
    for (std::size_t f = 0; f < m.tokens.size(); ++f) {
        const std::vector<Token>& ts = m.tokens[f];
        std::set<std::string> warned;
        for (std::size_t i = 0; i < ts.size(); ++i) {
            const Token& t = ts[i];
            if (!m.legacy_allowed && t.kind == Token::Name && !warned.count(t.text)) {
                const auto call = legacy_calls.find(t.text);
                const bool called = i + 1 < ts.size() && ts[i + 1].text == "(";
                if (call != legacy_calls.end() && called && !findDecl(m, t.text, true)) {
                    warned.insert(t.text);
                    warn(f, t, quote(t.text) + " is old GLSL (before 1.30)",
                         "Mesa accepts it, but a `#version 330 core` shader calls " +
                             quote(call->second + "(...)") +
                             ", which works for every sampler type; other drivers reject " + quote(t.text) +
                             ".");
                } else if ((t.text == "gl_FragColor" || t.text == "gl_FragData") && fragment) {
                    warned.insert(t.text);
                    warn(f, t, quote(t.text) + " is old GLSL (before 1.30)",
                         "Declare your own output, `out vec4 o_color;`, and write that: " + quote(t.text) +
                             " is gone from core profiles and other drivers reject it.");
                } else if (t.text == "varying" || t.text == "attribute") {
                    warned.insert(t.text);
                    const std::string now = t.text == "attribute" || fragment ? "in" : "out";
                    warn(f, t, quote(t.text) + " is old GLSL (before 1.30)",
                         "In this " + stage.stage + " shader write " + quote(now) +
                             " instead; other drivers reject " + quote(t.text) + " in a core profile.");
                }
            }
            // `1 / 2` is 0: integer division of two literals that leaves a remainder, outside
            // an index or an integer declaration (where it may be meant).
            if (t.kind == Token::Number && i + 2 < ts.size() && ts[i + 1].text == "/" &&
                ts[i + 2].kind == Token::Number) {
                static const std::regex integer(R"(\d{1,9})");
                const Token& b = ts[i + 2];
                if (!std::regex_match(t.text, integer) || !std::regex_match(b.text, integer)) continue;
                const long num = std::stol(t.text), den = std::stol(b.text);
                if (den == 0 || num % den == 0) continue;
                const std::string before = i > 0 ? ts[i - 1].text : "";
                if (before == "*" || before == "/" || before == "%" || before == "[") continue;
                bool integer_context = false;
                for (std::size_t k = 0; k < i; ++k)
                    if (ts[k].line == t.line &&
                        (ts[k].text == "int" || ts[k].text == "uint" || ts[k].text == "[" ||
                         ts[k].text.rfind("ivec", 0) == 0 || ts[k].text.rfind("uvec", 0) == 0))
                        integer_context = true;
                if (integer_context) continue;
                const std::string expr = t.text + " / " + b.text;
                warn(f, t, quote(expr) + " divides two integers: it is " + std::to_string(num / den),
                     "Integer division drops the fraction. Write " + quote(t.text + ".0 / " + b.text + ".0") +
                         " for " + formatNumber(static_cast<double>(num) / static_cast<double>(den)) + ".");
            }
        }
    }
    if (fragment) {
        for (const Decl& d : m.decls) {
            if (!d.global || (d.storage != "in" && d.storage != "varying")) continue;
            const auto used = m.uses.find(d.name);
            if (used != m.uses.end() && used->second > 0) continue;
            Token t;
            t.line = d.line;
            t.column = d.column;
            warn(d.file, t, "input " + quote(d.name) + " is declared but never used",
                 "If the lab needs it, use it; if not, delete the declaration.");
        }
    }
    return out;
}

std::vector<Diagnostic> explainLinkLog(const std::string& log, const StageText& vertex,
                                       const StageText& fragment) {
    const StageModel vm = buildModel(vertex), fm = buildModel(fragment);
    const std::string& vfile = vertex.files.empty() ? vertex.stage : vertex.files[0];
    const std::string& ffile = fragment.files.empty() ? fragment.stage : fragment.files[0];
    std::vector<Diagnostic> out;
    std::set<std::string> seen;
    // At a declaration of `name` (fragment first, then vertex); without one, the pair of files.
    auto place = [&](Diagnostic& d, const std::string& name, std::initializer_list<const char*> storages,
                     bool vertex_first) {
        const Decl* fdecl = findGlobal(fm, name, storages);
        const Decl* vdecl = findGlobal(vm, name, storages);
        const StageModel* sm = nullptr;
        const Decl* decl = nullptr;
        if (vertex_first ? vdecl != nullptr : fdecl == nullptr) {
            sm = &vm;
            decl = vdecl;
        } else {
            sm = &fm;
            decl = fdecl;
        }
        if (!decl) {
            d.file = vfile + " + " + ffile;
            return;
        }
        d.file = sm->text->files[decl->file];
        d.line = decl->line;
        d.column = decl->column;
        attachSource(d, *sm, decl->file);
    };
    auto lineOfDecl = [](const Decl* d) {
        return d ? " (line " + std::to_string(d->line) + ")" : std::string();
    };
    static const std::regex type_mismatch(
        R"(^(\w+) shader output `(\w+)' declared as type `(\w+)', but (\w+) shader input declared as type `(\w+)'$)");
    static const std::regex interpolation(
        R"(^(\w+) shader output `(\w+)' specifies (\w+) interpolation qualifier, but (\w+) shader input specifies (\w+) interpolation qualifier$)");
    static const std::regex not_written(R"(^(\w+) shader varying (\w+) not written by (\w+) shader$)");
    static const std::regex no_output(
        R"(^(\w+) shader input `(\w+)' has no matching output in the previous stage$)");
    static const std::regex uniform_types(R"(^uniform `(\w+)' declared as type `(\w+)' and type `(\w+)'$)");
    static const std::regex lacks_main(R"(^(\w+) shader lacks `main'$)");
    static const std::regex unresolved(R"(^unresolved reference to function `(\w+)'$)");
    std::istringstream in(log);
    std::string raw;
    while (std::getline(in, raw)) {
        // Mesa ends each message with "\n." and may print it once per link step.
        std::string line = trim(raw);
        while (!line.empty() && line[0] == '.') line = trim(line.substr(1));
        if (line.empty() || !seen.insert(line).second) continue;
        Diagnostic d;
        d.driver_message = line;
        std::string msg = line;
        d.severity = "error";
        if (msg.rfind("error:", 0) == 0) {
            msg = trim(msg.substr(6));
        } else if (msg.rfind("warning:", 0) == 0) {
            d.severity = "warning";
            msg = trim(msg.substr(8));
        }
        std::smatch m;
        if (std::regex_match(msg, m, type_mismatch)) {
            const std::string name = m[2];
            place(d, name, {"in", "varying"}, false);
            d.message = quote(name) + " is a " + m[3].str() + " in " + vfile + " but a " + m[5].str() +
                        " in " + ffile;
            d.explanation =
                "A value passed from the vertex stage to the fragment stage has the same type on both "
                "sides: declare `in " +
                m[3].str() + " " + name + ";` here, or make the `out` in " + vfile +
                lineOfDecl(findGlobal(vm, name, {"out", "varying"})) + " a " + m[5].str() + ".";
        } else if (std::regex_match(msg, m, interpolation)) {
            const std::string name = m[2];
            place(d, name, {"in", "varying"}, false);
            const std::string a = m[3] == "no" ? "none" : m[3].str(), b = m[5] == "no" ? "none" : m[5].str();
            d.message = quote(name) + " is interpolated differently in the two stages (" + a + " in " +
                        vfile + ", " + b + " in " + ffile + ")";
            d.explanation =
                "Write the same qualifier (`flat`, `smooth` or `noperspective`) on the `out` in " + vfile +
                " and the `in` in " + ffile + ".";
        } else if (std::regex_match(msg, m, not_written) || std::regex_match(msg, m, no_output)) {
            const std::string name = m[2];
            const Decl* vout = findGlobal(vm, name, {"out", "varying"});
            const Decl* fin = findGlobal(fm, name, {"in", "varying"});
            const std::string type = fin ? fin->type : "vec3";
            if (vout) {
                place(d, name, {"out", "varying"}, true);
                d.message = "output " + quote(name) + " of " + vfile + " is never written";
                d.explanation = ffile + " reads it and gets an undefined value (zero here). Assign it in " +
                                vfile + "'s main().";
            } else {
                place(d, name, {"in", "varying"}, false);
                // The name it was meant to be: a close spelling, else the one output of that
                // type no input receives (v_normal for v_world_normal is too far to spell).
                std::vector<std::string> outs, unread;
                for (const Decl& decl : vm.decls) {
                    if (!decl.global || (decl.storage != "out" && decl.storage != "varying")) continue;
                    outs.push_back(decl.name);
                    if (decl.type == type && !findGlobal(fm, decl.name, {"in", "varying"}))
                        unread.push_back(decl.name);
                }
                std::string guess = closestMatch(name, outs);
                if (guess.empty() && unread.size() == 1) guess = unread.front();
                d.message = ffile + " reads " + quote(name) + ", but " + vfile +
                            " has no output of that name" +
                            (guess.empty() ? "" : "; did you mean " + quote(guess) + "?");
                d.explanation =
                    "Each `in` of the fragment stage receives the vertex stage's `out` of the same name "
                    "and type; without one it is undefined (zero here). Declare `out " +
                    type + " " + name + ";` in " + vfile + " and write it, or use the name " + vfile +
                    " already gives.";
            }
        } else if (std::regex_match(msg, m, uniform_types)) {
            const std::string name = m[1];
            place(d, name, {"uniform"}, false);
            d.message = "uniform " + quote(name) + " has different types in the two stages (" + m[2].str() +
                        " and " + m[3].str() + ")";
            d.explanation = "A uniform used by both stages is one value: declare it with the same type in " +
                            vfile + lineOfDecl(findGlobal(vm, name, {"uniform"})) + " and " + ffile +
                            lineOfDecl(findGlobal(fm, name, {"uniform"})) + ".";
        } else if (std::regex_match(msg, m, lacks_main)) {
            const bool is_vertex = m[1] == "vertex";
            const StageModel& sm = is_vertex ? vm : fm;
            d.file = is_vertex ? vfile : ffile;
            std::vector<std::string> functions;
            for (const Decl& decl : sm.decls)
                if (decl.storage == "function") functions.push_back(decl.name);
            const std::string guess = closestMatch("main", functions);
            d.message = d.file + " has no `main` function";
            d.explanation = "Every stage starts at `void main()`.";
            if (const Decl* near = guess.empty() ? nullptr : findDecl(sm, guess, true)) {
                d.file = sm.text->files[near->file];
                d.line = near->line;
                d.column = near->column;
                attachSource(d, sm, near->file);
                d.explanation += " " + quote(guess) + " looks like it was meant to be it.";
            }
        } else if (std::regex_match(msg, m, unresolved)) {
            const std::string name = m[1];
            d.message = quote(name) + " is declared but never defined";
            d.explanation =
                "A prototype such as `float " + name +
                "(vec3 n);` promises a body with the same parameter types in the same stage: write "
                "the function, or fix its parameter types to match.";
            for (const StageModel* sm : {&fm, &vm}) {
                const Decl* decl = findDecl(*sm, name, true);
                if (!decl || d.line) continue;
                d.file = sm->text->files[decl->file];
                d.line = decl->line;
                d.column = decl->column;
                attachSource(d, *sm, decl->file);
            }
            if (!d.line) d.file = vfile + " + " + ffile;
        } else {
            d.file = vfile + " + " + ffile;
            d.message = msg;
        }
        d.message = scrubJargon(d.message);
        d.explanation = scrubJargon(d.explanation);
        out.push_back(std::move(d));
    }
    return out;
}

}  // namespace shaderlab
