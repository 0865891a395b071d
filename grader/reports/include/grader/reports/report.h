// The grading report as data, and its writers: report.json (docs/report-format.md), Gradescope's
// results.json, JUnit XML and a self-contained report.html. Writers only format; they do not
// grade. Image paths in the report are relative to the report's folder.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "grader/metrics/mask.h"

namespace grader {

constexpr int kReportSchemaVersion = 2;

// The closed set of lab and scene statuses.
//   passed, failed: rendered and judged; compile_error, link_error: the shaders did not build;
//   timeout, crashed: the render process was stopped or died; missing: a student file is absent;
//   not_attempted: the student files are the lab's starter code, unchanged (nothing drawn, 0 points).
// render_error (a GL error or a broken scene file) is reported as "crashed" with its message.
// A compile, link or framework message (docs/report-format.md): `message` in plain words, an
// `explanation` for the common mistakes, the student's `source_line` with `column` (1-based, 0:
// no caret) where known, the driver's own words in `driver_message`, and how many later errors
// were dropped as consequences of this one in `follow_on`.
struct ReportDiagnostic {
    std::string file;
    int line = 0;
    int column = 0;
    std::string severity;
    std::string message;
    std::string explanation{};
    std::string source_line{};
    std::string driver_message{};
    int follow_on = 0;
};

struct ReportMetrics {
    double psnr_db = 0.0;      // +infinity allowed; written as null with "identical": true
    bool ssim_defined = true;  // false: the image is smaller than SSIM's window; written as null
    double ssim = 0.0;
    double flip_mean = 0.0;
    double flip_weighted_median = 0.0;
    double mismatch_fraction = 0.0;
    std::size_t nan_count = 0;
    std::size_t inf_count = 0;
    std::size_t pixel_count = 0;
};

// The thresholds an image was judged with (the lab's, the pass's, then the scene's). `known` is
// false in a report written before they were recorded.
struct ReportThresholds {
    bool known = false;
    double psnr_min_db = 0.0;
    double ssim_min = 0.0;
    double flip_mean_max = 0.0;
    double mismatch_max = 0.0;
    double pixel_tolerance = 0.0;  // what a mismatching pixel is off by, at least (every channel)
};

// One graded image of a scene: a pass's attachment (most passes have one, named by the pass).
struct ReportPass {
    std::string name;        // "shade", or "gbuffer.normal" for one attachment of several
    std::string pass;        // the pass
    std::string attachment;  // its attachment ("color", "depth", ...)
    std::string range;       // "display" or "hdr" (how values were compared; docs/grading.md)
    double hdr_scale = 1.0;  // hdr: what both images were divided by
    bool passed = false;
    ReportMetrics metrics;
    std::vector<std::string> reasons;
    std::string student_image, reference_image, diff_image;
    // Optional (empty or 0 when a report predates them):
    ReportThresholds thresholds;
    int width = 0, height = 0;  // of the image, in pixels
    PixelBox worst_region;      // the worst 16x16 window of the shift-tolerant comparison
    PixelBox non_finite_box;    // around the NaN and Inf pixels
    PixelBox zoom_region;       // what zoom_image enlarges (a failing image only)
    std::string signed_image;   // too bright / too dark
    std::string zoom_image;     // zoom_region of student, reference and FLIP map, side by side
    // Pass isolation: the same pass run on the reference's inputs (lab.json `isolate`), judged
    // when its scene failed; the pass's goals use this verdict. `isolated` false: not judged so.
    bool isolated = false;
    bool isolated_passed = false;
    std::vector<std::string> isolated_reasons;
    ReportMetrics isolated_metrics;
};

// A failing scene whose picture is close to a known mistake's (tests/corpus/<lab>, stored as
// labs/<lab>/hints by `shaderlab goldens`); empty `mistake` when none is.
struct ReportHint {
    std::string mistake;   // the corpus case
    std::string about;     // what the mistake is, in one sentence
    std::string image;     // the graded image compared (a ReportPass name)
    double psnr_db = 0.0;  // of the student's picture against the mistake's (+infinity: identical)
};

struct ReportScene {
    std::string name;
    std::string status;  // passed | failed
    double score = 0.0, max_score = 0.0;
    std::string message;             // the reasons, joined
    std::string first_failing_pass;  // empty when every graded pass passed
    ReportMetrics metrics;           // of the final image, over covered pixels
    ReportMetrics frame_metrics;     // of the final image, whole frame
    PixelBox worst_region;
    PixelBox non_finite_box;
    std::string student_image, reference_image, diff_image;
    std::string signed_image, zoom_image;  // of the final image; optional
    std::vector<ReportPass> passes;        // every graded image, in order (the last is the final image)
    ReportHint hint;
    double render_ms = 0.0;
};

// A learning goal of the lab: met when every graded image of its scenes and passes passed.
struct ReportGoal {
    std::string id, title;
    double points = 0.0;  // what meeting it earns
    bool met = false;
    std::vector<std::string> scenes;   // where it is seen (optional: older reports lack it)
    std::vector<std::string> failing;  // "<scene>/<pass>" checks that failed, in order
    // The goals it rests on (lab.json "depends_on") that are not met: then it is not met because
    // of them, whatever its own checks say, and the report says so instead of a verdict of its own.
    std::vector<std::string> not_met_because;
    // How the verdict was reached (docs/grading.md, "Goal isolation"); empty in older reports:
    //   "alone": the student's whole shaders failed it, so it was judged on renders in which only
    //            the student's own work for it (its functions, files or passes) is theirs, the
    //            rest the reference's (error carried forward);
    //   "whole": judged on the student's whole shaders: they passed it, or its work could not be
    //            taken alone (judged_note says why);
    //   "combination": a goal about the parts put together, always judged on the whole shaders.
    std::string judged;
    std::string judged_note;  // why a goal with work of its own was not judged alone; else empty
    // Judged alone: the checks that failed on the whole shaders ("<scene>/<pass>"), which may
    // differ from `failing` (the isolated renders') because of another goal's mistake.
    std::vector<std::string> whole_failing;
    // Judged alone: code no goal asks for that the student changed and that feeds this goal's
    // work ("grayscale.frag: main", a function the starter gives), judged with it.
    std::vector<std::string> judged_with;
};

struct ReportLab {
    std::string id, title;
    std::string folder;              // the submission's folder of this lab, absolute
    std::vector<std::string> files;  // the student files graded there, relative to `folder`
    std::string status;              // one of the closed set above
    double score = 0.0, max_score = 0.0;
    std::string message;
    // Which limit stopped the render (timeout or crashed): "compile_timeout", "draw_timeout" or
    // "memory", or "loop" (a loop ran past the loop guard); empty otherwise.
    std::string limit;
    std::string reference_source;  // "reference_solutions" or "goldens"
    std::vector<ReportDiagnostic> diagnostics;
    std::vector<ReportGoal> goals;  // empty when the lab did not render
    std::vector<ReportScene> scenes;
    double wall_ms = 0.0;
};

struct Report {
    std::string tool_version;
    std::string submission;
    std::string backend;
    std::string renderer;  // the GL renderer string, when known
    std::vector<ReportLab> labs;
    double score = 0.0, max_score = 0.0;
};

// A diagnostic as a person reads it, lines joined by '\n' (no trailing newline):
//   phong.frag:25: error: missing `;` at the end of this line
//      25 |     vec3 v = normalize(u_camera_position - v_world_position)
//         |                                                             ^
//         = Every statement ends with `;`. ...
// `prefix` goes before the file name (e.g. "01-phong/"), `indent` before every line.
// Text made safe for HTML and XML, in content and in quoted attributes: & < > " ' escaped, and
// invalid UTF-8 and the control characters XML 1.0 forbids replaced by '?' (a hostile name or
// diagnostic cannot break the page). Every page the project writes escapes with it.
std::string escapeMarkup(const std::string& s);

// The titles of the goals of `lab` that `ids` names, quoted and joined: "'Ramp' and 'Edges'".
std::string goalsNamed(const ReportLab& lab, const std::vector<std::string>& ids);

// How a goal was judged, in one sentence for the student (goal isolation, docs/grading.md), or ""
// when there is nothing to say (met on the whole shaders, or a report without the fields):
// "Judged on your own work for it: ...", "Your own work for it is right ...", "Judged on your
// whole shaders: <why>." Every report writer, `check` and the workbench say the same.
std::string goalJudgement(const ReportGoal& goal);
// A goal's judged_with in words ("with your changes to grayscale.frag: main, code the starter gave
// that uses it"); empty when it has none.
std::string judgedWithText(const ReportGoal& goal);

std::string formatDiagnostic(const ReportDiagnostic& d, const std::string& prefix = "",
                             const std::string& indent = "");
// Where the writers that show pictures find them. With `image_root` (the folder the report's
// image paths are relative to) the images are embedded as data: URIs, as long as all of them
// together stay within `max_embedded_bytes` (base64 counted); otherwise they are linked by their
// relative paths. A missing file is linked too.
struct ImageEmbedding {
    std::string image_root;
    std::size_t max_embedded_bytes = 20u << 20;
};

// Each returns the text; the caller writes files.
std::string reportToJson(const Report& report);
bool reportFromJson(const std::string& text, Report* out, std::string* error);
// One test per learning goal, with its failing images when `images` allows (html output).
std::string reportToGradescope(const Report& report, const ImageEmbedding& images = {"", 2u << 20});
std::string reportToJunit(const Report& report);
// A page a student reads on a laptop or a phone: summary, goals and points, every scene.
std::string reportToHtml(const Report& report, const ImageEmbedding& images = {});

}  // namespace grader
