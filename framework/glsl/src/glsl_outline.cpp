// A shader's top-level declarations; see glsl_outline.h.
#include "shaderlab/glsl/glsl_outline.h"

#include <algorithm>
#include <set>

namespace shaderlab::glsl {

namespace {

bool isStorageQualifier(std::string_view w) {
    return w == "uniform" || w == "in" || w == "out" || w == "const" || w == "buffer" || w == "shared" ||
           w == "attribute" || w == "varying";
}

// Qualifiers that change nothing about how a parameter or return value is passed.
bool isIgnoredQualifier(std::string_view w) {
    return w == "in" || w == "const" || w == "highp" || w == "mediump" || w == "lowp" || w == "precise" ||
           w == "invariant" || w == "flat" || w == "smooth" || w == "noperspective" || w == "centroid";
}

bool startsWith(std::string_view w, std::string_view prefix) { return w.substr(0, prefix.size()) == prefix; }

// A built-in type name (GLSL 4.60, section 4.1): what may stand before a local variable's name.
bool isTypeKeyword(std::string_view w) {
    if (w == "void" || w == "bool" || w == "int" || w == "uint" || w == "float" || w == "double") return true;
    for (std::string_view p : {"vec", "ivec", "uvec", "bvec", "dvec", "mat", "dmat", "sampler", "isampler",
                               "usampler", "image", "iimage", "uimage", "atomic_uint"})
        if (startsWith(w, p)) return true;
    return false;
}

class Reader {
  public:
    Reader(std::string_view text, Outline& out) : s_(text), out_(out), t_(out.tokens) {}

    void run() {
        std::size_t i = 0;
        while (i < t_.size()) i = t_[i].kind == TokenKind::Preprocessor ? directive(i) : statement(i);
    }

  private:
    std::string_view text(std::size_t i) const { return tokenText(s_, t_[i]); }
    bool is(std::size_t i, std::string_view op) const {
        return i < t_.size() && t_[i].kind == TokenKind::Operator && text(i) == op;
    }
    bool isName(std::size_t i) const { return i < t_.size() && t_[i].kind == TokenKind::Identifier; }
    bool afterDot(std::size_t i) const { return i > 0 && is(i - 1, "."); }

    Declaration make(DeclKind kind, std::size_t first, std::size_t last) const {
        Declaration d;
        d.kind = kind;
        d.first = first;
        d.last = last;
        d.begin = t_[first].begin;
        d.end = t_[last].end;
        return d;
    }

    // The index of the bracket closing the one at `open` ("(" "[" or "{"), counting only that
    // kind; t_.size() when it is never closed.
    std::size_t closing(std::size_t open) const {
        const std::string_view o = text(open);
        const std::string_view c = o == "(" ? ")" : o == "[" ? "]" : "}";
        int depth = 0;
        for (std::size_t j = open; j < t_.size(); ++j) {
            if (is(j, o)) ++depth;
            if (is(j, c) && --depth == 0) return j;
        }
        return t_.size();
    }

    // A preprocessor line runs to the first newline not escaped by a backslash.
    std::size_t directive(std::size_t i) {
        std::size_t line_end = t_[i].begin;
        while (line_end < s_.size() && s_[line_end] != '\n') {
            if (s_[line_end] == '\\' && line_end + 1 < s_.size() &&
                (s_[line_end + 1] == '\n' || s_[line_end + 1] == '\r'))
                line_end += s_[line_end + 1] == '\r' ? 3 : 2;
            else
                ++line_end;
        }
        std::size_t last = i;
        while (last + 1 < t_.size() && t_[last + 1].begin < line_end) ++last;
        Declaration d = make(DeclKind::Directive, i, last);
        for (char c : text(i).substr(1))
            if (!isGlslBlank(c)) d.directive += c;
        std::size_t from = i + 1;
        if (d.directive == "define" && i + 1 <= last) {
            d.names.push_back(std::string(text(i + 1)));
            from = i + 2;
        }
        addUses(&d, from, last, {});
        out_.declarations.push_back(std::move(d));
        return last + 1;
    }

    // Identifiers of tokens first..last not after a '.', not among `local`, not declared by d.
    void addUses(Declaration* d, std::size_t first, std::size_t last,
                 const std::set<std::string>& local) const {
        std::set<std::string> seen(d->uses.begin(), d->uses.end());
        for (std::size_t j = first; j <= last && j < t_.size(); ++j) {
            if (!isName(j) || afterDot(j)) continue;
            const std::string w(text(j));
            if (local.count(w) || std::find(d->names.begin(), d->names.end(), w) != d->names.end() ||
                !seen.insert(w).second)
                continue;
            d->uses.push_back(w);
        }
    }

