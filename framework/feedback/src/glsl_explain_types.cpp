// Errors about types explained: a call no form of a function accepts, a value of the wrong type
// assigned or returned, a missing `return`, components or fields a value does not have,
// constructors given too few or too many components, operators on types that do not mix. The
// advice names the conversion to write. Errors about names are glsl_explain_names.cpp's.
#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "glsl_explain_detail.h"

namespace shaderlab::glsl_detail {

namespace {

constexpr std::size_t kMaxCandidates = 3;  // function signatures shown in an explanation

// "a, b, c" -> {"a", "b", "c"}; "" -> {}.
std::vector<std::string> splitList(const std::string& s) {
    std::vector<std::string> out;
    if (trim(s).empty()) return out;
    std::string item;
    std::istringstream in(s);
    while (std::getline(in, item, ',')) out.push_back(trim(item));
    return out;
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

std::string argumentCount(std::size_t n) { return std::to_string(n) + (n == 1 ? " argument" : " arguments"); }

// A column for a diagnostic about the expression Mesa points at: its first token.
int expressionCaret(const Ctx& c, const Diagnostic& d, std::size_t f) {
    return caretFor(c.m, f, d.line, d.column, "");
}

}  // namespace

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

void explainNoReturn(Diagnostic& d, const Ctx& c, std::size_t f, const std::string& function,
                     const std::string& type) {
    d.column = caretFor(c.m, f, d.line, 0, function);
    d.message = quote(function) + " must return a " + type + ", but has no `return`";
    d.explanation =
        "A function with a result type ends every path with `return <value>;`: return the value "
        "you computed, or declare the function `void` if it only has effects.";
}

void explainWrongReturn(Diagnostic& d, const Ctx& c, std::size_t f, const std::string& given,
                        const std::string& function, const std::string& returning) {
    d.column = expressionCaret(c, d, f);
    d.message = quote(function) + " returns a " + returning + ", but this `return` gives a " + given;
    d.explanation = conversionAdvice(given, returning, "");
}

// An invalid swizzle, or a field of a value that has none (`is_field`).
void explainComponentAccess(Diagnostic& d, const Ctx& c, std::size_t f, const std::string& name,
                            bool is_field) {
    d.column = 0;
    if (f < c.m.tokens.size()) {
        const std::vector<Token>& ts = c.m.tokens[f];
        for (std::size_t i = 1; i < ts.size(); ++i)
            if (ts[i].line == d.line && ts[i].text == name && ts[i - 1].text == ".")
                d.column = d.column ? -1 : ts[i].column;
        d.column = std::max(0, d.column);
    }
    if (is_field) {
        d.message = quote("." + name) + " cannot be taken of this value: it is neither a vector nor a struct";
        d.explanation =
            "Only vectors have components (.x .y ...) and only structs have fields; a float or an int "
            "has neither. Check the type the value was declared with.";
        return;
    }
    d.message = quote("." + name) + " is not a component of this value";
    d.explanation =
        "A vec2 has .x .y, a vec3 .x .y .z, a vec4 .x .y .z .w (or .rgba, or .stpq: one set at a "
        "time); a float has no components.";
}

void explainTooFew(Diagnostic& d, const Ctx& c, std::size_t f, const std::string& type) {
    d.column = caretFor(c.m, f, d.line, d.column, type);
    const int n = components(type);
    d.message = quote(type + "(...)") + " is given too few components";
    d.explanation = "The arguments of a constructor add up to its size" +
                    (n > 1 ? ": a " + type + " needs " + std::to_string(n) : std::string()) +
                    (type == "vec4" ? " (`vec4(v_normal, 1.0)`: 3 from the vec3, 1 more)" : "") +
                    ". One single value fills them all: " + quote(type + "(0.0)") + ".";
}

void explainTooMany(Diagnostic& d, const Ctx& c, std::size_t f, const std::string& type) {
    d.column = caretFor(c.m, f, d.line, d.column, type);
    d.message = quote(type + "(...)") + " is given more components than a " + type + " has";
    d.explanation =
        "Drop the extra arguments, or take part of a vector with a swizzle, e.g. `vec3(v.xy, 1.0)`.";
}

bool explainOperator(Diagnostic& d, const Ctx& c, std::size_t f, const std::string& msg) {
    if (msg == "size mismatch for matrix multiplication") {
        explainMatrixProduct(d, c, f);
        return true;
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
        return true;
    }
    if (msg == "if-statement condition must be scalar boolean") {
        d.column = expressionCaret(c, d, f);
        d.message = "an `if` needs one bool";
        d.explanation =
            "Compare to get a bool, e.g. `if (x > 0.0)`; for a vector, compare one component or use "
            "any() or all().";
        return true;
    }
    if (msg.find("of operator % must be an integer") != std::string::npos) {
        d.column = expressionCaret(c, d, f);
        d.message = "`%` works on integers only";
        d.explanation = "For floats, use mod(x, y).";
        return true;
    }
    if (msg == "could not implicitly convert operands to arithmetic operator") {
        d.column = expressionCaret(c, d, f);
        d.message = "the operands of this operator have types that do not mix";
        d.explanation =
            "GLSL turns an int into a float by itself but converts nothing else: convert explicitly, "
            "e.g. `float(i)`, or use the same type on both sides.";
        return true;
    }
    return false;
}

}  // namespace shaderlab::glsl_detail
