// Mutants of a reference file; see mutants.h.
#include "shaderlab/authoring/mutants.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <set>
#include <string_view>

#include "shaderlab/glsl/glsl_outline.h"

namespace shaderlab::authoring {

namespace {

using glsl::Token;
using glsl::TokenKind;

const std::map<std::string, std::string>& operatorSwaps() {
    static const std::map<std::string, std::string> swaps{
        {"+", "-"},   {"-", "+"},   {"*", "/"},   {"/", "*"},   {"<", "<="},  {"<=", "<"},
        {">", ">="},  {">=", ">"},  {"==", "!="}, {"!=", "=="}, {"&&", "||"}, {"||", "&&"},
        {"+=", "-="}, {"-=", "+="}, {"*=", "/="}, {"/=", "*="}};
    return swaps;
}

bool isSwizzle(const std::string& w) {
    if (w.empty() || w.size() > 4) return false;
    const std::string xyzw = "xyzw", rgba = "rgba";
    const bool a = w.find_first_not_of(xyzw) == std::string::npos;
    const bool b = w.find_first_not_of(rgba) == std::string::npos;
    return a || b;
}

std::string mutatedSwizzle(const std::string& w) {
    if (w.size() == 1) {
        const std::string xyzw = "xyzw", rgba = "rgba";
        const std::string& set = xyzw.find(w[0]) != std::string::npos ? xyzw : rgba;
        const std::size_t at = set.find(w[0]);
        return std::string(1, at == 3 ? set[0] : set[(at + 1) % 3]);
    }
    return std::string(w.rbegin(), w.rend());
}

std::string mutatedNumber(const std::string& spelled) {
    std::string digits = spelled, suffix;
    while (!digits.empty() && std::string("uUfFlL").find(digits.back()) != std::string::npos) {
        suffix.insert(suffix.begin(), digits.back());
        digits.pop_back();
    }
    const bool hex = digits.size() > 1 && (digits[1] == 'x' || digits[1] == 'X');
    if (hex) return "";
    const bool integer = digits.find_first_of(".eE") == std::string::npos;
    const double v = integer ? static_cast<double>(std::strtoll(digits.c_str(), nullptr, 10))
                             : std::strtod(digits.c_str(), nullptr);
    char buf[48];
    if (integer) {
        std::snprintf(buf, sizeof buf, "%lld", static_cast<long long>(v) + 1);
    } else {
        std::snprintf(buf, sizeof buf, "%.9g", v == 0.0 ? 1.0 : 2.0 * v);
        std::string s = buf;
        if (s.find_first_of(".eE") == std::string::npos) s += ".0";
        return s + suffix;
    }
    return std::string(buf) + suffix;
}

// One line of text, at most `max` characters.
std::string shortened(std::string s, std::size_t max = 60) {
    for (char& c : s)
        if (c == '\n' || c == '\r' || c == '\t') c = ' ';
    std::string out;
    for (char c : s)
        if (!(c == ' ' && !out.empty() && out.back() == ' ')) out += c;
    return out.size() > max ? out.substr(0, max - 3) + "..." : out;
}

class Mutator {
  public:
    Mutator(const std::string& file, const std::string& text)
        : file_(file), s_(text), o_(glsl::outlineGlsl(text)), t_(o_.tokens) {}

    std::vector<Mutant> run() {
        for (const glsl::Declaration& d : o_.declarations) {
            if (d.kind != glsl::DeclKind::Function || d.body_first == 0 || d.names.empty()) continue;
            function_ = d.names[0];
            counts_.clear();
            for (std::size_t k = d.body_first + 1; k < d.last; ++k) mutateAt(k, d);
        }
        return std::move(out_);
    }

  private:
    std::string text(std::size_t k) const { return std::string(glsl::tokenText(s_, t_[k])); }
    bool is(std::size_t k, const char* op) const {
        return k < t_.size() && t_[k].kind == TokenKind::Operator && glsl::tokenText(s_, t_[k]) == op;
    }
    // Whether the token before k ends a value (so an operator at k is binary): a name, a number, a
    // gl_ variable (`gl_PointCoord - 1.0`; the lexer calls it a keyword, as it does `return`), or a
    // closing bracket.
    bool valueBefore(std::size_t k) const {
        if (k == 0) return false;
        const Token& t = t_[k - 1];
        return t.kind == TokenKind::Identifier || t.kind == TokenKind::Number || is(k - 1, ")") ||
               is(k - 1, "]") || (t.kind == TokenKind::Keyword && text(k - 1).rfind("gl_", 0) == 0);
    }

