// The viewer's renders, done outside the window process. start() forks a small server before
// the window opens any GL context or thread; the server holds no GL either and runs each request
// through renderLabIsolated(), so student GLSL only ever runs in a grandchild with a time and
// memory limit: a shader that hangs or crashes the driver costs one picture, never the window.
// The server is one process for the viewer's lifetime (fork from a process that holds a GL
// driver's threads is what this avoids). No GLFW and no GL here.
#pragma once

#include <sys/types.h>

#include <memory>
#include <string>

#include "grader/reports/report.h"
#include "shaderlab/lab/lab_spec.h"
#include "shaderlab/render/isolated_render.h"
#include "shaderlab/scene/camera.h"

namespace shaderlab::viewer {

struct RenderRequest {
    std::string shader_dir;        // the submission's lab folder (or the reference solution's)
    std::string containment_root;  // the submission folder (RenderOptions::containment_root)
    std::string scene;             // one scene of the lab
    CameraOrbit orbit;
    double timeout_s = 5.0;
    // Not Off: the scene's vertex data instead of the lab's passes (shaderlab/render/debug_view.h);
    // shader_dir is then not read.
    DebugView debug_view = DebugView::Off;
};

// A whole lab graded as `check` grades it (gradeSubmission with the same options), for the
// verdict, goals and known-mistake hints of a workbench; no pictures are written.
struct GradeRequest {
    std::string submission_root;  // holds <lab id>/
    std::string labs_root;
    std::string reference_root;  // empty: the stored goldens
    IsolationLimits limits;
};

class RenderService {
  public:
    ~RenderService();
    RenderService(const RenderService&) = delete;
    RenderService& operator=(const RenderService&) = delete;

    // Forks the server. Call before creating any GL context or thread.
    static std::unique_ptr<RenderService> start(const LabSpec& spec, Backend backend, std::string* error);

    // Renders one scene with every pass read back (RenderOptions::keep_all_passes). Blocks for
    // as long as the render takes (at most the request's timeout, plus reading the images);
    // call it from one thread at a time. A server that has died answers "crashed".
    IsolatedRender render(const RenderRequest& request);

    // Grades the lab of start()'s spec (see GradeRequest) into `out` (one lab). Blocks like
    // render(); false, with the reason, when the server stopped answering.
    bool grade(const GradeRequest& request, grader::Report* out, std::string* error);

    // Stops the server now (a render in flight answers "crashed"); for quitting the window.
    void shutdown();

  private:
    RenderService() = default;
    pid_t pid_ = -1;
    int to_server_ = -1, from_server_ = -1;
};

}  // namespace shaderlab::viewer
