// Grades a submission: for each lab, renders the student's shaders in a child process, gets the
// reference images (by rendering the reference solution when it is present, else from the
// lab's stored goldens), judges every graded pass with the lab's thresholds and writes the
// images a person needs to see why (student, reference, signed difference, FLIP heat map, a
// close-up of the worst region) and looks for a known mistake behind each failing scene. Returns
// the report as data; writing report files is the caller's (see grader/report.h).
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "grader/metrics/scoring.h"
#include "grader/reports/report.h"
#include "shaderlab/gl/gl_context.h"
#include "shaderlab/render/isolated_render.h"

namespace shaderlab {

struct GradeOptions {
    Backend backend = Backend::OSMesa;
    std::string labs_root;       // where lab.json files live
    std::string reference_root;  // folder mirroring labs/ with reference shaders; empty or absent: goldens
    // Where goal isolation (docs/grading.md, "Goal isolation") reads the reference's student files
    // to compose with the student's work; empty: reference_root, or else the reference_solutions/
    // folder beside labs_root when there is one. Only sources are read there: the images the
    // isolated renders are compared with are the reference images of the grade.
    std::string isolation_root;
    std::vector<std::string> labs;  // empty: every lab under labs_root
    std::string out_dir;            // images go to out_dir/<lab>/<scene>/; empty: no pictures written
    IsolationLimits limits;
    // Told, as the student's render goes, what it is doing (RenderOptions::progress events,
    // with the lab id). May be empty.
    std::function<void(const std::string& lab, const std::string& event)> progress;
    // Where <lab>/golden/ and <lab>/hints/ are read from; empty: each lab's own folder.
    std::string goldens_root;
    // A lab's own root for them, over goldens_root (a batch worker grading several labs, each
    // against its reference-cache entry).
    std::map<std::string, std::string> lab_goldens_roots;
    bool hints = true;  // look for a known mistake (mistake_hints.h) behind every failing scene
    // Reference renders kept between runs (shaderlab/batch/reference_cache.h). Asked, for a lab
    // whose reference solution is present, once the student's render says which renderer drew it:
    // the root of <lab>/golden/ and <lab>/hints/ holding that reference's images, which are then
    // read instead of rendering the reference again; empty: render it. May be empty.
    std::function<std::string(const LabSpec& spec, const std::string& renderer)> reference_cache;
    // The root reference_cache would give if the renderer is the one the cache saw last, when that
    // entry is there; empty otherwise. It never renders, and is asked while the student's render
    // runs, so that the reference's images are read meanwhile; they are used only when
    // reference_cache then gives the same root. May be empty.
    std::function<std::string(const LabSpec& spec)> reference_cache_guess;
};

// Called after each lab is graded with the report so far (its last lab is the new one), so the
// caller can print progress and rewrite report files; may be empty.
using LabCallback = std::function<void(const grader::Report&)>;

grader::Report gradeSubmission(const std::string& submission_dir, const GradeOptions& options,
                               const LabCallback& on_lab = {});

// A diagnostic as the report carries it.
grader::ReportDiagnostic toReportDiagnostic(const Diagnostic& d);

// Where a lab's golden image lives: <lab_dir>/golden/<scene>.png for the final image,
// <scene>.<image>.png for another graded image (<image> is the pass, or pass.attachment when
// its target has several), ".hdr" instead of ".png" for images compared in the hdr range, and
// ".coverage.png" for the coverage mask.
std::string goldenPath(const std::string& lab_dir, const std::string& scene, const std::string& image,
                       bool final_image, bool coverage, bool hdr = false);

// The thresholds one graded image of `scene` is judged with: the lab's, then the pass's, then the
// scene's.
grader::Thresholds imageThresholds(const LabSpec& spec, const std::string& scene, const PassSpec& pass);

// The reference images of one scene read from the stored goldens under `stored_dir` (a lab
// folder holding golden/): one PassImage per graded image, in the order the renderer reads them.
// False, with the reason, when one is missing or unreadable.
bool loadGoldenScene(const LabSpec& spec, const std::string& stored_dir, const std::string& scene,
                     std::vector<PassImage>* out, std::string* error);

// Renders the reference solution of each lab and writes its goldens. Returns error messages.
std::vector<std::string> writeGoldens(const std::string& reference_root, const std::string& labs_root,
                                      const std::vector<std::string>& labs, Backend backend,
                                      const std::string& golden_root_override = "");

}  // namespace shaderlab
