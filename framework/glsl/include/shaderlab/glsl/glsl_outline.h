// A shader's top-level declarations, read from its tokens: preprocessor lines, function
// definitions and prototypes, global variables (uniforms, inputs, outputs, constants, plain
// globals), structs, interface blocks. For each, the names it declares and the names it uses, so
// that a function can be taken out of one file with what it needs (glsl_compose.h).
//
// It is not a GLSL parser: it splits the text where a declaration ends (a ';' or a function body's
// '}' outside any bracket) and reads the few shapes a declaration's head has. It does not check
// types, expand macros or follow #include. It never fails on any text; what it cannot read is an
// Other declaration, and unbalanced brackets are said in `error`.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "shaderlab/glsl/glsl_tokens.h"

namespace shaderlab::glsl {

enum class DeclKind {
    Directive,  // a preprocessor line (its continuation lines included)
    Function,   // a definition, with its body
    Prototype,  // a declaration without a body
    Variable,   // a global variable, constant, uniform, input or output
    Struct,     // `struct S { ... };`, with any variables declared after the '}'
    Block,      // an interface block: `uniform B { ... } b;`
    Other,      // `precision highp float;`, `layout(...) in;`, or what this reader does not know
};

struct Declaration {
    DeclKind kind = DeclKind::Other;
    std::size_t first = 0, last = 0;  // token indices, inclusive
    std::size_t begin = 0, end = 0;   // byte range in the text: first token's start to last token's end
    // Declared names: a function's, each variable's, a struct's and its variables', a block's
    // instance (or its members when it has none), a #define's macro.
    std::vector<std::string> names;
    // Identifiers used, not declared here, in order of first use (members and swizzles after '.'
    // are not names): what the declaration needs from the rest of the file. For a function, its
    // parameters and locals are among them when they are named like something global.
    std::vector<std::string> uses;
    // Functions and prototypes: the return type and each parameter's type as a call sees them
    // ("vec3", "out float", "float[3]"; `in`, `const` and precision qualifiers dropped), and the
    // head as written, whitespace collapsed ("vec3 diffuse(vec3 n, vec3 l)").
    std::string return_type;
    std::vector<std::string> parameter_types;
    std::string head;
    std::size_t body_first = 0;  // Function: token index of the body's '{'
    // Variables: the storage qualifier that decides where the value comes from ("uniform", "in",
    // "out", "const", "buffer", "shared", "attribute", "varying"), "" for a plain global.
    std::string storage;
    std::string directive;  // Directive: its name without '#' ("define", "version", "if", ...)
};

struct Outline {
    std::vector<Token> tokens;
    std::vector<Declaration> declarations;  // in the order of the text
    std::string error;                      // brackets that do not balance; empty when they do
};

Outline outlineGlsl(std::string_view text);

// The declarations of `outline` that declare `name` (several for an overloaded function).
std::vector<const Declaration*> declarationsNamed(const Outline& outline, const std::string& name);

// A declaration's tokens as text, one space between tokens: equal for two spellings that differ
// only in comments, spacing and line breaks.
std::string canonicalText(std::string_view text, const Outline& outline, const Declaration& d);

}  // namespace shaderlab::glsl
