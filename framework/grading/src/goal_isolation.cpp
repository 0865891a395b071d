// Goal isolation (lab.json goals[].work; docs/grading.md, "Goal isolation"): a goal whose checks
// fail on the student's whole shaders is judged again on renders of the reference solution with
// only the student's own work for that goal swapped in (glsl_compose.h), so that a goal whose own
// work is right keeps its points when another goal's mistake spoils its pictures (error carried
// forward). Only failing goals are rendered again, all of them by one child: a passing lab costs
// nothing more. Which images are judged, and against what, is the same as for the whole shaders.
#include <algorithm>
#include <filesystem>
#include <map>
#include <memory>
#include <set>

#include "grader/metrics/scoring.h"
#include "grading_detail.h"
#include "shaderlab/base/paths.h"
#include "shaderlab/base/timings.h"
#include "shaderlab/glsl/glsl_compose.h"

namespace fs = std::filesystem;

namespace shaderlab::grading_detail {

namespace {

constexpr std::size_t kMaxShaderBytes = 1u << 20;  // as the renderer reads them

// The files every isolated render needs: the reference's, the student's and the starter's text
// of each student file.
struct LabTexts {
    std::map<std::string, std::string> reference, student, starter;
    std::string problem;  // why no goal can be taken alone here; empty when they can
};

LabTexts readTexts(const LabSpec& spec, const std::string& submission_dir, const std::string& reference_dir) {
    LabTexts t;
    std::error_code ec;
    if (reference_dir.empty() || !fs::is_directory(reference_dir, ec)) {
        t.problem = "the reference solution is not here to take your work for it alone";
        return t;
    }
    for (const std::string& file : spec.student_files) {
        const FileText ref = readFile((fs::path(reference_dir) / file).string(), kMaxShaderBytes);
        if (!ref.ok) {
            t.problem = "the reference solution's " + file + " cannot be read (" + ref.error + ")";
            return t;
        }
        t.reference[file] = ref.text;
        // The student's own files, read as the render child reads them: inside the submission.
        const FileText mine =
            readFileInside(submission_dir, (fs::path(spec.id) / file).string(), kMaxShaderBytes);
        if (mine.ok) t.student[file] = mine.text;
        const FileText starter = readFileInside(spec.lab_dir, file, kMaxShaderBytes);
        if (starter.ok) t.starter[file] = starter.text;
    }
    return t;
}

// The functions other goals are judged on, per file: they stay the reference's where the student's
// code for this goal calls them.
std::map<std::string, std::vector<std::string>> othersWork(const LabSpec& spec, const GoalSpec& goal) {
    std::map<std::string, std::vector<std::string>> out;
    for (const GoalSpec& g : spec.goals) {
        if (&g == &goal) continue;
        for (const GoalWork& w : g.work)
            if (!w.function.empty()) out[w.file].push_back(w.function);
    }
    return out;
}

// The student files of `goal`'s render: the reference's, with the goal's work taken from the
// student. False, with the reason in `note`, when the work cannot be taken alone.
bool composeGoal(const LabSpec& spec, const GoalSpec& goal, const LabTexts& texts,
                 std::map<std::string, std::string>* files, std::vector<std::string>* with,
                 std::string* note) {
    *files = texts.reference;
    std::map<std::string, std::vector<std::string>> take;  // file -> functions; empty: whole file
    std::set<std::string> whole;
    for (const GoalWork& w : goal.work) {
        if (w.function.empty())
            whole.insert(w.file);
        else
            take[w.file].push_back(w.function);
    }
    const std::map<std::string, std::vector<std::string>> others = othersWork(spec, goal);
    for (const std::string& file : spec.student_files) {
        if (!whole.count(file) && !take.count(file)) continue;
        const auto mine = texts.student.find(file);
        if (mine == texts.student.end()) {
            *note = "your " + file + " cannot be read";
            return false;
        }
        if (whole.count(file)) {
            (*files)[file] = mine->second;
            continue;
        }
        glsl::ComposeInput in;
        in.file = file;
        in.reference = texts.reference.at(file);
        in.student = mine->second;
        const auto starter = texts.starter.find(file);
        if (starter != texts.starter.end()) in.starter = starter->second;
        in.take = take[file];
        const auto kept = others.find(file);
        if (kept != others.end())
            for (const std::string& f : kept->second)
                if (std::find(in.take.begin(), in.take.end(), f) == in.take.end()) in.keep.push_back(f);
        const glsl::Composed c = glsl::composeFunctions(in);
        if (!c.ok) {
            *note = c.note;
            return false;
        }
        (*files)[file] = c.text;
        for (const std::string& f : c.callers) with->push_back(file + ": " + f);
    }
    return true;
}

// One render of the reference with some student work swapped in, for the goals it serves.
struct IsolationJob {
    std::map<std::string, std::string> files;
    std::vector<std::size_t> goals;  // indices into spec.goals
    std::vector<std::string> scenes;
};

// The failing checks of `goal` in an isolated render; the render holds at least its scenes.
std::vector<std::string> judgeGoal(const LabSpec& spec, const GoalSpec& goal, const LabRender& render,
                                   const ReferenceImages& ref) {
    const std::vector<GradedImage> graded = gradedImages(spec);
    std::vector<std::string> failing;
    for (const std::string& scene : goal.scenes) {
        const auto mine = std::find_if(render.scenes.begin(), render.scenes.end(),
                                       [&](const SceneRender& s) { return s.scene == scene; });
        const auto theirs = ref.scenes.find(scene);
        if (mine == render.scenes.end() || theirs == ref.scenes.end() || !mine->error.empty()) continue;
        for (const std::string& pass : goal.passes) {
            bool passed = true;
            for (std::size_t i = 0; i < graded.size() && i < mine->passes.size() && i < theirs->second.size();
                 ++i) {
                if (graded[i].pass->name != pass) continue;
                const grader::ImageVerdict v = grader::judgeImage(
                    theirs->second[i].color, theirs->second[i].coverage, mine->passes[i].color,
                    mine->passes[i].coverage, imageThresholds(spec, scene, *graded[i].pass),
                    graded[i].hdr ? grader::ImageRange::Hdr : grader::ImageRange::Display);
                passed = passed && v.passed;
            }
            if (!passed) failing.push_back(scene + "/" + pass);
        }
    }
    return failing;
}

void judgedAlone(grader::ReportGoal* g, std::vector<std::string> failing) {
    g->judged = "alone";
    g->whole_failing = std::move(g->failing);
    g->failing = std::move(failing);
    g->met = g->failing.empty();
}

std::vector<IsolatedRender> renderJobs(const LabSpec& spec, const std::string& reference_dir,
                                       const std::vector<IsolationJob>& jobs, const GradeOptions& options) {
    std::vector<IsolatedLabJob> lab_jobs;
    for (const IsolationJob& job : jobs) {
        IsolatedLabJob j;
        j.spec = &spec;
        j.shader_dir = reference_dir;
        j.options.containment_root = reference_dir;
        j.options.only_scenes = job.scenes;
        j.options.source_overrides = job.files;
        lab_jobs.push_back(std::move(j));
    }
    ScopedTiming timing("render_child", spec.id, "goals");
    std::vector<IsolatedRender> out;
    if (lab_jobs.size() == 1) {
        out.push_back(
            renderLabIsolated(spec, reference_dir, options.backend, options.limits, lab_jobs[0].options));
        return out;
    }
    IsolatedRenderQueue queue(std::move(lab_jobs), options.backend, options.limits);
    queue.start();
    for (std::size_t i = 0; i < jobs.size(); ++i) out.push_back(queue.next());
    return out;
}

}  // namespace

std::string isolationRoot(const GradeOptions& options) {
    if (!options.isolation_root.empty()) return options.isolation_root;
    if (!options.reference_root.empty()) return options.reference_root;
    const fs::path beside = fs::path(options.labs_root).parent_path() / "reference_solutions";
    std::error_code ec;
    return fs::is_directory(beside, ec) ? beside.string() : std::string();
}

void isolateGoals(const LabSpec& spec, const std::string& submission_dir, const ReferenceImages& ref,
                  const GradeOptions& options, std::vector<grader::ReportGoal>* goals) {
    std::vector<std::size_t> failing;
    for (std::size_t i = 0; i < goals->size(); ++i) {
        (*goals)[i].judged = "whole";
        if (!spec.goals[i].work.empty() && !(*goals)[i].met) failing.push_back(i);
    }
    if (failing.empty()) return;
    const std::string root = isolationRoot(options);
    const std::string reference_dir = root.empty() ? std::string() : (fs::path(root) / spec.id).string();
    const LabTexts texts = readTexts(spec, submission_dir, reference_dir);
    std::vector<IsolationJob> jobs;
    for (const std::size_t i : failing) {
        grader::ReportGoal& g = (*goals)[i];
        if (!texts.problem.empty()) {
            g.judged_note = texts.problem;
            continue;
        }
        std::map<std::string, std::string> files;
        std::vector<std::string> with;
        if (!composeGoal(spec, spec.goals[i], texts, &files, &with, &g.judged_note)) continue;
        g.judged_with = std::move(with);
        if (files == texts.reference) {
            // The student's work for this goal is the reference's, token for token where it
            // differs at all: it is right, and something else spoils the goal's pictures.
            judgedAlone(&g, {});
            continue;
        }
        if (files == texts.student) {
            // The student's files differ from the reference only in this goal's work: the
            // composition is their own shaders, already judged.
            judgedAlone(&g, g.failing);
            continue;
        }
        auto same =
            std::find_if(jobs.begin(), jobs.end(), [&](const IsolationJob& j) { return j.files == files; });
        if (same == jobs.end()) {
            jobs.push_back({std::move(files), {}, {}});
            same = jobs.end() - 1;
        }
        same->goals.push_back(i);
        for (const std::string& s : spec.goals[i].scenes)
            if (std::find(same->scenes.begin(), same->scenes.end(), s) == same->scenes.end())
                same->scenes.push_back(s);
    }
    if (jobs.empty()) return;
    const std::vector<IsolatedRender> renders = renderJobs(spec, reference_dir, jobs, options);
    ScopedTiming timing("metrics", spec.id, "goals");
    for (std::size_t j = 0; j < jobs.size(); ++j) {
        for (const std::size_t i : jobs[j].goals) {
            grader::ReportGoal& g = (*goals)[i];
            if (renders[j].status != IsolatedStatus::Ok) {
                g.judged_with.clear();
                g.judged_note = std::string("your work for it did not render alone (") +
                                isolatedStatusName(renders[j].status) + "): " + renders[j].message;
                continue;
            }
            judgedAlone(&g, judgeGoal(spec, spec.goals[i], renders[j].render, ref));
        }
    }
}

}  // namespace shaderlab::grading_detail
