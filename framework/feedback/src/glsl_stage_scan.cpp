// Warnings of our own about a stage that compiled: what Mesa accepts silently but other drivers
// reject (texture2D, gl_FragColor, varying, attribute in a core profile), integer division of two
// literals that drops a fraction, and fragment inputs never used. It reads no driver log.
#include <map>
#include <regex>
#include <set>
#include <string>

#include "glsl_explain_detail.h"
#include "shaderlab/base/json_messages.h"

namespace shaderlab {

using namespace glsl_detail;

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

}  // namespace shaderlab
