// Compiles and links the student's GLSL, keeping compile and link logs as structured data.
// The framework injects a small prelude after the student's `#version` line (or a default
// `#version 330 core` when there is none) followed by a `#line` directive, so the driver's line
// numbers are the student's own. `#include "file"` lines are replaced by the file's text between
// `#line` directives that give each included file its own source-string number, so diagnostics
// name the file a line belongs to. The logs are then explained in plain words, one error per root
// cause, at the line to fix (framework/feedback/include/shaderlab/feedback/glsl_explain.h). This file does
// not decide what a failure is worth: the grader does.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "shaderlab/base/paths.h"
#include "shaderlab/feedback/diagnostic.h"

namespace shaderlab {

// Reads the file an `#include "name"` in `includer` names (a FileText with ok = false and an
// error when it cannot). Empty: includes are refused.
using IncludeReader = std::function<FileText(const std::string& includer, const std::string& name)>;

// GLSL text as handed to the driver, and where the student's first line landed.
struct PreparedSource {
    std::string text;
    int first_student_line = 1;
    std::vector<std::string> files;  // by source-string number: [0] the file itself, then includes
    std::vector<std::string> texts;  // their text, by the same numbers
    std::vector<Diagnostic> errors;  // includes that could not be read (or nest too deep)
    // Not text a driver should see (a NUL byte, which would silently end the source there):
    // `errors` says where, and the stage is not compiled.
    bool rejected = false;
};

// Inserts the prelude after the `#version` directive (keeping the student's version) and a
// `#line` so that line numbers in the driver's log match the student's file, and expands
// `#include "name"` lines (at most 16 levels, each file once) with `includes`.
PreparedSource prepareSource(const std::string& student_text, const std::string& prelude,
                             const std::string& file = "", const IncludeReader& includes = {});

// Parses a driver info log (Mesa "0:12(5): error: ...", NVIDIA "0(12) : error C1008: ...",
// "ERROR: 0:12: ...") into diagnostics. The leading source-string number picks the file from
// `files` (the first one when out of range). Lines it cannot parse become diagnostics with line
// 0 so nothing the driver said is lost; Mesa's indented candidate lines join the message above.
std::vector<Diagnostic> parseInfoLog(const std::string& log, const std::vector<std::string>& files);
std::vector<Diagnostic> parseInfoLog(const std::string& log, const std::string& file);

// The loop guard. llvmpipe stops any loop after 65,535 iterations, so an endless loop does not
// hang: it ends with whatever it computed, and a loop whose result is unused is removed. Either
// way a shader that never terminates on a GPU could pass. A guarded program counts, per shader
// invocation, the iterations of all its loops (a call in every `for` and `while` condition);
// past kLoopGuardLimit every loop ends at once and the invocation adds 1 to a counter in a
// storage buffer at binding kLoopGuardBinding, which the renderer reads after each pass. There is
// a counter for each stage, source string and line (kLoopGuardWords uints: stage-major, then
// kLoopGuardFiles source strings of kLoopGuardLines lines each; a later file or line counts in the
// last), so the counter says where the loop was (the preprocessor's __LINE__, which the `#line`
// directives make the student's own, and the number of the last `#line`); loopSite() reads that
// back. The limit sits below llvmpipe's own so that it is always met first; the labs' loops stay
// far below it (the irradiance convolution of lab 07, the largest, runs 6 x 16 x 16 + 6 x 16 + 6 =
// 1,638).
constexpr int kLoopGuardLimit = 60000;
constexpr unsigned kLoopGuardBinding = 7;
constexpr int kLoopGuardFiles = 8;
constexpr int kLoopGuardLines = 2048;
constexpr int kLoopGuardWords = 2 * kLoopGuardFiles * kLoopGuardLines;
// `prepared` (a prepareSource() text) with a guard call in the condition of every `for` and
// `while` (`do ... while` included) outside comments: `while (c)` becomes
// `while (shaderlab_loop_tick() && (c))`. Lines and the text outside the conditions are kept;
// before each `#line N F` the guard's file number is set to F (two directives).
std::string guardLoops(const std::string& prepared);
// The declarations a guarded stage needs (stage 0: vertex, 1: fragment), for the prelude.
std::string loopGuardPrelude(int stage);

// The loop the guard stopped, in the student's files: the file as the diagnostics name it, the
// 1-based line and the column of its `for`/`while`/`do` (0 when the line holds none or several),
// and the line's text. `file` is empty when the place is unknown.
struct LoopSite {
    std::string file;
    int line = 0;
    int column = 0;
    std::string source_line;
};

struct StageLog {
    std::string file;
    std::string stage;  // "vertex" | "fragment"
    bool compiled = false;
    std::string info_log;
    double compile_us = 0.0;
};

struct UniformSlot {
    std::string name;  // without the "[0]" GL adds to arrays
    int location = -1;
    unsigned type = 0;  // GL type enum
    int size = 1;       // array length
};

struct FragmentOutput {
    std::string name;
    int location = -1;
};

struct StageSource {
    std::string file;
    std::string text;
    IncludeReader includes;
};

class ShaderProgram {
  public:
    ShaderProgram() = default;
    ~ShaderProgram();
    ShaderProgram(const ShaderProgram&) = delete;
    ShaderProgram& operator=(const ShaderProgram&) = delete;
    ShaderProgram(ShaderProgram&& other) noexcept;
    ShaderProgram& operator=(ShaderProgram&& other) noexcept;

