// Executes a LabSpec: for every graded scene, runs the lab's passes in order on the current GL
// context and reads back the graded passes' float targets. The same code path serves headless
// grading and (later) the student's window: it only needs a current context.
// It does not judge images (grader/ does) and does not isolate untrusted code: the caller runs
// it in a child process when the shaders are a submission's.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "grader/image.h"
#include "shaderlab/lab_spec.h"
#include "shaderlab/scene.h"
#include "shaderlab/shader_program.h"

namespace shaderlab {

// Outcome of building or rendering one lab for one submission. The closed set of statuses the
// grader reports adds passed/failed/timeout/crashed on top of these.
enum class RenderStatus { Ok, Missing, CompileError, LinkError, RenderError };
const char* renderStatusName(RenderStatus status);

struct PassImage {
    std::string pass;    // pass name
    std::string target;  // target name
    bool graded = false;
    grader::Image color;                 // RGBA float, top row first, NaN/Inf preserved
    std::vector<std::uint8_t> coverage;  // 1 where scene geometry wrote depth; all 1 for fullscreen
};

struct SceneRender {
    std::string scene;
    std::vector<PassImage> passes;  // graded passes, in pass order (the last one is the final image)
    double render_ms = 0.0;
};

struct LabRender {
    RenderStatus status = RenderStatus::Ok;
    std::string message;                  // one line a person reads first
    std::vector<Diagnostic> diagnostics;  // compile/link logs and uniform warnings
    std::vector<SceneRender> scenes;
};

struct RenderOptions {
    bool keep_all_passes = false;          // read back ungraded passes too (debugging a multi-pass lab)
    std::vector<std::string> only_scenes;  // empty: all scenes of the lab
    // The submission folder: student files must resolve inside it (so a lab folder that is a
    // symlink out of the submission is refused). Empty: the shader folder itself.
    std::string containment_root;
};

// Renders `spec` with the shader files found in `shader_dir` (the submission's lab folder,
// e.g. reference_solutions/01-phong). Needs a current GL context.
LabRender renderLab(const LabSpec& spec, const std::string& shader_dir, const RenderOptions& options = {});

}  // namespace shaderlab
