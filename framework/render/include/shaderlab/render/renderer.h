// Executes a LabSpec: for every graded scene, runs the lab's passes in order (repeat groups as
// often as asked) on the current GL context and reads back the graded passes' float targets. The same code
// path serves headless grading and the student viewer (framework/viewer/, through a child process): it
// only needs a current context. It does not judge images (grader/ does) and does not isolate untrusted
// code: the caller runs it in a child process when the shaders are a submission's.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "grader/metrics/image.h"
#include "shaderlab/lab/lab_spec.h"
#include "shaderlab/render/shader_program.h"
#include "shaderlab/scene/camera.h"
#include "shaderlab/scene/scene.h"

namespace shaderlab {

// Outcome of building or rendering one lab for one submission. The closed set of statuses the
// grader reports adds passed/failed/timeout/crashed on top of these.
enum class RenderStatus { Ok, Missing, CompileError, LinkError, RenderError };
const char* renderStatusName(RenderStatus status);

struct PassImage {
    std::string pass;        // pass name
    std::string target;      // target name
    std::string attachment;  // colour attachment name, or "depth"
    bool graded = false;
    // RGBA float, top row first, NaN/Inf preserved. A cube target's six faces side by side
    // (+x, -x, +y, -y, +z, -z); depth as grey.
    grader::Image color;
    // 1 where geometry wrote depth; all 1 when a fullscreen pass drew into the target (or it
    // has no depth).
    std::vector<std::uint8_t> coverage;
};

struct SceneRender {
    std::string scene;
    // Graded images, in pass order and attachment order (the last one is the final image);
    // every pass's when RenderOptions::keep_all_passes.
    std::vector<PassImage> passes;
    double render_ms = 0.0;
    // Set when the scene's file did not load ("<path>: <problem>"); `passes` is then empty and
    // the lab's other scenes are rendered all the same.
    std::string error;
};

struct LabRender {
    RenderStatus status = RenderStatus::Ok;
    std::string message;                  // one line a person reads first
    std::vector<Diagnostic> diagnostics;  // compile/link logs and uniform warnings
    std::vector<SceneRender> scenes;
    // A loop ran past the loop guard's limit (ShaderProgram, "loop guard"): the render stopped
    // with RenderError and `message` says where. The grader reports it as a timeout.
    bool endless_loop = false;
};

// Pass isolation (PassSpec::isolate): an image that stands in for what isolated passes read, the
// reference's image of one graded pass in one scene (as the grader has it: PassImage::color).
struct StandIn {
    std::string scene, pass, attachment;
    grader::Image image;
};

// Instead of the lab's passes, a picture of each scene's vertex data drawn by the framework's own
// program (debug_view.h says what each shows). Off: the lab's passes.
enum class DebugView { Off, Normals, Tangents, Bitangents, Handedness, Uv, UvChecker };

struct RenderOptions {
    bool keep_all_passes = false;          // read back ungraded passes too (debugging a multi-pass lab)
    std::vector<std::string> only_scenes;  // empty: all scenes of the lab
    // The submission folder: student files must resolve inside it (so a lab folder that is a
    // symlink out of the submission is refused). Empty: the shader folder itself.
    std::string containment_root;
    // Turns every scene's camera about its target (the student viewer's orbit and zoom); the
    // lights stay where the graded view puts them. Identity: the graded view.
    CameraOrbit orbit;
    // Told what the renderer is about to do, one line each: "compile <vertex> <fragment>",
    // "scene <scene>", "pass <scene> <pass>" (a repeated pass on its first run only) and
    // "done <scene> <milliseconds>". May be empty.
    std::function<void(const std::string&)> progress;
    // When set, every pass with `isolate` reads these instead of what the submission's own passes
    // drew, wherever one is given (standInSource in lab_spec.h says which it wants). Empty: the
    // pipeline as it is.
    std::vector<StandIn> stand_ins;
    // Student files given as text instead of read from the submission (goal isolation: the
    // reference's files with some of the student's functions swapped in), by their name in
    // lab.json. Includes of student files are looked up here too.
    std::map<std::string, std::string> source_overrides;
    // Not Off: renderLab draws this debug view of every scene (renderDebugView, debug_view.h) and
    // reads none of the submission's files.
    DebugView debug_view = DebugView::Off;
};

// Renders `spec` with the shader files found in `shader_dir` (the submission's lab folder,
// e.g. reference_solutions/01-phong). Needs a current GL context.
LabRender renderLab(const LabSpec& spec, const std::string& shader_dir, const RenderOptions& options = {});

}  // namespace shaderlab
