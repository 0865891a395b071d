// GLSL compile and link logs in plain words; see glsl_explain.h. The message patterns are Mesa
// 22.3's (src/compiler/glsl/ast_to_hir.cpp, ast_function.cpp, linker.cpp, link_varyings.cpp).
// This file reads one stage's compile log: it picks the explanation for each message and keeps
// one error per root cause. The explanations themselves are glsl_explain_syntax.cpp,
// glsl_explain_names.cpp and glsl_explain_types.cpp; link logs are glsl_link_log.cpp's, and our
// own warnings glsl_stage_scan.cpp's.
#include "shaderlab/feedback/glsl_explain.h"

#include <map>
#include <optional>
#include <regex>
#include <string>
#include <vector>

#include "glsl_explain_detail.h"

namespace shaderlab {

using namespace glsl_detail;

namespace {

std::string firstLine(const std::string& s) { return s.substr(0, s.find('\n')); }

std::size_t fileIndex(const StageModel& m, const std::string& file) {
    for (std::size_t i = 0; i < m.text->files.size(); ++i)
        if (m.text->files[i] == file) return i;
    return 0;
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
    if (std::regex_match(msg, m, no_return)) return explainNoReturn(d, c, f, m[1], m[2]);
    if (std::regex_match(msg, m, wrong_return)) return explainWrongReturn(d, c, f, m[1], m[2], m[3]);
    if (std::regex_match(msg, m, swizzle) || std::regex_match(msg, m, field))
        return explainComponentAccess(d, c, f, m[1], msg.rfind("cannot access field", 0) == 0);
    if (std::regex_match(msg, m, too_few)) return explainTooFew(d, c, f, m[1]);
    if (std::regex_match(msg, m, too_many))
        return explainTooMany(d, c, f, m[1].matched ? m[1].str() : m[2].str());
    if (std::regex_match(msg, m, uninitialized)) return explainUninitialized(d, c, f, m[1]);
    if (msg == "Unterminated #if") {
        d.column = 0;
        d.message = "this `#if` has no `#endif`";
        d.explanation = "Every `#if`, `#ifdef` and `#ifndef` needs an `#endif` below it.";
        return;
    }
    if (explainOperator(d, c, f, msg)) return;
    // Not one we know: the driver's words with jargon replaced, and a caret only under the name it
    // quotes.
    static const std::regex quoted(R"([`'](\w+)')");
    d.column = std::regex_search(msg, m, quoted) ? caretFor(c.m, f, d.line, d.column, m[1]) : 0;
}

void finish(Diagnostic& d, const StageModel& m, std::size_t file) {
    d.message = scrubJargon(d.message);
    d.explanation = scrubJargon(d.explanation);
    attachSource(d, m, file);
}

}  // namespace

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

}  // namespace shaderlab
