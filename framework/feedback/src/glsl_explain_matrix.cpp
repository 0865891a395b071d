// "size mismatch for matrix multiplication" explained: the `*` whose sides do not agree, with the
// type of each side as the source declares it, and the conversion that makes them agree. Mesa
// names neither the operator nor the types. The types are read from declarations, constructors,
// swizzles and indexing on the error's line (a product chain `a * b * c` is folded left to
// right); a side it cannot type (a call of the student's own function returning a struct, a
// parenthesised sum) leaves the message general rather than guessing.
#include <optional>
#include <string>
#include <vector>

#include "glsl_explain_detail.h"

namespace shaderlab::glsl_detail {

namespace {

// A GLSL value's shape: a scalar, a vector of `rows` components, or a matrix of `cols` columns
// of `rows` rows (GLSL's matCxR).
struct Shape {
    enum Kind { Scalar, Vector, Matrix } kind = Scalar;
    int cols = 1, rows = 1;
    std::string type;  // as written: "mat4", "vec3", "float"
};

std::optional<Shape> shapeOf(const std::string& type) {
    if (type == "float" || type == "int" || type == "uint" || type == "bool" || type == "double")
        return Shape{Shape::Scalar, 1, 1, type};
    std::string t = type;
    if (!t.empty() && (t[0] == 'b' || t[0] == 'i' || t[0] == 'u' || t[0] == 'd')) t = t.substr(1);
    const auto digit = [](char c) { return c >= '2' && c <= '4'; };
    if (t.size() == 4 && t.compare(0, 3, "vec") == 0 && digit(t[3]))
        return Shape{Shape::Vector, 1, t[3] - '0', type};
    if (t.size() == 4 && t.compare(0, 3, "mat") == 0 && digit(t[3]))
        return Shape{Shape::Matrix, t[3] - '0', t[3] - '0', type};
    if (t.size() == 6 && t.compare(0, 3, "mat") == 0 && digit(t[3]) && t[4] == 'x' && digit(t[5]))
        return Shape{Shape::Matrix, t[3] - '0', t[5] - '0', type};
    return std::nullopt;
}

std::string typeName(const Shape& s) {
    if (!s.type.empty()) return s.type;
    if (s.kind == Shape::Scalar) return "float";
    if (s.kind == Shape::Vector) return "vec" + std::to_string(s.rows);
    return s.cols == s.rows ? "mat" + std::to_string(s.cols)
                            : "mat" + std::to_string(s.cols) + "x" + std::to_string(s.rows);
}

// The product's shape, or nothing when the sizes do not agree.
std::optional<Shape> product(const Shape& a, const Shape& b) {
    if (a.kind == Shape::Scalar) return b;
    if (b.kind == Shape::Scalar) return a;
    if (a.kind == Shape::Vector && b.kind == Shape::Vector)
        return a.rows == b.rows ? std::optional<Shape>(a) : std::nullopt;
    if (a.kind == Shape::Matrix && b.kind == Shape::Vector)
        return a.cols == b.rows ? std::optional<Shape>(Shape{Shape::Vector, 1, a.rows, ""}) : std::nullopt;
    if (a.kind == Shape::Vector && b.kind == Shape::Matrix)
        return a.rows == b.rows ? std::optional<Shape>(Shape{Shape::Vector, 1, b.cols, ""}) : std::nullopt;
    return a.cols == b.rows ? std::optional<Shape>(Shape{Shape::Matrix, b.cols, a.rows, ""}) : std::nullopt;
}

// One side of a `*`: tokens [begin, end) of the line, its text and its shape when known.
struct Operand {
    std::size_t begin = 0, end = 0;
    std::optional<Shape> shape;
};

// The declaration of `name` that a use on `line` of file `f` sees: the nearest one above it (a
// local of this function before a global), else any.
const Decl* declarationSeen(const StageModel& m, std::size_t f, int line, const std::string& name) {
    const Decl *nearest = nullptr, *any = nullptr;
    for (const Decl& d : m.decls) {
        if (d.name != name || d.storage == "function" || d.storage == "struct") continue;
        if (!any) any = &d;
        if (d.file == f && d.line <= line && (!nearest || d.line >= nearest->line)) nearest = &d;
    }
    return nearest ? nearest : any;
}

// Index of the bracket matching ts[open] (an opening one), scanning in `step` direction.
std::size_t matching(const std::vector<Token>& ts, std::size_t open, int step) {
    const std::string o = ts[open].text;
    const std::string close = o == "(" ? ")" : o == "[" ? "]" : o == ")" ? "(" : "[";
    int depth = 0;
    for (std::size_t i = open; i<ts.size(); i = step> 0 ? i + 1 : i - 1) {
        if (ts[i].text == o) ++depth;
        if (ts[i].text == close && --depth == 0) return i;
        if (i == 0 && step < 0) break;
    }
    return std::string::npos;
}

// The shape after `.mask` (a swizzle of a vector) or `[i]` (a matrix's column, a vector's
// component, an array's element).
std::optional<Shape> selected(std::optional<Shape> s, const std::string& mask, bool indexed, bool array) {
    if (!s) return s;
    if (indexed) {
        if (array) return s;
        if (s->kind == Shape::Matrix) return Shape{Shape::Vector, 1, s->rows, ""};
        if (s->kind == Shape::Vector) return Shape{Shape::Scalar, 1, 1, "float"};
        return std::nullopt;
    }
    if (s->kind != Shape::Vector || mask.empty() || mask.size() > 4) return std::nullopt;
    if (mask.size() == 1) return Shape{Shape::Scalar, 1, 1, "float"};
    return Shape{Shape::Vector, 1, static_cast<int>(mask.size()), ""};
}

// The operand that starts at ts[i] (a name, a call or constructor, a number, a bracketed group),
// with its swizzles and indexing.
Operand operandFrom(const StageModel& m, std::size_t f, const std::vector<Token>& ts, std::size_t i) {
    Operand op;
    op.begin = i;
    if (i >= ts.size()) return op;
    std::optional<Shape> s;
    std::size_t p = i;
    if (ts[p].kind == Token::Number) {
        s = Shape{Shape::Scalar, 1, 1, "float"};
        ++p;
    } else if (ts[p].kind == Token::Name) {
        const std::string& name = ts[p].text;
        if (p + 1 < ts.size() && ts[p + 1].text == "(") {  // a constructor or a call
            const std::size_t close = matching(ts, p + 1, 1);
            if (close == std::string::npos) return op;
            s = shapeOf(name);
            if (!s)
                if (const Decl* fn = findDecl(m, name, true)) s = shapeOf(fn->type);
            p = close + 1;
        } else {
            const Decl* d = declarationSeen(m, f, ts[p].line, name);
            if (d) s = shapeOf(d->type);
            bool array = false;
            if (d && p + 1 < ts.size() && ts[p + 1].text == "[") {
                // An array's element has the declared type; a matrix's column does not.
                for (const Token& t : m.tokens[d->file])
                    if (t.line == d->line && t.column > d->column && t.text == "[") array = true;
            }
            ++p;
            while (p < ts.size() && (ts[p].text == "[" || ts[p].text == ".")) {
                if (ts[p].text == "[") {
                    const std::size_t close = matching(ts, p, 1);
                    if (close == std::string::npos) return op;
                    s = selected(s, "", true, array);
                    array = false;
                    p = close + 1;
                } else {
                    if (p + 1 >= ts.size() || ts[p + 1].kind != Token::Name) return op;
                    s = selected(s, ts[p + 1].text, false, false);
                    p += 2;
                }
            }
        }
    } else if (ts[p].text == "(") {
        const std::size_t close = matching(ts, p, 1);
        if (close == std::string::npos) return op;
        p = close + 1;  // a group: typed only as a product chain would be, which it is not here
    } else {
        return op;
    }
    op.end = p;
    op.shape = s;
    return op;
}

// The operand that ends just before ts[end] (walking back over swizzles, indexing and calls).
std::size_t operandStart(const std::vector<Token>& ts, std::size_t end) {
    if (end == 0) return std::string::npos;
    std::size_t p = end - 1;
    for (;;) {
        if (ts[p].text == ")" || ts[p].text == "]") {
            const std::size_t open = matching(ts, p, -1);
            if (open == std::string::npos) return std::string::npos;
            p = open;
            if (ts[p].text == "(" && p > 0 && ts[p - 1].kind == Token::Name)
                --p;  // a call
            else if (ts[p].text == "[" && p > 0) {
                --p;
                continue;
            }
        } else if (ts[p].kind == Token::Name && p > 1 && ts[p - 1].text == ".") {
            p -= 2;
            continue;
        } else if (ts[p].kind != Token::Name && ts[p].kind != Token::Number) {
            return std::string::npos;
        }
        return p;
    }
}

std::string joined(const std::vector<Token>& ts, std::size_t begin, std::size_t end) {
    std::string s;
    for (std::size_t i = begin; i < end && i < ts.size(); ++i) {
        const bool tight = i == begin || ts[i].text == "." || ts[i - 1].text == "." || ts[i].text == "(" ||
                           ts[i - 1].text == "(" || ts[i].text == ")" || ts[i].text == "[" ||
                           ts[i - 1].text == "[" || ts[i].text == "]" || ts[i].text == ",";
        s += (tight ? "" : " ") + ts[i].text;
    }
    return s;
}

// What to write so that a `left * right` of these shapes agrees.
std::string advice(const Shape& a, const Shape& b, const std::string& left, const std::string& right) {
    const std::string l = left.size() <= 40 ? left : "the matrix", r = right.size() <= 40 ? right : "v";
    if (a.kind == Shape::Matrix && b.kind == Shape::Vector) {
        std::string s = "A " + typeName(a) + " times a vector needs a vector of " + std::to_string(a.cols) +
                        " components, one for each of its columns. ";
        if (a.cols == 4 && b.rows == 3)
            return s + "Make the vec3 a vec4: " + quote(l + " * vec4(" + r + ", 1.0)") +
                   " for a position (w = 1: the translation applies), " +
                   quote(l + " * vec4(" + r + ", 0.0)") +
                   " for a direction; or use the upper-left 3x3 part, " + quote("mat3(" + l + ") * " + r) +
                   ".";
        if (a.cols == 3 && b.rows == 4)
            return s + "Drop the w component with a swizzle, " + quote(l + " * " + r + ".xyz") +
                   ", or use a mat4.";
        return s + "Build the vector to that size, or use a matrix of " + std::to_string(b.rows) +
               " columns.";
    }
    if (a.kind == Shape::Vector && b.kind == Shape::Matrix)
        return "A vector on the left of a matrix is a row: `v * M` needs as many components as M has rows "
               "(" +
               std::to_string(b.rows) + " for a " + typeName(b) +
               "). Usually the matrix belongs on the left: " + quote("M * v") + ".";
    return "In " + quote("A * B") + " A needs as many columns as B has rows; a " + typeName(a) + " has " +
           std::to_string(a.cols) + " and a " + typeName(b) + " " + std::to_string(b.rows) +
           ". Check the order of the two (matrix products do not commute) or convert one, e.g. " +
           quote("mat3(M)") + ".";
}

}  // namespace

void explainMatrixProduct(Diagnostic& d, const Ctx& c, std::size_t f) {
    d.message = "the sizes in this matrix product do not agree";
    d.explanation =
        "A matCxR (C columns, R rows) times a vector needs C components, and a vector times it needs R; "
        "mat4 * vec3 is the usual slip: write vec4(p, 1.0) for a position, or use mat3(M).";
    d.column = caretFor(c.m, f, d.line, d.column, "");
    if (f >= c.m.tokens.size()) return;
    std::vector<Token> line;
    for (const Token& t : c.m.tokens[f])
        if (t.line == d.line) line.push_back(t);
    for (std::size_t i = 0; i < line.size(); ++i) {
        if (line[i].text != "*") continue;
        // The left side: the chain of operands joined by `*` that ends here, folded left to right.
        std::vector<Operand> chain;
        std::size_t end = i;
        for (;;) {
            const std::size_t start = operandStart(line, end);
            if (start == std::string::npos) break;
            chain.insert(chain.begin(), operandFrom(c.m, f, line, start));
            if (chain.front().end != end) {  // what stands there is not one operand
                chain.clear();
                break;
            }
            if (start == 0 || line[start - 1].text != "*") break;
            end = start - 1;
        }
        if (chain.empty()) continue;
        std::optional<Shape> left = chain.front().shape;
        for (std::size_t k = 1; k < chain.size() && left; ++k)
            left = chain[k].shape ? product(*left, *chain[k].shape) : std::nullopt;
        const Operand right = operandFrom(c.m, f, line, i + 1);
        if (!left || !right.shape || product(*left, *right.shape)) continue;
        const std::string left_text = joined(line, chain.front().begin, chain.back().end);
        const std::string right_text = joined(line, right.begin, right.end);
        d.column = line[i].column;
        d.message = quote(left_text) + " is a " + typeName(*left) + " and " + quote(right_text) + " a " +
                    typeName(*right.shape) + ": their sizes do not agree for `*`";
        d.explanation = advice(*left, *right.shape, left_text, right_text);
        return;
    }
}

}  // namespace shaderlab::glsl_detail
