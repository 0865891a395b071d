// What the window shows and what it says of it: the image on screen picked from the selection
// (a pass's output or a texture a pass reads) and uploaded, and the judgements of that image and
// of the scene, made on the worker and taken back in the main loop. It draws nothing itself.
#include <cstdio>
#include <filesystem>
#include <mutex>

#include "shaderlab/gl/gl.h"
// glad above provides the GL declarations; GLFW must not include its own.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "grader/metrics/heatmap.h"
#include "shaderlab/grading/grading.h"
#include "viewer_window.h"

namespace fs = std::filesystem;

namespace shaderlab::viewer::detail {

namespace {

const PassImage* findImage(const std::vector<PassImage>* list, const std::string& key) {
    if (!list) return nullptr;
    for (const PassImage& p : *list)
        if (imageKey(p) == key) return &p;
    return nullptr;
}

}  // namespace

// Picks the image on screen from the selection and works out its texture, verdict and diff.
void Viewer::refreshShown() {
    dirty_ = false;
    shown_ = Shown();
    shown_verdict_.reset();
    ++shown_seq_;  // whatever the worker is judging is for another picture now
    shown_pending_ = false;
    const std::vector<PassImage>* mine = studentPasses();
    const std::vector<PassImage>* theirs = referencePasses();
    if (!mine || mine->empty()) {
        shown_.note = "no picture yet";
        return;
    }
    // The selected pass output, else the final graded image.
    std::size_t index = mine->size() - 1;
    for (std::size_t i = 0; i < mine->size(); ++i)
        if ((*mine)[i].graded) index = i;
    for (std::size_t i = 0; i < mine->size(); ++i)
        if (!selected_.empty() && imageKey((*mine)[i]) == selected_) index = i;
    const PassImage& out = (*mine)[index];
    const PassSpec* pass = spec_.findPass(out.pass);
    if (input_ < 0 || !pass || input_ >= static_cast<int>(pass->inputs.size())) {
        input_ = -1;
        shown_.label = "pass " + out.pass + " -> " + out.target + "." + out.attachment;
        shown_.student_pass = &out;
        shown_.reference_pass = findImage(theirs, imageKey(out));
        shown_.pass = pass;
    } else {
        showInput(out, *pass, mine, theirs, index);
    }
    if (shown_.student_pass) shown_.student = &shown_.student_pass->color;
    if (shown_.reference_pass) shown_.reference = &shown_.reference_pass->color;
    if (shown_.student) tex_student_.upload(*shown_.student);
    if (shown_.reference) tex_reference_.upload(*shown_.reference);
    if (shown_.student && shown_.reference && shown_.student->width == shown_.reference->width &&
        shown_.student->height == shown_.reference->height && shown_.student != shown_.reference) {
        judgeShown();
    }
}

// The texture input `input_` of `pass` (which drew `out`, image `index` of `mine`): what the
// pass read, when the window can show it.
void Viewer::showInput(const PassImage& out, const PassSpec& pass, const std::vector<PassImage>* mine,
                       const std::vector<PassImage>* theirs, std::size_t index) {
    const PassInput& in = pass.inputs[static_cast<std::size_t>(input_)];
    shown_.label = "pass " + out.pass + " reads " + in.sampler;
    if (in.source == InputSource::Target) {
        // What the pass read: the latest image of that target drawn before it, or (a
        // repeated pass reading its own group's output) the latest of all.
        auto latest = [&](const std::vector<PassImage>* list, std::size_t before) -> const PassImage* {
            if (!list) return nullptr;
            const PassImage* found = nullptr;
            for (std::size_t i = 0; i < list->size(); ++i) {
                const PassImage& p = (*list)[i];
                const bool same =
                    p.target == in.target && (in.attachment.empty() || p.attachment == in.attachment);
                if (same && (i < before || !found)) found = &p;
            }
            return found;
        };
        shown_.student_pass = latest(mine, index);
        const PassImage* mine_input = shown_.student_pass;
        shown_.reference_pass = mine_input ? findImage(theirs, imageKey(*mine_input)) : nullptr;
        shown_.label += " <- target " + in.target + (in.attachment.empty() ? "" : "." + in.attachment);
        if (!mine_input) shown_.note = "the render did not read back target " + in.target;
    } else if (in.source == InputSource::File) {
        const std::string path = labFilePath(spec_, in.file);
        auto it = files_.find(path);
        if (it == files_.end()) {
            grader::Image img;
            std::string err;
            const bool hdr = fs::path(path).extension() == ".hdr";
            if (!(hdr ? grader::readHdr(path, &img, &err) : grader::readPng(path, &img, &err)))
                img = grader::Image();
            it = files_.emplace(path, std::move(img)).first;
        }
        shown_.label += " <- file " + in.file;
        if (it->second.empty())
            shown_.note = "cannot show " + in.file;
        else
            shown_.student = shown_.reference = &it->second;
    } else {
        shown_.label +=
            in.source == InputSource::Cube ? " <- cube map" : " <- generated " + in.generated.pattern;
        shown_.note = "a texture the framework makes or a cube map: nothing to show here";
    }
}

// Judges the image on screen against its reference on the worker, with the heat map of the diff.
void Viewer::judgeShown() {
    const PassSpec* judge_pass = shown_.student_pass ? spec_.findPass(shown_.student_pass->pass) : nullptr;
    const grader::Thresholds t =
        judge_pass ? imageThresholds(spec_, student_scene_, *judge_pass) : grader::Thresholds();
    const grader::ImageRange range = judge_pass && judge_pass->compare == CompareMode::Hdr
                                         ? grader::ImageRange::Hdr
                                         : grader::ImageRange::Display;
    // The shared pointers keep the images alive for the worker (input files live in files_,
    // which only grows).
    const std::uint64_t seq = shown_seq_;
    shown_pending_ = true;
    worker_->submit(0, [this, seq, t, range, mine = student_, theirs = referenceOwner(), shown = shown_]() {
        static const std::vector<std::uint8_t> none;
        ShownAnalysis a;
        a.seq = seq;
        a.verdict = grader::judgeImage(
            *shown.reference, shown.reference_pass ? shown.reference_pass->coverage : none, *shown.student,
            shown.student_pass ? shown.student_pass->coverage : none, t, range);
        grader::HeatmapConfig hc;
        hc.outline = a.verdict.mismatches.empty() ? nullptr : &a.verdict.mismatches;
        a.heat = grader::diffHeatmap(a.verdict.flip_map, shown.student->width, shown.student->height, hc);
        std::lock_guard<std::mutex> lock(analysis_m_);
        shown_ready_ = std::move(a);
        glfwPostEmptyEvent();
    });
}

// The verdict grading would give this scene: every graded image against its reference.
void Viewer::judgeScene() {
    judged_.clear();
    judged_graded_view_ = !student_orbit_.any();
    const std::uint64_t seq = ++scene_seq_;
    scene_pending_ = false;
    const std::vector<PassImage>* mine = studentPasses();
    const std::vector<PassImage>* theirs = referencePasses();
    if (!mine || !theirs) return;
    scene_pending_ = true;
    worker_->submit(1, [this, seq, mine, theirs, keep_mine = student_, keep_theirs = referenceOwner(),
                        scene = student_scene_]() {
        SceneAnalysis a;
        a.seq = seq;
        for (const PassImage& p : *mine) {
            if (!p.graded) continue;
            const PassSpec* pass = spec_.findPass(p.pass);
            const PassImage* ref = nullptr;
            for (const PassImage& q : *theirs)
                if (imageKey(q) == imageKey(p)) ref = &q;
            if (!pass || !ref || ref->color.width != p.color.width || ref->color.height != p.color.height)
                continue;
            Judged j;
            j.label = imageKey(p);
            j.verdict = grader::judgeImage(
                ref->color, ref->coverage, p.color, p.coverage, imageThresholds(spec_, scene, *pass),
                pass->compare == CompareMode::Hdr ? grader::ImageRange::Hdr : grader::ImageRange::Display);
            a.judged.push_back(std::move(j));
        }
        std::lock_guard<std::mutex> lock(analysis_m_);
        scene_ready_ = std::move(a);
        glfwPostEmptyEvent();
    });
}

// Takes what the worker judged, when it is about the pictures on screen now.
void Viewer::takeAnalyses() {
    std::optional<ShownAnalysis> shown;
    std::optional<SceneAnalysis> scene;
    {
        std::lock_guard<std::mutex> lock(analysis_m_);
        shown.swap(shown_ready_);
        scene.swap(scene_ready_);
    }
    if (shown && shown->seq == shown_seq_) {
        shown_pending_ = false;
        tex_diff_.upload(shown->heat);
        shown_verdict_ = std::move(shown->verdict);
    }
    if (scene && scene->seq == scene_seq_) {
        scene_pending_ = false;
        judged_ = std::move(scene->judged);
        if (judged_.empty() || !judged_graded_view_) return;
        bool passed = true;
        for (const Judged& j : judged_) passed = passed && j.verdict.passed;
        std::printf("view: scene %s %s\n", student_scene_.c_str(), passed ? "passes" : "FAILS");
        for (const Judged& j : judged_)
            for (const std::string& reason : j.verdict.reasons)
                std::printf("      %s: %s\n", j.label.c_str(), reason.c_str());
        std::fflush(stdout);
    }
}

}  // namespace shaderlab::viewer::detail