    // Builds from two sources. Fragment outputs named `o_<attachment>` or `<attachment>` are bound
    // to that attachment's location before linking. Returns false on a compile or link error;
    // logs and diagnostics are filled either way (warnings too).
    // With `guard_loops`, the program that is kept for drawing is a second build of the same
    // sources with every loop guarded (guardLoops()); the diagnostics come from the plain build.
    // When the guarded build fails (a very old #version, an #extension of the student's), the
    // plain program is kept and loopGuarded() is false.
    bool build(const StageSource& vertex, const StageSource& fragment,
               const std::vector<std::string>& attachments = {"color"}, bool guard_loops = false);
    bool build(const std::string& vertex_file, const std::string& vertex_text,
               const std::string& fragment_file, const std::string& fragment_text);

    bool loopGuarded() const { return loop_guarded_; }
    // The loop at `line` of source string `file` of a guarded stage (0: vertex, 1: fragment), as
    // its counter in the guard's buffer names it (kLoopGuardWords); an empty site for a place the
    // stage does not have.
    LoopSite loopSite(int stage, int file, int line) const;
    bool compiled() const { return compiled_; }
    bool linked() const { return linked_; }
    unsigned id() const { return program_; }
    const std::vector<StageLog>& stages() const { return stages_; }
    const std::string& linkLog() const { return link_log_; }
    const std::vector<Diagnostic>& diagnostics() const { return diagnostics_; }
    // The text each stage was compiled from (prelude and includes expanded).
    const std::string& preparedText(int stage) const { return prepared_[stage == 0 ? 0 : 1]; }

    // Active uniforms by name, without the "[0]" GL adds to arrays.
    const UniformSlot* uniform(const std::string& name) const;
    const std::vector<UniformSlot>& uniforms() const { return uniform_list_; }
    // Active fragment outputs (needs OpenGL 4.3 program interface queries; empty before that).
    const std::vector<FragmentOutput>& outputs() const { return outputs_; }
    bool outputsKnown() const { return outputs_known_; }
    // Sets every non-sampler uniform back to the value it had right after linking (its GLSL
    // initialiser, or zero), so no value of one pass leaks into the next pass using the program.
    void restoreDefaults() const;

  private:
    void release();
    void snapshotDefaults();
    unsigned guardedProgram(const StageSource& vertex, const StageSource& fragment,
                            const std::vector<std::string>& attachments) const;
    unsigned program_ = 0;
    bool compiled_ = false, linked_ = false, outputs_known_ = false, loop_guarded_ = false;
    std::vector<StageLog> stages_;
    std::string link_log_;
    std::vector<Diagnostic> diagnostics_;
    std::map<std::string, std::size_t> uniform_index_;
    std::vector<UniformSlot> uniform_list_;
    std::vector<FragmentOutput> outputs_;
    std::string prepared_[2];
    // Each stage's files by source-string number and their text, for loopSite().
    std::vector<std::string> stage_files_[2], stage_texts_[2];
    struct Default {
        int location;
        unsigned type;
        int count;
        std::vector<std::uint32_t> bits;  // raw 32-bit words of the values
    };
    std::vector<Default> defaults_;
};

// The default prelude: defines a submission may test for.
std::string defaultPrelude();

// GLSL's name of a GL type enum ("vec3", "sampler2DShadow"), or "another type".
const char* glslTypeName(unsigned type);

}  // namespace shaderlab
