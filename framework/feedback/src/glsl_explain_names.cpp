// Errors about a name explained: undeclared (used too early, out of its block, declared only in
// the other stage, or misspelt: "did you mean"), a function that does not exist yet, a read-only
// variable assigned, a name declared twice, a variable read before it has a value. It decides
// nothing about types (glsl_explain_types.cpp does).
#include <algorithm>
#include <string>
#include <vector>

#include "glsl_explain_detail.h"
#include "shaderlab/base/json_messages.h"

namespace shaderlab::glsl_detail {

namespace {

std::vector<std::string> variableNames(const StageModel& m) {
    std::vector<std::string> names;
    for (const Decl& d : m.decls)
        if (d.storage != "function" && d.storage != "struct") names.push_back(d.name);
    names.insert(names.end(), builtinVariables().begin(), builtinVariables().end());
    return names;
}

}  // namespace

std::string suggestion(const std::string& word, const std::vector<std::string>& candidates) {
    return word.size() < 3 ? std::string() : closestMatch(word, candidates);
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

void explainUninitialized(Diagnostic& d, const Ctx& c, std::size_t f, const std::string& name) {
    d.column = caretFor(c.m, f, d.line, d.column, name);
    d.message = quote(name) + " is used before it is given a value";
    d.explanation =
        "Its value is undefined: this machine happens to give 0, a GPU may give anything. Give it "
        "a value where it is declared, or on every path before it is read.";
}

}  // namespace shaderlab::glsl_detail
