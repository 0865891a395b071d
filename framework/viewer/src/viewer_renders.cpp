// The viewer's renders: what it asks of the render server (the student's shaders for the scene
// and camera on screen, and the reference solution's, or the stored goldens when there is no
// reference solution; and the whole lab graded as `check` grades it) and what it does with the
// answers. It draws nothing and judges nothing.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "grader/base/untrusted_text.h"
#include "grader/reports/report.h"
#include "shaderlab/grading/grading.h"
#include "shaderlab/live/diagnostic_view.h"
#include "shaderlab/live/render_outcome.h"
#include "viewer_window.h"

namespace fs = std::filesystem;

namespace shaderlab::viewer::detail {

namespace {

// The diagnostics of `severity` ("error", or anything else for warnings and notes) with the lines
// around each, for the window; `terminal` adds the command that opens each in the editor.
std::string messagesText(const std::vector<Diagnostic>& ds, bool errors, const std::string& folder,
                         bool terminal) {
    std::string text;
    for (const Diagnostic& d : ds) {
        if ((d.severity == "error") != errors) continue;
        const DiagnosticView v = viewDiagnostic(d, folder);
        text += formatWithContext(v) + "\n";
        const std::string open = editorCommand(v);
        if (terminal && !open.empty()) text += "   open it: " + open + "\n";
    }
    return text;
}

}  // namespace

const std::vector<PassImage>* Viewer::studentPasses() const {
    if (!student_ || student_->render.scenes.empty()) return nullptr;
    return &student_->render.scenes[0].passes;
}

// The reference for the picture on screen: the reference solution rendered for the same scene
// and camera, or (graded view only) the stored goldens.
const std::vector<PassImage>* Viewer::referencePasses() const {
    if (!student_) return nullptr;
    if (!opt_.reference_root.empty()) {
        if (!reference_ || reference_->status != IsolatedStatus::Ok || reference_->render.scenes.empty() ||
            reference_scene_ != student_scene_ || reference_orbit_ != student_orbit_)
            return nullptr;
        return &reference_->render.scenes[0].passes;
    }
    if (student_orbit_.any()) return nullptr;
    const auto it = goldens_.find(student_scene_);
    return it == goldens_.end() ? nullptr : it->second.get();
}

// What keeps referencePasses() alive while the worker judges with it.
std::shared_ptr<const void> Viewer::referenceOwner() const {
    if (!opt_.reference_root.empty()) return reference_;
    const auto it = goldens_.find(student_scene_);
    return it == goldens_.end() ? nullptr : it->second;
}

void Viewer::requestStudent(std::int64_t save_ns) {
    Job job;
    job.kind = kStudent;
    job.request.shader_dir = (fs::path(opt_.submission_root) / spec_.id).string();
    job.request.containment_root = opt_.submission_root;
    job.request.scene = sceneName();
    job.request.orbit = orbit_;
    job.request.timeout_s = opt_.timeout_s;
    job.generation = generation_;
    job.save_ns = save_ns;
    queue_->submit(std::move(job));
    requestReference();
    requestDebug();
}

void Viewer::requestReference() {
    if (opt_.reference_root.empty()) {
        const std::string scene = sceneName();
        if (!goldens_.count(scene) && !golden_errors_.count(scene)) {
            std::vector<PassImage> images;
            std::string error;
            if (loadGoldenScene(spec_, spec_.lab_dir, scene, &images, &error))
                goldens_[scene] = std::make_shared<const std::vector<PassImage>>(std::move(images));
            else
                golden_errors_[scene] = error;
        }
        return;
    }
    if (reference_ && reference_scene_ == sceneName() && reference_orbit_ == orbit_) return;
    Job job;
    job.kind = kReference;
    job.request.shader_dir = (fs::path(opt_.reference_root) / spec_.id).string();
    job.request.containment_root = opt_.reference_root;
    job.request.scene = sceneName();
    job.request.orbit = orbit_;
    job.request.timeout_s = std::max(opt_.timeout_s, 30.0);
    queue_->submit(std::move(job));
}

// The lab as `check` grades it, against the same reference the window compares with.
void Viewer::requestGrade() {
    Job job;
    job.kind = kGrade;
    job.grade.submission_root = opt_.submission_root;
    job.grade.labs_root = opt_.labs_root;
    job.grade.reference_root = opt_.reference_root;
    job.grade.limits = opt_.grade_limits;
    job.generation = generation_;
    grade_asked_ = generation_;
    queue_->submit(std::move(job));
}

// One line for the grade, and one for each failing scene that looks like a known mistake, in
// the words `check` uses, so that a script (or a test) reads the same verdict in both.
void Viewer::onGrade(Finished& f) {
    grade_done_ = f.job.generation;
    grade_error_ = f.grade_error;
    if (!grade_error_.empty()) {
        std::printf("view: %s\n", grade_error_.c_str());
        std::fflush(stdout);
        return;
    }
    grade_ = std::move(f.report.labs.front());
    buildGradeLines();
    const grader::ReportLab& lab = *grade_;
    std::string missed;
    for (const grader::ReportGoal& g : lab.goals)
        if (!g.met) missed += (missed.empty() ? "" : ", ") + g.id;
    std::printf("view: grade %.2f / %.2f; ", lab.score, lab.max_score);
    if (lab.goals.empty())
        std::printf("%s\n", lab.status.c_str());
    else if (missed.empty())
        std::printf("every goal met\n");
    else
        std::printf("goals not met: %s\n", missed.c_str());
    for (const grader::ReportScene& s : lab.scenes)
        if (s.status != "passed" && !s.hint.mistake.empty())
            std::printf("view: scene %s: This looks like a known mistake: %s\n", s.name.c_str(),
                        grader::printableText(s.hint.about).c_str());
    std::fflush(stdout);
}

void Viewer::onStudent(const Finished& f) {
    const IsolatedRender& r = f.result;
    got_first_result_ = true;
    const bool fresh_reload = f.job.save_ns != 0;
    if (r.status == IsolatedStatus::Ok && !r.render.scenes.empty()) {
        student_ = std::make_shared<const IsolatedRender>(r);
        student_scene_ = f.job.request.scene;
        student_orbit_ = f.job.request.orbit;
        error_title_.clear();
        error_text_.clear();
        last_printed_error_.clear();
        dirty_ = judge_dirty_ = true;
        char line[256];
        std::snprintf(line, sizeof line, "scene %s rendered in %.0f ms", student_scene_.c_str(), r.wall_ms);
        status_line_ = line;
        if (fresh_reload) {
            const double latency_ms = static_cast<double>(nowNs() - f.job.save_ns) / 1e6;
            std::printf("view: %s; on screen %.0f ms after the save\n", line, latency_ms);
        } else {
            std::printf("view: %s\n", line);
        }
        // Warnings and notes: in the window under the picture; in the terminal when they change.
        const std::string folder = (fs::path(opt_.submission_root) / spec_.id).string();
        std::size_t warnings = 0, notes = 0;
        for (const Diagnostic& d : r.render.diagnostics) {
            warnings += d.severity == "warning";
            notes += d.severity != "warning" && d.severity != "error";
        }
        warning_text_ = messagesText(r.render.diagnostics, false, folder, false);
        warning_title_ = std::to_string(warnings) + (warnings == 1 ? " warning" : " warnings") +
                         (notes ? " and " + std::to_string(notes) + (notes == 1 ? " note" : " notes") : "");
        const std::string printed = messagesText(r.render.diagnostics, false, folder, true);
        if (printed != warnings_printed_ && !printed.empty())
            std::printf("view: %s\n%s", warning_title_.c_str(), printed.c_str());
        warnings_printed_ = printed;
    } else {
        const RenderFailure failure = describeFailure(spec_, r);
        const std::string& title = failure.title;
        const std::string folder = (fs::path(opt_.submission_root) / spec_.id).string();
        // Each error with the lines around it; the terminal adds the command that opens it.
        std::string text = messagesText(r.render.diagnostics, true, folder, true);
        error_text_ = messagesText(r.render.diagnostics, true, folder, false);
        if (error_text_.empty()) text = error_text_ = failure.text;
        error_title_ = title + (student_ ? " - the last good picture is shown" : "");
        const std::string printed = title + "\n" + text;
        if (printed != last_printed_error_) {
            std::printf("view: %s\n%s", title.c_str(), text.c_str());
            last_printed_error_ = printed;
        }
        status_line_ = title;
    }
    if (fresh_reload) ++reloads_shown_;
    std::fflush(stdout);
}

void Viewer::takeResults() {
    for (Finished& f : queue_->take()) {
        if (f.job.kind == kStudent) {
            onStudent(f);
        } else if (f.job.kind == kGrade) {
            onGrade(f);
        } else if (f.job.kind == kDebug) {
            onDebug(f);
        } else {
            reference_error_.clear();
            if (f.result.status != IsolatedStatus::Ok)
                reference_error_ = "the reference solution did not render: " + f.result.message;
            reference_ = std::make_shared<const IsolatedRender>(std::move(f.result));
            reference_scene_ = f.job.request.scene;
            reference_orbit_ = f.job.request.orbit;
            dirty_ = judge_dirty_ = true;
        }
    }
}

std::string Viewer::changeScene(int delta) {
    const int n = static_cast<int>(spec_.scenes.size());
    scene_ = ((scene_ + delta) % n + n) % n;
    requestStudent(0);
    return sceneName();
}

}  // namespace shaderlab::viewer::detail
