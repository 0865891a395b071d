// What the files behind glsl_explain.h share and the header does not say: the student's source
// read into tokens and declarations, lookups on it (lines, tokens, carets, declarations), GLSL's
// own names, Mesa's token names in words, the text helpers of every message (quoting, trimming),
// and one explainer per kind of compile error. Private to framework/feedback/src; nothing here
// is part of the library's interface.
#pragma once

#include <cstddef>
#include <initializer_list>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "shaderlab/feedback/diagnostic.h"
#include "shaderlab/feedback/glsl_explain.h"

namespace shaderlab::glsl_detail {

constexpr std::size_t kMaxNameLength = 64;  // names in messages; a student can write any length

inline bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

inline std::string quote(const std::string& s) {
    return "`" + (s.size() > kMaxNameLength ? s.substr(0, kMaxNameLength) + "..." : s) + "`";
}

inline std::string trim(const std::string& s) {
    std::size_t a = 0, b = s.size();
    while (a < b && isBlank(s[a])) ++a;
    while (b > a && isBlank(s[b - 1])) --b;
    return s.substr(a, b - a);
}

// ---- the student's source, tokenized (glsl_source_model.cpp) ---------------------------------

struct Token {
    enum Kind { Name, Number, Symbol } kind = Symbol;
    std::string text;
    int line = 0;    // 1-based
    int column = 0;  // 1-based, in the source line
};

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

StageModel buildModel(const StageText& t);

const std::string* lineOf(const StageModel& m, std::size_t file, int line);
const Token* tokenAt(const StageModel& m, std::size_t file, int line, int column);

// Where a diagnostic about `name` belongs on its line: Mesa's column, when a token starts there
// and is `name` (any token when `name` is empty); else the one `name` on the line; else 0.
int caretFor(const StageModel& m, std::size_t file, int line, int mesa_column, const std::string& name);

const Decl* findDecl(const StageModel& m, const std::string& name, bool functions);
const Decl* findGlobal(const StageModel& m, const std::string& name,
                       std::initializer_list<const char*> storages);

// Sets `source_line` from the file, and drops a column the line cannot hold.
void attachSource(Diagnostic& d, const StageModel& m, std::size_t file);

// ---- GLSL's own names (glsl_builtins.cpp) ----------------------------------------------------

const std::set<std::string>& builtinTypes();
bool isStorageWord(const std::string& s);
bool isKeyword(const std::string& s);
const std::vector<std::string>& builtinFunctions();
const std::vector<std::string>& builtinVariables();

// ---- Mesa's words (glsl_mesa_words.cpp) ------------------------------------------------------

// Mesa's parser token names, in words.
std::string tokenWords(const std::string& token);

// Replaces parser token names that slipped into a message (the safety net behind every rewrite).
std::string scrubJargon(const std::string& s);

// ---- compile errors, one explainer per kind --------------------------------------------------

struct Ctx {
    const StageModel& m;
    const StageModel* other;
};

// Each sets the message, explanation and column of `d` (Mesa's column on entry) for an error in
// file `f` of the stage.

// glsl_explain_syntax.cpp
void explainSyntax(Diagnostic& d, const Ctx& c, std::size_t f, const std::string& unexpected,
                   const std::string& expecting);

// glsl_explain_names.cpp

// "did you mean" only for names long enough that a near miss means something (for `v`, every
// one-letter name is one edit away).
std::string suggestion(const std::string& word, const std::vector<std::string>& candidates);

void explainUndeclared(Diagnostic& d, const Ctx& c, std::size_t f, const std::string& name);
void explainNoFunction(Diagnostic& d, const Ctx& c, std::size_t f, const std::string& name);
void explainReadOnly(Diagnostic& d, const Ctx& c, std::size_t f, const std::string& name);
void explainRedeclared(Diagnostic& d, const Ctx& c, std::size_t f, const std::string& name);
void explainUninitialized(Diagnostic& d, const Ctx& c, std::size_t f, const std::string& name);

// glsl_explain_types.cpp
void explainNoMatch(Diagnostic& d, const Ctx& c, std::size_t f, const std::string& name,
                    const std::string& args_text);
void explainAssignment(Diagnostic& d, const Ctx& c, std::size_t f, bool initializer, const std::string& from,
                       const std::string& to);
void explainNoReturn(Diagnostic& d, const Ctx& c, std::size_t f, const std::string& function,
                     const std::string& type);
void explainWrongReturn(Diagnostic& d, const Ctx& c, std::size_t f, const std::string& given,
                        const std::string& function, const std::string& returning);
void explainComponentAccess(Diagnostic& d, const Ctx& c, std::size_t f, const std::string& name,
                            bool is_field);
void explainTooFew(Diagnostic& d, const Ctx& c, std::size_t f, const std::string& type);
void explainTooMany(Diagnostic& d, const Ctx& c, std::size_t f, const std::string& type);
// The operator errors Mesa words without a name; false when `msg` is none of them.
bool explainOperator(Diagnostic& d, const Ctx& c, std::size_t f, const std::string& msg);

// glsl_explain_matrix.cpp: "size mismatch for matrix multiplication", at the `*` whose sides do not
// agree, with their types.
void explainMatrixProduct(Diagnostic& d, const Ctx& c, std::size_t f);

}  // namespace shaderlab::glsl_detail
