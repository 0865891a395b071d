// `shaderlab view`: a window on one lab, rendered from a submission's shaders by the grader's own
// render path (renderLab through RenderService, in a child process), beside the reference, with
// the diff heat map, the per-scene verdict and a pass inspector; it renders again when a file of
// the submission's lab folder changes. The window is glue: GLFW for the window, Dear ImGui for
// the panels, the grader for every number. At start and after each change it also grades the
// whole lab as `check` does (same limits, same report), for the points, the goals not met and
// the known-mistake hints, in `check`'s words; it writes no report. Instead of the lab's picture it
// can show a debug view of the scene's vertex data (normals, tangents, texture coordinates: see
// shaderlab/render/debug_view.h), drawn by the same render server.
#pragma once

#include <string>

#include "shaderlab/gl/gl_context.h"
#include "shaderlab/lab/lab_spec.h"
#include "shaderlab/render/isolated_render.h"
#include "shaderlab/scene/camera.h"

namespace shaderlab::viewer {

struct ViewerOptions {
    LabSpec spec;                 // the lab, parsed and valid
    std::string submission_root;  // folder mirroring labs/; the lab's shaders are in <root>/<lab id>
    std::string reference_root;   // reference solutions (same layout); empty: the stored goldens
    std::string labs_root;        // where the lab's lab.json lives, for the grade
    IsolationLimits grade_limits{10.0, 30.0, std::size_t(2048) << 20};  // `check`'s
    Backend backend = Backend::OSMesa;
    double timeout_s = 5.0;  // one render of one scene
    std::string scene;       // first scene shown (empty: the lab's first)
    std::string image;       // first image shown, "pass.attachment" (empty: the final graded image)
    CameraOrbit orbit;       // first camera: the graded view turned by this
    // For scripts and tests: exit after this many frames once the first picture (or error), the
    // reference (when one is rendered) and the newest grade are in, or once this many pictures
    // (or errors) made after a file change are shown and graded (0: neither).
    int frames = 0;
    int exit_after_reloads = 0;
    std::string screenshot;         // at exit: the picture as the window shows it, one pixel per image pixel
    std::string screenshot_window;  // at exit: the whole window, panels included
    std::string panel_text;         // at exit: the lines of the grade and verdict panels, as drawn
    std::string view_mode = "student";      // student | reference | diff | split
    DebugView debug_view = DebugView::Off;  // first picture: a debug view (Off: the lab's picture)
    int width = 1180, height = 760;
};

// Runs the window until it is closed. Returns 0, or 2 when it cannot open (no display, no GL 3.3).
int runViewer(const ViewerOptions& options);

}  // namespace shaderlab::viewer
