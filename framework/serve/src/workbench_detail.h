// The workbench's insides, shared by workbench.cpp (threads, renders, snapshots) and
// workbench_state.cpp (what the page is told and shown). Private to framework/serve/src.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "grader/metrics/scoring.h"
#include "grader/reports/report.h"
#include "shaderlab/live/diagnostic_view.h"
#include "shaderlab/live/file_watch.h"
#include "shaderlab/live/render_service.h"
#include "shaderlab/serve/workbench.h"

namespace shaderlab::serve {

using Clock = std::chrono::steady_clock;

// One judged image: the verdict grading would give it and the heat map of its difference.
struct Judgement {
    grader::ImageVerdict verdict;
    grader::Thresholds thresholds;
    bool hdr = false;
    grader::Image heat;
};

// A texture a pass reads, as the page lists it.
struct InputEntry {
    std::string sampler;
    std::string from;  // "target" | "file" | "cube" | "generated"
    std::string label;
    int image = -1;  // from == target: the image of this snapshot the pass read
    int file = -1;   // from == file: the lab's input file
};

struct ImageEntry {
    const PassImage* student = nullptr;
    const PassImage* reference = nullptr;  // same pass and attachment, same size; may be null
    const PassSpec* pass = nullptr;
    std::vector<InputEntry> inputs;
};

// One render of one view, never changed once published except for its judgements (set once, on
// the render thread, under `m`) and the pictures encoded for the page (a cache).
struct Snapshot {
    std::uint64_t seq = 0;
    std::uint64_t generation = 0;  // the student's files it was rendered from
    std::string scene;
    CameraOrbit orbit;
    std::shared_ptr<const IsolatedRender> student;
    std::shared_ptr<const std::vector<PassImage>> reference;  // may be null
    std::string reference_note;                               // why there is none
    std::vector<ImageEntry> images;
    int final_image = -1;
    double render_ms = 0.0;
    double latency_ms = -1.0;  // from the save that asked for it to the picture (-1: no save)
    // A debug view's snapshot: which one (its one image has no reference and no pass), and what it
    // could not show. Off: the lab's picture.
    DebugView debug = DebugView::Off;
    std::vector<std::string> notes;
    // The render's warnings and notes as the page shows them (diagnosticsJson): errors stop a
    // render, so a picture has none.
    nlohmann::json diagnostics = nlohmann::json::array();

    mutable std::mutex m;
    std::vector<std::shared_ptr<const Judgement>> judged;  // by image; empty until judged
    mutable std::map<std::string, std::shared_ptr<const std::string>> pngs;
};

struct RenderFailureInfo {
    std::string title, text, scene;
    nlohmann::json diagnostics = nlohmann::json::array();
    std::uint64_t generation = 0;
    bool endless_loop = false;  // the loop guard stopped it (a time-out otherwise, when one)
};

// Diagnostics as the page shows them: each with the lines around it (diagnostic_view.h), the text
// the terminal prints, and the links that open it in an editor. `lab_folder` is the student's.
nlohmann::json diagnosticJson(const Diagnostic& d, const std::string& lab_folder);
nlohmann::json diagnosticsJson(const std::vector<Diagnostic>& ds, const std::string& lab_folder, bool errors);

// The heat map's colours, for the page's legend: the FLIP error at evenly spaced values.
nlohmann::json heatmapLegendJson();

struct Workbench::Impl {
    WorkbenchOptions opt;
    std::unique_ptr<viewer::RenderService> service;
    std::vector<std::string> input_files;  // the lab's input files (lab-relative), by index

    mutable std::mutex m;
    std::condition_variable changed;  // version moved (pages wait on it)
    std::condition_variable work;     // a job for the render thread, or stopping
    std::uint64_t version = 1;
    bool stopping = false;

    // What the page looks at, and what the render thread is asked to do.
    std::string scene;
    CameraOrbit orbit;
    std::uint64_t generation = 1;  // bumped by each settled change of the student's files
    std::int64_t pending_save_ns = 0;
    DebugView debug = DebugView::Off;  // the debug view the page shows (Off: the lab's picture)
    bool want_student = false, want_reference = false, want_grade = false, want_debug = false;
    std::string busy;  // what the render thread is doing ("" when idle)
    Clock::time_point busy_since;

    std::shared_ptr<const Snapshot> snapshot;  // the newest picture
    std::shared_ptr<const Snapshot> previous;  // the one before, for a page still loading it
    std::uint64_t next_seq = 1;
    std::shared_ptr<const IsolatedRender> reference;  // the newest reference render, and its view
    std::string reference_scene;
    CameraOrbit reference_orbit;
    std::string reference_error;
    std::map<std::string, std::shared_ptr<const std::vector<PassImage>>> goldens;  // by scene
    std::map<std::string, std::string> golden_errors;
    std::shared_ptr<const Snapshot> debug_snapshot;  // the newest debug view drawn, and the one before
    std::shared_ptr<const Snapshot> debug_previous;
    std::string debug_error;                   // the last debug view that was not drawn, and why
    std::optional<RenderFailureInfo> failure;  // the last render that gave no picture
    nlohmann::json grade;                      // the lab's grade as report.json has it (null until the first)
    std::uint64_t grade_generation = 0;
    std::string grade_error;
    std::map<int, std::shared_ptr<const grader::Image>> files;  // input files read, by index
    // Saves that changed nothing (FolderWatch::takeSavedUnchanged): how many, and the last files.
    std::uint64_t unchanged_saves = 0;
    std::vector<std::string> unchanged_files;
    std::string warnings_said;  // the render warnings last printed, to print each set once

    std::thread render_thread, watch_thread;

    void bump() {  // call with `m` held
        ++version;
        changed.notify_all();
    }
    std::string labFolder() const;
    void say(const std::string& message) const {
        if (opt.say) opt.say(message);
    }
    // What the terminal is told of a picture, a failed render, a grade (workbench_messages.cpp).
    void sayPicture(const Snapshot& snap, const IsolatedRender& r);
    void sayFailure(const RenderFailureInfo& info, const IsolatedRender& r);
    void sayVerdict(const Snapshot& snap);
    void sayGrade(const grader::ReportLab& lab) const;
    void renderLoop();
    void watchLoop();
    void renderStudent(const std::string& scene, const CameraOrbit& orbit, std::uint64_t generation,
                       std::int64_t save_ns);
    void renderReference(const std::string& scene, const CameraOrbit& orbit);
    void renderDebug(const std::string& scene, const CameraOrbit& orbit, DebugView view);
    void gradeLab(std::uint64_t generation);
    std::shared_ptr<Snapshot> buildSnapshot(std::shared_ptr<const IsolatedRender> student,
                                            const std::string& scene, const CameraOrbit& orbit);
    void judge(const std::shared_ptr<Snapshot>& snap);
    std::shared_ptr<const grader::Image> inputFile(int index);
    // The snapshot numbered `seq` among the newest pictures and debug views, or null.
    std::shared_ptr<const Snapshot> findSnapshot(std::uint64_t seq) const;
};

std::string pictureKindName(PictureKind kind);

}  // namespace shaderlab::serve