    std::size_t closing(std::size_t open, std::size_t limit) const {
        const std::string o = text(open);
        const std::string c = o == "(" ? ")" : o == "[" ? "]" : "}";
        int depth = 0;
        for (std::size_t j = open; j < limit; ++j) {
            if (is(j, o.c_str())) ++depth;
            if (is(j, c.c_str()) && --depth == 0) return j;
        }
        return limit;
    }

    // The token after a primary expression starting at j (a name, a number, a call or a
    // constructor, a parenthesised group, then indexing and members); `limit` when none is there.
    std::size_t primaryEnd(std::size_t j, std::size_t limit) const {
        if (j >= limit) return limit;
        if (is(j, "(")) {
            j = closing(j, limit);
            if (j >= limit) return limit;
            ++j;
        } else if (t_[j].kind == TokenKind::Identifier || t_[j].kind == TokenKind::Keyword ||
                   t_[j].kind == TokenKind::Number) {
            ++j;
            if (j < limit && is(j, "(") && t_[j - 1].kind != TokenKind::Number) {
                j = closing(j, limit);
                if (j >= limit) return limit;
                ++j;
            }
        } else {
            return limit;
        }
        while (j < limit) {
            if (is(j, "[")) {
                j = closing(j, limit);
                if (j >= limit) return limit;
                ++j;
            } else if (is(j, ".") && j + 1 < limit && t_[j + 1].kind == TokenKind::Identifier) {
                j += 2;
            } else {
                break;
            }
        }
        return j;
    }

    // The token after a term (primaries joined by * and /, each with an optional unary sign).
    std::size_t termEnd(std::size_t j, std::size_t limit) const {
        for (;;) {
            while (j < limit && (is(j, "-") || is(j, "+") || is(j, "!"))) ++j;
            j = primaryEnd(j, limit);
            if (j >= limit || !(is(j, "*") || is(j, "/"))) return j;
            ++j;
        }
    }

    void add(const std::string& op, std::size_t first, std::size_t last, const std::string& replacement) {
        addSpans(op, t_[first].line, {{t_[first].begin, t_[last].end, replacement}},
                 "`" + shortened(s_.substr(t_[first].begin, t_[last].end - t_[first].begin)) + "` -> `" +
                     shortened(replacement) + "`");
    }

    struct Span {
        std::size_t begin, end;
        std::string replacement;
    };

    // Spans in the order of the text, not overlapping.
    void addSpans(const std::string& op, int line, const std::vector<Span>& spans,
                  const std::string& change) {
        std::string mutated;
        std::size_t at = 0;
        for (const Span& sp : spans) {
            mutated += s_.substr(at, sp.begin - at) + sp.replacement;
            at = sp.end;
        }
        mutated += s_.substr(at);
        // Every place counts, so that an id stays with its place when another mutant is a repeat.
        const int place = ++counts_[op];
        if (mutated == s_ || !seen_.insert(mutated).second) return;
        Mutant m;
        m.file = file_;
        m.function = function_;
        m.op = op;
        m.id = file_ + ":" + function_ + ":" + op + "#" + std::to_string(place);
        m.line = line;
        m.change = change;
        m.text = std::move(mutated);
        out_.push_back(std::move(m));
    }

    void mutateAt(std::size_t k, const glsl::Declaration& d) {
        const std::size_t limit = d.last;
        const Token& t = t_[k];
        const std::string w = text(k);
        if (t.kind == TokenKind::Number) {
            const std::string n = mutatedNumber(w);
            if (!n.empty()) add("constant", k, k, n);
        } else if (t.kind == TokenKind::Identifier && is(k - 1, ".") && isSwizzle(w)) {
            add("swizzle", k, k, mutatedSwizzle(w));
        } else if (t.kind == TokenKind::Keyword &&
                   (w == "normalize" || w == "max" || w == "min" || w == "clamp") && is(k + 1, "(")) {
            mutateCall(k, limit);
        } else if (t.kind == TokenKind::Keyword && w == "for") {
            mutateLoop(k, d);
        } else if (t.kind == TokenKind::Operator) {
            mutateOperator(k, limit);
        }
    }