    std::size_t statement(std::size_t i) {
        int depth = 0;  // ( and [
        std::size_t j = i;
        std::size_t body = 0;  // a function body's '{'
        bool braces = false;   // a struct's or a block's members
        for (; j < t_.size(); ++j) {
            if (is(j, "(") || is(j, "[")) ++depth;
            if (is(j, ")") || is(j, "]")) --depth;
            if (is(j, "{") && depth <= 0) {
                const std::size_t close = closing(j);
                if (close == t_.size()) {
                    out_.error = "a '{' on line " + std::to_string(t_[j].line) + " is never closed";
                    j = t_.size() - 1;
                    break;
                }
                if (j > i && is(j - 1, ")")) {
                    body = j;
                    j = close;
                    break;
                }
                braces = true;
                j = close;
                continue;
            }
            if (is(j, ";") && depth <= 0) break;
        }
        if (j >= t_.size()) j = t_.size() - 1;
        if (body) {
            function(i, body, j);
        } else if (braces) {
            aggregate(i, j);
        } else {
            plain(i, j);
        }
        return j + 1;
    }

    // The head of a function or prototype: the name before the first '(' outside brackets, and
    // the types of its parameters. False when the head has no such shape.
    bool readHead(std::size_t first, std::size_t end, Declaration* d, std::set<std::string>* params) const {
        std::size_t open = first;
        while (open < end && !is(open, "(")) {
            if (is(open, "=") || is(open, "[")) return false;
            ++open;
        }
        if (open >= end || open == first || !(isName(open - 1) || text(open - 1) == "main")) return false;
        const std::size_t close = closing(open);
        if (close >= t_.size() || close > end) return false;
        d->names.push_back(std::string(text(open - 1)));
        for (std::size_t k = first; k + 1 < open; ++k)
            if (!isIgnoredQualifier(text(k))) d->return_type += text(k);
        std::vector<std::pair<std::size_t, std::size_t>> ranges;  // each parameter's tokens
        std::size_t from = open + 1;
        int depth = 0;
        for (std::size_t k = open + 1; k <= close; ++k) {
            if (is(k, "(") || is(k, "[")) ++depth;
            if ((is(k, ")") || is(k, "]")) && k != close) --depth;
            if ((is(k, ",") && depth == 0) || k == close) {
                if (k > from) ranges.push_back({from, k});
                from = k + 1;
            }
        }
        for (const auto& [a, b] : ranges) {
            std::string qualifier, type, arrays;
            std::size_t name = b;
            for (std::size_t k = a; k < b; ++k) {
                const std::string_view w = text(k);
                if (isIgnoredQualifier(w)) continue;
                if (w == "out" || w == "inout") {
                    qualifier = std::string(w) + " ";
                } else if (type.empty()) {
                    type = w;
                } else if (is(k, "[")) {
                    const std::size_t c = std::min(closing(k), b - 1);
                    for (std::size_t m = k; m <= c; ++m) arrays += text(m);
                    k = c;
                } else if (isName(k)) {
                    name = k;
                }
            }
            if (type == "void" && ranges.size() == 1) break;
            d->parameter_types.push_back(qualifier + type + arrays);
            if (name < b) params->insert(std::string(text(name)));
        }
        for (std::size_t k = first; k <= close; ++k) {
            const bool tight = is(k, "(") || is(k, ")") || is(k, ",") || is(k, "[") || is(k, "]") ||
                               is(k - 1, "(") || is(k - 1, "[");
            if (!d->head.empty() && !tight) d->head += ' ';
            d->head += text(k);
        }
        return true;
    }

    void function(std::size_t first, std::size_t body, std::size_t last) {
        Declaration d = make(DeclKind::Function, first, last);
        d.body_first = body;
        std::set<std::string> local;
        if (!readHead(first, body, &d, &local)) {
            Declaration other = make(DeclKind::Other, first, last);
            addUses(&other, first, last, {});
            out_.declarations.push_back(std::move(other));
            return;
        }
        // Locals: a name declared after a type (`vec3 n =`, `Light l;`, `int i = 0` in a for's
        // header), or after a ',' in a statement that begins with a type (`float a = 1.0, b;`).
        // One pass: `starts` holds where the statement of each open '(' began.
        std::vector<std::size_t> starts;
        std::size_t start = body + 1;
        for (std::size_t k = body + 1; k + 1 <= last; ++k) {
            if (is(k, "(")) {
                starts.push_back(start);
                start = k + 1;
                continue;
            }
            if (is(k, ")") && !starts.empty()) {
                start = starts.back();
                starts.pop_back();
                continue;
            }
            if (is(k, ";") || is(k, "{") || is(k, "}")) {
                start = k + 1;
                continue;
            }
            if (!isName(k) || afterDot(k)) continue;
            const bool declares = is(k + 1, "=") || is(k + 1, ";") || is(k + 1, ",") || is(k + 1, "[");
            if (!declares) continue;
            const bool after_type = (t_[k - 1].kind == TokenKind::Keyword && isTypeKeyword(text(k - 1))) ||
                                    (isName(k - 1) && !afterDot(k - 1));
            if (after_type || (is(k - 1, ",") && beginsWithType(start, k)))
                local.insert(std::string(text(k)));
        }
        addUses(&d, first, last, local);
        out_.declarations.push_back(std::move(d));
    }

