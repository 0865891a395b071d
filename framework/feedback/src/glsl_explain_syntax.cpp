// Syntax errors explained: Mesa notices a missing ';' at the next token, often on a later line,
// and reports a file that ends inside a block as an unexpected end of file. This points at the
// spot to fix (the end of the statement, the `{` never closed, the word that is not a type) and
// counts brackets when nothing more certain is known. Errors after the syntax error are not its
// business (explainCompileLog folds them into this one).
#include <algorithm>
#include <string>
#include <vector>

#include "glsl_explain_detail.h"

namespace shaderlab::glsl_detail {

namespace {

bool knownName(const StageModel& m, const std::string& name) {
    for (const Decl& d : m.decls)
        if (d.name == name) return true;
    const auto& f = builtinFunctions();
    const auto& v = builtinVariables();
    return builtinTypes().count(name) || isKeyword(name) || std::find(f.begin(), f.end(), name) != f.end() ||
           std::find(v.begin(), v.end(), name) != v.end();
}

std::string indentOf(const std::string& line) {
    std::size_t n = 0;
    while (n < line.size() && isBlank(line[n])) ++n;
    return line.substr(0, n);
}

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

}  // namespace

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

}  // namespace shaderlab::glsl_detail