    // normalize(x) -> (x); max(x, y) -> (x): the call left out, its first argument kept.
    void mutateCall(std::size_t k, std::size_t limit) {
        const std::size_t close = closing(k + 1, limit);
        if (close >= limit) return;
        std::size_t comma = close;
        int depth = 0;
        for (std::size_t j = k + 1; j < close; ++j) {
            if (is(j, "(") || is(j, "[")) ++depth;
            if (is(j, ")") || is(j, "]")) --depth;
            if (depth == 1 && is(j, ",")) {
                comma = j;
                break;
            }
        }
        if (comma == k + 2) return;
        add("call", k, close, "(" + s_.substr(t_[k + 2].begin, t_[comma - 1].end - t_[k + 2].begin) + ")");
    }

    void mutateOperator(std::size_t k, std::size_t limit) {
        const std::string w = text(k);
        const auto swap = operatorSwaps().find(w);
        const bool binary = valueBefore(k);
        if (swap != operatorSwaps().end() && (binary || (w != "+" && w != "-" && w != "*" && w != "/")))
            add("operator", k, k, swap->second);
        if ((w == "-") && !binary && k + 1 < limit) add("sign", k, k, "");
        if ((w == "+" || w == "-") && binary) {
            const std::size_t end = termEnd(k + 1, limit);
            if (end < limit && end > k + 1) {
                const std::string term = s_.substr(t_[k].begin, t_[end - 1].end - t_[k].begin);
                add("term-dropped", k, end - 1, "");
                addSpans("term-doubled", t_[k].line, {{t_[end - 1].end, t_[end - 1].end, " " + term}},
                         "`" + shortened(term) + "` twice");
            }
        }
        if (w == "*" && binary && is(k + 1, "(")) {
            const std::size_t close = closing(k + 1, limit);
            if (close >= limit) return;
            bool sum = false;
            int depth = 0;
            for (std::size_t j = k + 2; j < close; ++j) {
                if (is(j, "(") || is(j, "[")) ++depth;
                if (is(j, ")") || is(j, "]")) --depth;
                sum = sum || (depth == 0 && (is(j, "+") || is(j, "-")) && valueBefore(j));
            }
            if (sum)
                addSpans("distribute", t_[k].line,
                         {{t_[k + 1].begin, t_[k + 1].end, ""}, {t_[close].begin, t_[close].end, ""}},
                         "`" + shortened(s_.substr(t_[k].begin, t_[close].end - t_[k].begin)) +
                             "` without its brackets");
        }
    }

    // The statement ending at token `end` (a ';'): its first token, found walking back to the
    // previous ';', '{' or '}' at the same depth.
    std::size_t statementStart(std::size_t end, std::size_t floor) const {
        int depth = 0;
        std::size_t j = end;
        while (j > floor) {
            if (is(j - 1, ")") || is(j - 1, "]") || is(j - 1, "}")) {
                if (is(j - 1, "}") && depth == 0) break;
                ++depth;
            }
            if (is(j - 1, "(") || is(j - 1, "[") || is(j - 1, "{")) {
                if (depth == 0) break;
                --depth;
            }
            if (depth == 0 && is(j - 1, ";")) break;
            --j;
        }
        return j;
    }