    // Whether the statement whose first token is `s` begins with a type (after qualifiers).
    bool beginsWithType(std::size_t s, std::size_t k) const {
        while (s < k && isIgnoredQualifier(text(s))) ++s;
        return s < k &&
               ((t_[s].kind == TokenKind::Keyword && isTypeKeyword(text(s))) || (isName(s) && isName(s + 1)));
    }

    // `struct S { ... } s;` or an interface block `uniform B { ... } b;`.
    void aggregate(std::size_t first, std::size_t last) {
        std::size_t open = first;
        while (open < last && !is(open, "{")) ++open;
        const std::size_t close = std::min(closing(open), last);
        const bool is_struct = text(first) == "struct" || (open > first + 1 && text(open - 2) == "struct");
        Declaration d = make(is_struct ? DeclKind::Struct : DeclKind::Block, first, last);
        if (is_struct && open > first && isName(open - 1)) d.names.push_back(std::string(text(open - 1)));
        bool instance = false;
        for (std::size_t k = close + 1; k < last; ++k)
            if (isName(k) && (is(k + 1, ";") || is(k + 1, ",") || is(k + 1, "["))) {
                d.names.push_back(std::string(text(k)));
                instance = true;
            }
        if (!is_struct) {
            for (std::size_t k = first; k < open; ++k)
                if (isStorageQualifier(text(k)) && d.storage.empty()) d.storage = text(k);
            // A block without an instance name puts its members in the global scope.
            if (!instance)
                for (std::size_t k = open + 1; k < close; ++k)
                    if (isName(k) && (is(k + 1, ";") || is(k + 1, "[") || is(k + 1, ",")))
                        d.names.push_back(std::string(text(k)));
        }
        std::set<std::string> members;
        for (std::size_t k = open + 1; k < close; ++k)
            if (isName(k) && (is(k + 1, ";") || is(k + 1, "[") || is(k + 1, ",")))
                members.insert(std::string(text(k)));
        addUses(&d, first, last, members);
        out_.declarations.push_back(std::move(d));
    }

    void plain(std::size_t first, std::size_t last) {
        if (text(first) == "precision") {
            out_.declarations.push_back(make(DeclKind::Other, first, last));
            return;
        }
        // A prototype: `type name(params);` with nothing after the ')'.
        {
            Declaration d = make(DeclKind::Prototype, first, last);
            std::set<std::string> params;
            if (is(last, ";") && last > first && is(last - 1, ")") && readHead(first, last, &d, &params) &&
                closingOfHead(first, last) == last - 1) {
                addUses(&d, first, last, params);
                out_.declarations.push_back(std::move(d));
                return;
            }
        }
        Declaration d = make(DeclKind::Variable, first, last);
        int depth = 0;
        bool in_initialiser = false;
        for (std::size_t k = first; k <= last; ++k) {
            const std::string_view w = text(k);
            if (is(k, "(") || is(k, "[") || is(k, "{")) ++depth;
            if (is(k, ")") || is(k, "]") || is(k, "}")) --depth;
            if (depth != 0) continue;
            if (d.storage.empty() && isStorageQualifier(w) && d.names.empty()) d.storage = w;
            if (is(k, "=")) in_initialiser = true;
            if (is(k, ",")) in_initialiser = false;
            if (!in_initialiser && isName(k) &&
                (is(k + 1, "=") || is(k + 1, ",") || is(k + 1, ";") || is(k + 1, "[")))
                d.names.push_back(std::string(w));
        }
        if (d.names.empty()) d.kind = DeclKind::Other;  // `layout(...) in;` and the like
        addUses(&d, first, last, {});
        out_.declarations.push_back(std::move(d));
    }

    std::size_t closingOfHead(std::size_t first, std::size_t last) const {
        for (std::size_t k = first; k < last; ++k)
            if (is(k, "(")) return closing(k);
        return t_.size();
    }

    std::string_view s_;
    Outline& out_;
    const std::vector<Token>& t_;
};

}  // namespace

Outline outlineGlsl(std::string_view text) {
    Outline out;
    out.tokens = lexGlsl(text);
    Reader(text, out).run();
    return out;
}

std::vector<const Declaration*> declarationsNamed(const Outline& outline, const std::string& name) {
    std::vector<const Declaration*> out;
    for (const Declaration& d : outline.declarations)
        if (std::find(d.names.begin(), d.names.end(), name) != d.names.end()) out.push_back(&d);
    return out;
}

std::string canonicalText(std::string_view text, const Outline& outline, const Declaration& d) {
    std::string out;
    for (std::size_t k = d.first; k <= d.last && k < outline.tokens.size(); ++k) {
        if (!out.empty()) out += ' ';
        out += tokenText(text, outline.tokens[k]);
    }
    return out;
}

}  // namespace shaderlab::glsl
