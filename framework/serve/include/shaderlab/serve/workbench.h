// The browser workbench's model of one lab, with no HTTP in it: the student's pictures of the scene
// and camera on the page, the reference's, the judgement of every image, and the lab's verdict
// as `check` gives it. Every render goes through the render server (shaderlab/live/render_service.h):
// the grader's passes and limits, in a child process, the same path as the window and the grade.
// A save in the student's lab folder (however the editor saves) renders and grades again.
//
// What the page asks for is served from immutable snapshots: a snapshot is one render of one view,
// numbered (`seq`), with its pictures encoded on demand and kept with it; a page that asks for a
// picture of a snapshot that is gone gets nothing, and asks for the newest state again. A debug
// view of the scene's vertex data (shaderlab/render/debug_view.h), when the page asks for one, is a
// snapshot of its own, numbered alike, drawn by the same render server.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "shaderlab/gl/gl_context.h"
#include "shaderlab/lab/lab_spec.h"
#include "shaderlab/render/isolated_render.h"
#include "shaderlab/scene/camera.h"

namespace shaderlab::serve {

struct WorkbenchOptions {
    LabSpec spec;                 // the lab, parsed and valid
    std::string labs_root;        // where its lab.json lives
    std::string submission_root;  // folder mirroring labs/; the student's files are in <root>/<lab id>
    std::string reference_root;   // reference solutions (same layout); empty: the stored goldens
    Backend backend = Backend::OSMesa;
    double view_timeout_s = 5.0;                                        // one scene's render for the picture
    IsolationLimits grade_limits{10.0, 30.0, std::size_t(2048) << 20};  // `check`'s
    bool grade = true;                                                  // grade the lab on every save
    std::chrono::milliseconds poll{20};                                 // the folder watch
    // What the terminal is told, one message at a time (several lines at most), from the
    // workbench's threads: saves, pictures, errors with the lines around them and the editor
    // command that opens them, grades. Unset: nothing is said.
    std::function<void(const std::string& message)> say;
};

// What a picture request names: one image of a snapshot, in one form (Debug: of a debug view's).
enum class PictureKind { Student, Reference, Diff, File, Debug };

class Workbench {
  public:
    // Forks the render server (before any thread of this process exists: call it first).
    static std::unique_ptr<Workbench> create(const WorkbenchOptions& options, std::string* error);
    ~Workbench();
    Workbench(const Workbench&) = delete;
    Workbench& operator=(const Workbench&) = delete;

    // Starts the folder watch and the render thread, and asks for the first pictures and grade.
    void start();
    // Stops both threads; waiters in waitForChange() return.
    void stop();

    // The page's state as JSON (docs/students.md, "In your browser", describes what it shows).
    nlohmann::json state() const;
    // The state's version: it grows with every change a page should show.
    std::uint64_t version() const;
    // Blocks until version() differs from `seen`, `timeout` passes or stop(); returns version().
    std::uint64_t waitForChange(std::uint64_t seen, std::chrono::milliseconds timeout);

    // Shows `scene` (a scene of the lab) through `orbit` (the graded camera turned); renders again.
    // `debug` not Off: the page shows that debug view of the vertex data instead of the lab's picture
    // (the lab's picture is still rendered when the scene or camera changes, for the verdict).
    bool setView(const std::string& scene, const CameraOrbit& orbit, DebugView debug, std::string* error);

    // One picture of snapshot `seq`, PNG-encoded: image `index` of its list (File: input file
    // `index` of the lab). False when the snapshot is gone or has no such picture.
    bool picture(std::uint64_t seq, PictureKind kind, int index, std::string* png);
    // The values at pixel (x, y) of image `index` of snapshot `seq`: student and reference RGBA
    // as rendered (floats) and the FLIP error there; of a debug view's, its RGB and what it reads.
    bool pixel(std::uint64_t seq, int index, int x, int y, nlohmann::json* out) const;

    struct Impl;

  private:
    explicit Workbench(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

}  // namespace shaderlab::serve