    void mutateLoop(std::size_t k, const glsl::Declaration& d) {
        const std::size_t limit = d.last;
        if (!is(k + 1, "(")) return;
        const std::size_t header_end = closing(k + 1, limit);
        if (header_end + 1 >= limit || !is(header_end + 1, "{")) return;
        const std::size_t body_open = header_end + 1, body_close = closing(body_open, limit);
        if (body_close >= limit) return;
        // Out of the loop: its body's last statement, when it is a plain one.
        if (body_close > body_open + 1 && is(body_close - 1, ";")) {
            const std::size_t first = statementStart(body_close - 1, body_open + 1);
            const std::string w = text(first);
            if (first > body_open && w != "if" && w != "for" && w != "while" && w != "return" &&
                w != "break" && w != "continue") {
                const std::string stmt = s_.substr(t_[first].begin, t_[body_close - 1].end - t_[first].begin);
                addSpans("out-of-loop", t_[first].line,
                         {{t_[first].begin, t_[body_close - 1].end, ""},
                          {t_[body_close].end, t_[body_close].end, "\n    " + stmt}},
                         "`" + shortened(stmt) + "` moved after the loop");
            }
        }
        // Into the loop: the statement right before it.
        if (k > d.body_first + 1 && is(k - 1, ";")) {
            const std::size_t first = statementStart(k - 1, d.body_first + 1);
            const std::string w = text(first);
            if (w != "if" && w != "for" && w != "while" && w != "return") {
                const std::string stmt = s_.substr(t_[first].begin, t_[k - 1].end - t_[first].begin);
                addSpans("into-loop", t_[first].line,
                         {{t_[first].begin, t_[k - 1].end, ""},
                          {t_[body_open].end, t_[body_open].end, " " + stmt}},
                         "`" + shortened(stmt) + "` moved into the loop");
            }
        }
    }

    std::string file_;
    const std::string& s_;
    glsl::Outline o_;
    const std::vector<Token>& t_;
    std::string function_;
    std::map<std::string, int> counts_;
    std::set<std::string> seen_;
    std::vector<Mutant> out_;
};

}  // namespace

std::vector<Mutant> mutateFile(const std::string& file, const std::string& text) {
    return Mutator(file, text).run();
}

namespace {

// A line without its // comment, its spacing collapsed: "" for a blank or comment-only line.
std::string lineKey(std::string_view line) {
    const std::size_t comment = line.find("//");
    if (comment != std::string_view::npos) line = line.substr(0, comment);
    std::string key;
    for (char c : line) {
        const bool space = c == ' ' || c == '\t' || c == '\r';
        if (space && (key.empty() || key.back() == ' ')) continue;
        key += space ? ' ' : c;
    }
    while (!key.empty() && key.back() == ' ') key.pop_back();
    return key;
}

// Calls `f(line number, key)` for each line of `text` in the byte range [begin, end).
template <typename F>
void forLines(const std::string& text, std::size_t begin, std::size_t end, F f) {
    int number = 1 + static_cast<int>(std::count(text.begin(), text.begin() + begin, '\n'));
    std::size_t start = text.rfind('\n', begin == 0 ? 0 : begin - 1);
    start = start == std::string::npos || begin == 0 ? 0 : start + 1;
    while (start < end) {
        std::size_t stop = text.find('\n', start);
        if (stop == std::string::npos) stop = text.size();
        f(number++, lineKey(std::string_view(text).substr(start, stop - start)));
        start = stop + 1;
    }
}

}  // namespace

std::set<int> providedLines(const std::string& reference, const std::string& starter) {
    const glsl::Outline r = glsl::outlineGlsl(reference), s = glsl::outlineGlsl(starter);
    std::set<int> provided;
    for (const glsl::Declaration& d : r.declarations) {
        if (d.kind != glsl::DeclKind::Function || d.names.empty()) continue;
        std::set<std::string> given;
        for (const glsl::Declaration* t : glsl::declarationsNamed(s, d.names.front()))
            if (t->kind == glsl::DeclKind::Function)
                forLines(starter, t->begin, t->end, [&](int, const std::string& key) { given.insert(key); });
        forLines(reference, d.begin, d.end, [&](int line, const std::string& key) {
            if (!key.empty() && given.count(key)) provided.insert(line);
        });
    }
    return provided;
}

std::set<std::string> providedFunctions(const std::string& reference, const std::string& starter) {
    const glsl::Outline r = glsl::outlineGlsl(reference), s = glsl::outlineGlsl(starter);
    std::set<std::string> provided;
    for (const glsl::Declaration& d : r.declarations) {
        if (d.kind != glsl::DeclKind::Function || d.names.empty()) continue;
        const std::string text = glsl::canonicalText(reference, r, d);
        for (const glsl::Declaration* t : glsl::declarationsNamed(s, d.names.front()))
            if (t->kind == glsl::DeclKind::Function && glsl::canonicalText(starter, s, *t) == text)
                provided.insert(d.names.front());
    }
    return provided;
}

}  // namespace shaderlab::authoring
