// Explains GLSL compile and link logs in plain words. Mesa 22.3 (what this project renders with)
// notices a missing ';' at the next token, names tokens the way its parser does
// (BASIC_TYPE_TOK), counts columns in the preprocessor's output (every run of blanks or comments
// is one character, macros expanded), follows one mistake with a dozen consequences, and prints
// link problems without positions, repeated, with a stray '.' on the next line. This turns each
// log into diagnostics that point at the line to fix, carry that line with a caret where the
// column is certain, explain the common mistakes and keep one error per root cause; the driver's
// own words stay in `driver_message`. It also warns about what Mesa accepts silently but other
// drivers reject or that quietly breaks an image. A message it does not know passes through with
// parser jargon replaced. It compiles nothing and knows nothing about labs.
#pragma once

#include <string>
#include <vector>

#include "shaderlab/feedback/diagnostic.h"

namespace shaderlab {

// One stage's source as the driver saw it, by source-string number ([0] the stage's own file,
// then its includes), as prepareSource numbered them.
struct StageText {
    std::string stage;  // "vertex" | "fragment"
    std::vector<std::string> files;
    std::vector<std::string> texts;
};

// One stage's compile log, already split by parseInfoLog, explained and collapsed: after a
// syntax error nothing else of the stage is kept, an undeclared name is reported once, and an
// error on a line that already has one (or about a value of type `error`) counts as a
// consequence in the first one's `follow_on`. `other` is the program's other stage (may be
// null), for "declared in the other stage" hints.
std::vector<Diagnostic> explainCompileLog(const std::vector<Diagnostic>& parsed, const StageText& stage,
                                          const StageText* other);

// Warnings of our own from reading a stage that compiled: legacy GLSL that Mesa accepts in a core
// profile (texture2D, gl_FragColor, varying, attribute), integer division of literals that drops
// a fraction, and fragment inputs declared but never used.
std::vector<Diagnostic> scanStage(const StageText& stage);

// A link log, one diagnostic per problem, placed at the declaration it concerns.
std::vector<Diagnostic> explainLinkLog(const std::string& log, const StageText& vertex,
                                       const StageText& fragment);

// The 1-based column of `line` that Mesa's column `mesa_column` counts to, or 0 when it falls
// between tokens or past the end (glcpp writes each run of blanks and comments as one space).
int sourceColumnOfMesa(const std::string& line, int mesa_column);

}  // namespace shaderlab
