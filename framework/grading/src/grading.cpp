// Grading a submission lab by lab; see grading.h and docs/grading.md. The reference images come
// from reference_images.cpp and the report's pictures are written by report_pictures.cpp; here
// are the steps of one lab's grade, from the student's render to the lab's score.
#include "shaderlab/grading/grading.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <filesystem>
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <system_error>
#include <thread>

#include "grader/base/atomic_file.h"
#include "grader/metrics/scoring.h"
#include "grading_detail.h"
#include "not_attempted.h"
#include "shaderlab/base/timings.h"
#include "shaderlab/grading/mistake_hints.h"
#include "shaderlab/lab/lab_catalog.h"
#include "shaderlab/lab/lab_spec.h"

namespace fs = std::filesystem;

namespace shaderlab {

namespace grading_detail {

IsolatedRender renderFrom(const LabSpec& spec, const std::string& root, Backend backend,
                          const IsolationLimits& limits,
                          const std::function<void(const std::string&)>& progress,
                          const std::function<void()>& while_rendering) {
    RenderOptions options;
    options.containment_root = root;
    options.progress = progress;
    return renderLabIsolated(spec, (fs::path(root) / spec.id).string(), backend, limits, options,
                             while_rendering);
}

std::vector<GradedImage> gradedImages(const LabSpec& spec) {
    std::vector<GradedImage> out;
    for (const PassSpec& p : spec.passes) {
        const TargetSpec* t = spec.findTarget(p.target);
        for (const std::string& a : p.graded) {
            GradedImage g;
            g.pass = &p;
            g.attachment = a;
            g.id = (t && t->attachments.size() == 1 && a != "depth") ? p.name : p.name + "." + a;
            g.hdr = p.compare == CompareMode::Hdr;
            out.push_back(std::move(g));
        }
    }
    return out;
}

}  // namespace grading_detail

namespace {

using grading_detail::GradedImage;
using grading_detail::gradedImages;
using grading_detail::ReferenceImages;

// The report's closed set of lab statuses for a render that did not succeed: the isolated
// render's names, except that a GL error or broken scene (render_error) counts as crashed.
std::string labStatusOf(IsolatedStatus s) {
    return s == IsolatedStatus::RenderError ? "crashed" : isolatedStatusName(s);
}

struct FailingImage {
    std::size_t image;  // index into gradedImages()
    std::vector<std::string> reasons;
};

std::size_t passIndex(const LabSpec& spec, const std::string& name) {
    for (std::size_t i = 0; i < spec.passes.size(); ++i)
        if (spec.passes[i].name == name) return i;
    return 0;
}

// For each pass, the passes whose results reach it: those that drew a target it reads (earlier,
// or anywhere in its repeat group) or drew its own target before it, and theirs in turn.
std::vector<std::set<std::size_t>> passAncestors(const LabSpec& spec) {
    const std::size_t n = spec.passes.size();
    std::vector<std::set<std::size_t>> direct(n), all(n);
    for (std::size_t i = 0; i < n; ++i) {
        const PassSpec& p = spec.passes[i];
        for (std::size_t j = 0; j < n; ++j) {
            if (j == i) continue;
            const PassSpec& q = spec.passes[j];
            const bool same_loop = p.loop >= 0 && p.loop == q.loop;
            const bool reads = std::any_of(p.inputs.begin(), p.inputs.end(), [&](const PassInput& in) {
                return in.source == InputSource::Target && in.target == q.target;
            });
            if ((reads && (j < i || same_loop)) || (q.target == p.target && j < i)) direct[i].insert(j);
        }
    }
    for (std::size_t i = 0; i < n; ++i) {
        std::vector<std::size_t> stack(direct[i].begin(), direct[i].end());
        while (!stack.empty()) {
            const std::size_t j = stack.back();
            stack.pop_back();
            if (!all[i].insert(j).second) continue;
            stack.insert(stack.end(), direct[j].begin(), direct[j].end());
        }
    }
    return all;
}

std::string joinReasons(const std::vector<std::string>& reasons) {
    std::string out;
    for (const std::string& r : reasons) out += (out.empty() ? "" : "; ") + r;
    return out;
}

grader::ReportMetrics reportMetrics(const grader::MetricSet& m, const grader::ImageVerdict& v) {
    grader::ReportMetrics out;
    out.psnr_db = m.psnr_db;
    out.ssim_defined = m.ssim_defined;
    out.ssim = m.ssim;
    out.flip_mean = m.flip_mean;
    out.flip_weighted_median = m.flip_weighted_median;
    out.mismatch_fraction = m.mismatch_fraction;
    out.pixel_count = m.pixel_count;
    out.nan_count = v.nan_count;
    out.inf_count = v.inf_count;
    return out;
}

// What the steps of one lab's grade share once the student's render and the reference are in:
// the lab, where its stored files are, and what the scenes leave for the lab's message, its
// goals and its known-mistake hints.
struct LabGrading {
    LabGrading(const LabSpec& lab_spec, const std::string& lab_id, const GradeOptions& grade_options,
               const std::string& lab_stored_dir)
        : spec(lab_spec), id(lab_id), options(grade_options), stored_dir(lab_stored_dir) {}

    const LabSpec& spec;
    const std::string& id;
    const GradeOptions& options;
    const std::string& stored_dir;
    std::vector<GradedImage> graded;
    std::vector<std::set<std::size_t>> ancestors;
    std::vector<std::string> write_errors;
    LabHints hints;
    std::string hints_error;  // the lab's fault: said in the lab's message, and grading goes on
    // Read at the first failing image: a lab that passes never needs its known-mistake pictures.
    bool hints_read = false;
    // (scene, pass) -> every graded image of that pass passed
    std::map<std::pair<std::string, std::string>, bool> checks;
    // scene -> its first wrong image, for the known-mistake hints once every scene is judged
    std::map<std::string, FailingPicture> failing_pictures;
    // scene -> its failing images, for pass isolation once every scene is judged
    std::map<std::string, std::vector<FailingImage>> failing_images;
    // (scene, pass) -> every graded image of that pass passed on the reference's inputs
    std::map<std::pair<std::string, std::string>, bool> isolated_checks;

    void readHints() {
        if (!options.hints || hints_read) return;
        hints_read = true;
        ScopedTiming timing("hints", id, "load");
        loadLabHints((fs::path(stored_dir) / "hints").string(), &hints, &hints_error);
    }
};

// How the student's lab is rendered: the submission's folder is the containment root and the
// progress events carry the lab's id.
RenderOptions studentRenderOptions(const std::string& submission_dir, const std::string& id,
                                   const GradeOptions& options) {
    RenderOptions render;
    render.containment_root = submission_dir;
    if (options.progress)
        render.progress = [progress = options.progress, id](const std::string& event) {
            progress(id, event);
        };
    return render;
}

// The student first: a submission that does not build needs no reference at all. From `queue`
// when the submission's labs are rendered by one child, else by a child of its own.
IsolatedRender renderStudent(const LabSpec& spec, const std::string& submission_dir, const std::string& id,
                             const GradeOptions& options, IsolatedRenderQueue* queue, std::string* renderer,
                             grader::ReportLab* lab, const std::function<void()>& while_rendering) {
    // What was graded, named in the report: the student files of this lab in this folder.
    lab->folder = fs::absolute(fs::path(submission_dir) / id).lexically_normal().string();
    lab->files = spec.student_files;
    ScopedTiming student_timing("render_child", id, "student");
    IsolatedRender student =
        queue ? queue->next(while_rendering)
              : renderLabIsolated(spec, (fs::path(submission_dir) / id).string(), options.backend,
                                  options.limits, studentRenderOptions(submission_dir, id, options),
                                  while_rendering);
    student_timing.stop();
    if (!student.renderer.empty()) *renderer = student.renderer;
    for (const Diagnostic& d : student.render.diagnostics) lab->diagnostics.push_back(toReportDiagnostic(d));
    return student;
}

// Scenes whose file did not load: reported, not graded.
struct UnloadableScenes {
    std::set<std::string> names;
    std::string message;
};

UnloadableScenes unloadableScenes(const std::vector<SceneRender>& scenes) {
    UnloadableScenes unloadable;
    for (const SceneRender& scene : scenes) {
        if (scene.error.empty()) continue;
        unloadable.names.insert(scene.scene);
        unloadable.message += (unloadable.message.empty() ? "" : "; ") + std::string("scene '") +
                              scene.scene + "' did not load: " + scene.error;
    }
    return unloadable;
}

// The reference must match the lab as it is now; a mismatch (goldens older than lab.json)
// is the lab's fault, never the student's. Returns the lab's message for it, or "".
std::string referenceMismatch(const std::vector<SceneRender>& scenes, const ReferenceImages& ref,
                              const std::vector<GradedImage>& graded,
                              const std::set<std::string>& unloadable) {
    for (const SceneRender& scene : scenes) {
        if (unloadable.count(scene.scene)) continue;
        const auto it = ref.scenes.find(scene.scene);
        bool consistent = it != ref.scenes.end() && it->second.size() == graded.size() &&
                          scene.passes.size() == graded.size();
        for (std::size_t i = 0; consistent && i < scene.passes.size(); ++i)
            consistent = it->second[i].color.width == scene.passes[i].color.width &&
                         it->second[i].color.height == scene.passes[i].color.height &&
                         scene.passes[i].pass == graded[i].pass->name &&
                         scene.passes[i].attachment == graded[i].attachment;
        if (!consistent)
            return "the reference images (" + ref.source + ") do not match lab.json for scene '" +
                   scene.scene + "': regenerate them with `shaderlab goldens`";
    }
    return {};
}

// The report's entry for one judged image, its pictures aside.
grader::ReportPass reportPass(const GradedImage& g, const grader::ImageVerdict& v,
                              const grader::Thresholds& thresholds, const grader::Image& mine) {
    grader::ReportPass rp;
    rp.name = g.id;
    rp.pass = g.pass->name;
    rp.attachment = g.attachment;
    rp.range = g.hdr ? "hdr" : "display";
    rp.hdr_scale = v.hdr_scale;
    rp.passed = v.passed;
    rp.reasons = v.reasons;
    rp.metrics = reportMetrics(v.covered, v);
    rp.thresholds.known = true;
    rp.thresholds.psnr_min_db = thresholds.psnr_min_db;
    rp.thresholds.ssim_min = thresholds.ssim_min;
    rp.thresholds.flip_mean_max = thresholds.flip_mean_max;
    rp.thresholds.mismatch_max = thresholds.mismatch_max;
    rp.thresholds.pixel_tolerance = thresholds.pixel_tolerance;
    rp.width = mine.width;
    rp.height = mine.height;
    rp.worst_region = v.worst.tile;
    rp.non_finite_box = v.non_finite_box;
    return rp;
}

// What a scene's judged images leave for the scene's verdict.
struct SceneFailures {
    std::vector<FailingImage> failing;
    // What each image looked like, for the known-mistake comparison once the scene is judged.
    std::vector<FailingPicture> pictures;
};

// One graded image judged and its pictures written: what the scene's verdict takes from it.
struct JudgedImage {
    grader::ImageVerdict verdict;  // its FLIP map and mismatch mask dropped once drawn
    grader::ReportPass pass;
    grading_detail::ShownPictures shown;
    std::vector<std::string> write_errors;
};

// Judges graded image `i` of `scene` against `theirs` and writes its pictures. Reads `lab` and
// writes only the scene's own pictures, so that scenes can be judged on threads of their own.
JudgedImage judgeGradedImage(const LabGrading& lab, const SceneRender& scene, std::size_t i,
                             const PassImage& theirs, const std::string& reference_source) {
    const PassImage& mine = scene.passes[i];
    const GradedImage& g = lab.graded[i];
    const grader::Thresholds thresholds = imageThresholds(lab.spec, scene.scene, *g.pass);
    JudgedImage j;
    ScopedTiming metrics_timing("metrics", lab.id, scene.scene);
    j.verdict = grader::judgeImage(theirs.color, theirs.coverage, mine.color, mine.coverage, thresholds,
                                   g.hdr ? grader::ImageRange::Hdr : grader::ImageRange::Display);
    metrics_timing.stop();
    ScopedTiming images_timing("images", lab.id, scene.scene);
    j.pass = reportPass(g, j.verdict, thresholds, mine.color);
    grading_detail::PicturePlace place;
    place.out_dir = lab.options.out_dir;
    place.lab = lab.id;
    place.scene = scene.scene;
    place.final_image = i + 1 == scene.passes.size();
    place.reference_source = reference_source;
    place.stored_dir = lab.stored_dir;
    j.shown = grading_detail::writeReportPictures(place, g, j.verdict, mine.color, theirs.color, &j.pass,
                                                  &j.write_errors);
    j.verdict.flip_map = {};
    j.verdict.mismatches = {};
    return j;
}

// Adds judged image `i` of `scene` to the scene's report and to what the lab keeps of it (the
// scene's own figures and pictures are its final image's). In the scenes' order, one at a time.
void recordImage(LabGrading& lab, const SceneRender& scene, std::size_t i, JudgedImage&& j,
                 grader::ReportScene* rs, SceneFailures* failures) {
    const GradedImage& g = lab.graded[i];
    const grader::ImageVerdict& v = j.verdict;
    lab.write_errors.insert(lab.write_errors.end(), j.write_errors.begin(), j.write_errors.end());
    // Only a failing image can be the one a known mistake explains.
    if (!v.passed) lab.readHints();
    failures->pictures.push_back(
        !v.passed && !lab.hints.hints.empty()
            ? FailingPicture{g.id, std::move(j.shown.student), std::move(j.shown.reference), v.graded}
            : FailingPicture{});
    auto& check = lab.checks.emplace(std::make_pair(scene.scene, g.pass->name), true).first->second;
    check = check && v.passed;
    if (!v.passed) failures->failing.push_back({i, v.reasons});
    grader::ReportPass& rp = j.pass;
    if (i + 1 == scene.passes.size()) {
        rs->metrics = rp.metrics;
        rs->frame_metrics = reportMetrics(v.frame, v);
        rs->worst_region = v.worst.tile;
        rs->non_finite_box = v.non_finite_box;
        rs->student_image = rp.student_image;
        rs->reference_image = rp.reference_image;
        rs->diff_image = rp.diff_image;
        rs->signed_image = rp.signed_image;
        rs->zoom_image = rp.zoom_image;
    }
    rs->passes.push_back(std::move(rp));
}

// Every graded image of every scene judged (judgeGradedImage), the scenes shared among up to as many
// threads as the machine has cores: the metrics and the pictures of one scene need nothing of
// another's. Unloadable scenes get no images. An exception on a thread is thrown again here.
std::vector<std::vector<JudgedImage>> judgeScenes(const LabGrading& lab,
                                                  const std::vector<SceneRender>& scenes,
                                                  const ReferenceImages& ref,
                                                  const std::set<std::string>& unloadable) {
    std::vector<std::vector<JudgedImage>> judged(scenes.size());
    // The lab's picture folder first, so that threads never race to make the same folder.
    if (!lab.options.out_dir.empty()) {
        std::string ignored;  // a failure shows again, with its reason, at the first picture
        grader::createFoldersInside(lab.options.out_dir, lab.id, &ignored);
    }
    std::atomic<std::size_t> next{0};
    std::exception_ptr failure;
    std::mutex failure_lock;
    auto work = [&]() {
        for (std::size_t s = next++; s < scenes.size(); s = next++) {
            const SceneRender& scene = scenes[s];
            if (unloadable.count(scene.scene)) continue;
            try {
                const std::vector<PassImage>& theirs = ref.scenes.at(scene.scene);
                for (std::size_t i = 0; i < scene.passes.size(); ++i)
                    judged[s].push_back(judgeGradedImage(lab, scene, i, theirs[i], ref.source));
            } catch (...) {
                const std::lock_guard<std::mutex> hold(failure_lock);
                if (!failure) failure = std::current_exception();
            }
        }
    };
    const std::size_t threads =
        std::min<std::size_t>(scenes.size(), std::max(1u, std::min(4u, std::thread::hardware_concurrency())));
    std::vector<std::thread> pool;
    for (std::size_t t = 1; t < threads; ++t) {
        try {
            pool.emplace_back(work);
        } catch (const std::system_error&) {
            break;  // no more threads to be had: the ones there (this one at least) do the rest
        }
    }
    work();
    for (std::thread& t : pool) t.join();
    if (failure) std::rethrow_exception(failure);
    return judged;
}

// Where to look first: the failing images no other failing image feeds (through the
// targets their passes read and draw into). A later pass that uses a wrong image differs
// as a consequence, and its numbers would point the student at the wrong place; two
// independent tasks that both fail are both named.
std::vector<const FailingImage*> firstWrongImages(const LabGrading& lab,
                                                  const std::vector<FailingImage>& failing) {
    std::vector<const FailingImage*> roots;
    for (const FailingImage& f : failing) {
        const std::size_t pass = passIndex(lab.spec, lab.graded[f.image].pass->name);
        const bool fed_by_failure = std::any_of(failing.begin(), failing.end(), [&](const FailingImage& o) {
            return lab.ancestors[pass].count(passIndex(lab.spec, lab.graded[o.image].pass->name)) > 0;
        });
        if (!fed_by_failure) roots.push_back(&f);
    }
    return roots;
}

// The scene's message and first failing pass from its failing images: where to look first.
// `inherited`: failing images that match on the reference's inputs (pass isolation), so they
// differ only because of what they read.
std::vector<const FailingImage*> describeScene(const LabGrading& lab,
                                               const std::vector<FailingImage>& failing,
                                               std::size_t image_count, std::size_t inherited,
                                               grader::ReportScene* rs) {
    const std::vector<const FailingImage*> roots = firstWrongImages(lab, failing);
    if (!roots.empty()) rs->first_failing_pass = lab.graded[roots.front()->image].id;
    if (image_count == 1 && !failing.empty()) {
        rs->message = joinReasons(failing.front().reasons);
    } else if (roots.size() == 1 && failing.size() + inherited > 1) {
        rs->message = "first wrong pass: '" + rs->first_failing_pass +
                      "': " + joinReasons(roots.front()->reasons) +
                      (inherited > 0 ? " (" + std::to_string(inherited) +
                                           " later images differ only because of what they read: on the "
                                           "reference's inputs they match)"
                                     : " (later passes that use it differ too)");
    } else {
        for (const FailingImage* r : roots)
            rs->message += (rs->message.empty() ? "'" : "; '") + lab.graded[r->image].id +
                           "': " + joinReasons(r->reasons);
        if (inherited > 0)
            rs->message += " (" + std::to_string(inherited) +
                           " later images differ only because of what they read: on the reference's inputs "
                           "they match)";
    }
    return roots;
}

// One scene's verdict: every graded image judged, and the scene's message naming where to look.
grader::ReportScene gradeScene(LabGrading& lab, const SceneRender& scene, std::vector<JudgedImage>&& judged,
                               bool unloadable) {
    grader::ReportScene rs;
    rs.name = scene.scene;
    rs.render_ms = scene.render_ms;
    if (unloadable) {
        // The lab's fault: said plainly, and the lab's other scenes are graded as usual.
        rs.status = "failed";
        rs.message =
            "the scene's file did not load, so this scene was not rendered (a problem of the lab, "
            "not of the submission): " +
            scene.error;
        return rs;
    }
    SceneFailures failures;
    for (std::size_t i = 0; i < judged.size(); ++i)
        recordImage(lab, scene, i, std::move(judged[i]), &rs, &failures);
    const std::vector<FailingImage>& failing = failures.failing;
    rs.status = failing.empty() ? "passed" : "failed";
    const std::vector<const FailingImage*> roots = describeScene(lab, failing, scene.passes.size(), 0, &rs);
    if (!roots.empty() && !lab.hints.hints.empty())
        lab.failing_pictures[scene.scene] = std::move(failures.pictures[roots.front()->image]);
    if (!failing.empty()) lab.failing_images[scene.scene] = failing;
    return rs;
}

// Whether a pass is judged in the render on the reference's inputs: an isolated pass, and every
// pass its results reach (a blur chain isolated at its first pass is judged as a chain, fed
// with the reference's bright image).
bool judgedAlone(const LabGrading& lab, const PassSpec& pass) {
    if (pass.isolate) return true;
    const std::set<std::size_t>& before = lab.ancestors[passIndex(lab.spec, pass.name)];
    return std::any_of(before.begin(), before.end(),
                       [&](std::size_t j) { return lab.spec.passes[j].isolate; });
}

// Pass isolation: the scenes that failed rendered again with each isolated pass reading the
// reference's images, and those passes judged on that. Their goals then use this verdict (a
// wrong bright pass costs the bright goal, not the blur's), and the scene's message names the
// images that are wrong on their own. A render that does not succeed leaves the pipeline's
// verdicts, and the lab's message says why.
void judgeOnReferenceInputs(LabGrading& lab, const std::string& submission_dir, const ReferenceImages& ref,
                            grader::ReportLab* report) {
    if (lab.failing_images.empty() || !grading_detail::isolatesAnyPass(lab.spec)) return;
    std::vector<std::string> scenes;
    for (const auto& [scene, failing] : lab.failing_images) scenes.push_back(scene);
    const IsolatedRender alone =
        grading_detail::renderOnReferenceInputs(lab.spec, submission_dir, ref, scenes, lab.options);
    if (alone.status != IsolatedStatus::Ok) {
        report->message += (report->message.empty() ? "" : "; ") +
                           std::string("the passes could not be judged on the reference's inputs (") +
                           isolatedStatusName(alone.status) + "): " + alone.message;
        return;
    }
    for (const SceneRender& scene : alone.render.scenes) {
        const auto rs = std::find_if(report->scenes.begin(), report->scenes.end(),
                                     [&](const grader::ReportScene& r) { return r.name == scene.scene; });
        const auto theirs = ref.scenes.find(scene.scene);
        if (rs == report->scenes.end() || theirs == ref.scenes.end() || !scene.error.empty() ||
            scene.passes.size() != lab.graded.size() || rs->passes.size() != lab.graded.size())
            continue;
        for (std::size_t i = 0; i < lab.graded.size(); ++i) {
            const GradedImage& g = lab.graded[i];
            if (!judgedAlone(lab, *g.pass)) continue;
            ScopedTiming metrics_timing("metrics", lab.id, scene.scene);
            const grader::ImageVerdict v =
                grader::judgeImage(theirs->second[i].color, theirs->second[i].coverage, scene.passes[i].color,
                                   scene.passes[i].coverage, imageThresholds(lab.spec, scene.scene, *g.pass),
                                   g.hdr ? grader::ImageRange::Hdr : grader::ImageRange::Display);
            grader::ReportPass& rp = rs->passes[i];
            rp.isolated = true;
            rp.isolated_passed = v.passed;
            rp.isolated_reasons = v.reasons;
            rp.isolated_metrics = reportMetrics(v.covered, v);
            auto& check =
                lab.isolated_checks.emplace(std::make_pair(scene.scene, g.pass->name), true).first->second;
            check = check && v.passed;
        }
        // The images wrong on their own: those not isolated, and the isolated ones that differ
        // on the reference's inputs too.
        const std::vector<FailingImage>& failing = lab.failing_images[scene.scene];
        std::vector<FailingImage> wrong;
        for (const FailingImage& f : failing)
            if (!rs->passes[f.image].isolated || !rs->passes[f.image].isolated_passed) wrong.push_back(f);
        if (wrong.empty()) continue;  // each pass right alone: the pipeline's message stands
        rs->message.clear();
        rs->first_failing_pass.clear();
        describeScene(lab, wrong, scene.passes.size(), failing.size() - wrong.size(), &*rs);
    }
}

// A known mistake that draws every scene it fails the way the student did explains them.
void explainSceneFailures(const LabGrading& lab, grader::ReportLab* report) {
    if (lab.failing_pictures.empty()) return;
    ScopedTiming timing("hints", lab.id, "explain");
    const std::map<std::string, grader::ReportHint> explained =
        explainFailures(lab.hints, lab.failing_pictures);
    for (grader::ReportScene& rs : report->scenes) {
        const auto it = explained.find(rs.name);
        if (it != explained.end()) rs.hint = it->second;
    }
}

// A goal that rests on others (depends_on) is not met while one of them is not, because of it,
// whatever its own checks say. The dependencies form no circle (the lab's validator), so walking
// them in the lab's order until nothing changes settles every goal.
void applyGoalDependencies(const LabSpec& spec, std::vector<grader::ReportGoal>* goals) {
    std::map<std::string, const grader::ReportGoal*> by_id;
    for (const grader::ReportGoal& g : *goals) by_id[g.id] = &g;
    for (bool changed = true; changed;) {
        changed = false;
        for (std::size_t i = 0; i < goals->size(); ++i) {
            grader::ReportGoal& g = (*goals)[i];
            for (const std::string& dep : spec.goals[i].depends_on) {
                const auto it = by_id.find(dep);
                if (it == by_id.end() || it->second->met ||
                    std::find(g.not_met_because.begin(), g.not_met_because.end(), dep) !=
                        g.not_met_because.end())
                    continue;
                g.not_met_because.push_back(dep);
                g.met = false;
                changed = true;
            }
        }
    }
}

// Goals' own verdicts: met when every check of theirs passed. An isolated pass's check is its
// verdict on the reference's inputs where it was judged so, unless the goal is judged on the
// pipeline.
std::vector<grader::ReportGoal> goalVerdicts(
    const LabSpec& spec, const std::map<std::pair<std::string, std::string>, bool>& pipeline_checks,
    const std::map<std::pair<std::string, std::string>, bool>& isolated_checks) {
    std::vector<grader::ReportGoal> goals;
    for (const GoalSpec& goal : spec.goals) {
        grader::ReportGoal rg;
        rg.id = goal.id;
        rg.title = goal.title;
        rg.points = goal.points;
        rg.scenes = goal.scenes;
        rg.met = true;
        for (const std::string& scene : goal.scenes) {
            for (const std::string& pass : goal.passes) {
                const auto alone = isolated_checks.find({scene, pass});
                const auto it = pipeline_checks.find({scene, pass});
                const bool passed = !goal.pipeline && alone != isolated_checks.end()
                                        ? alone->second
                                        : it != pipeline_checks.end() && it->second;
                if (!passed) {
                    rg.met = false;
                    rg.failing.push_back(scene + "/" + pass);
                }
            }
        }
        goals.push_back(std::move(rg));
    }
    return goals;
}

// The lab's score from its goals' final verdicts. A goal's points are shared among its scenes for
// the per-scene figures, so scene scores add up to the lab's.
void scoreGoals(const LabSpec& spec, std::vector<grader::ReportGoal>&& goals, grader::ReportLab* lab) {
    for (std::size_t i = 0; i < goals.size(); ++i) {
        const GoalSpec& goal = spec.goals[i];
        const grader::ReportGoal& rg = goals[i];
        const double share =
            goal.scenes.empty() ? 0.0 : goal.points / static_cast<double>(goal.scenes.size());
        for (grader::ReportScene& rs : lab->scenes) {
            if (std::find(goal.scenes.begin(), goal.scenes.end(), rs.name) == goal.scenes.end()) continue;
            rs.max_score += share;
            if (rg.met) rs.score += share;
        }
        if (rg.met) lab->score += goal.points;
    }
    lab->goals = std::move(goals);
}

const std::string& goldensRoot(const GradeOptions& options, const std::string& id) {
    const auto own = options.lab_goldens_roots.find(id);
    return own != options.lab_goldens_roots.end() ? own->second : options.goldens_root;
}

// Grades lab `id`, parsed as `parsed`. `queue`: the child rendering the submission's labs, whose
// next lab is this one; null: a child of its own.
grader::ReportLab gradeLab(const std::string& submission_dir, const std::string& id,
                           const LabSpecResult& parsed, const GradeOptions& options,
                           IsolatedRenderQueue* queue, std::string* renderer) {
    grader::ReportLab lab;
    lab.id = id;
    ScopedTiming lab_timing("lab", id);
    const auto t0 = std::chrono::steady_clock::now();
    auto finish = [&]() {
        lab.wall_ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        return lab;
    };

    if (!parsed.ok) {
        lab.status = "crashed";
        lab.message = "the lab itself is broken: " + joinReasons(parsed.errors);
        return finish();
    }
    const LabSpec& spec = parsed.spec;
    lab.title = spec.title;
    lab.max_score = spec.grading.points;

    // (A lab in the queue had its folder when the queue was made: the child says if it is gone.)
    std::error_code ec;
    if (!queue && !fs::is_directory(fs::path(submission_dir) / id, ec)) {
        lab.status = "missing";
        lab.message =
            (fs::path(submission_dir) / id).string() + ": the submission has no folder for this lab";
        return finish();
    }
    // (A queued lab was found attempted when the queue was made.)
    if (!queue && grading_detail::untouchedStarter(spec, submission_dir, &lab.message)) {
        lab.status = "not_attempted";
        lab.folder = fs::absolute(fs::path(submission_dir) / id).lexically_normal().string();
        lab.files = spec.student_files;
        return finish();
    }

    // Stored goldens (no reference solution to render), or the reference's images kept in the
    // cache for the renderer it saw last, are read while the student's render runs: on a thread
    // started once the render child exists (so that no thread runs at its fork) and joined here,
    // before anything else forks; with a queue, whose child is drawing this lab already and may
    // have to start again, right away on this thread. Read without knowing which scenes the
    // render could not load: a missing golden of such a scene reads again below, skipping it.
    std::string stored_dir =
        goldensRoot(options, id).empty() ? spec.lab_dir : (fs::path(goldensRoot(options, id)) / id).string();
    const bool stored_goldens = !grading_detail::hasReference(options.reference_root, id);
    std::string guessed_cache;
    std::future<ReferenceImages> early_goldens;
    ReferenceImages early;
    const IsolatedRender student =
        renderStudent(spec, submission_dir, id, options, queue, renderer, &lab, [&]() {
            if (!stored_goldens && options.reference_cache_guess)
                guessed_cache = options.reference_cache_guess(spec);
            const std::string early_dir = stored_goldens          ? stored_dir
                                          : guessed_cache.empty() ? std::string()
                                                                  : (fs::path(guessed_cache) / id).string();
            if (early_dir.empty()) return;
            if (queue) {
                early = grading_detail::loadGoldens(spec, early_dir, {});
                return;
            }
            try {
                if (!early_dir.empty())
                    early_goldens = std::async(std::launch::async, [&spec, early_dir]() {
                        return grading_detail::loadGoldens(spec, early_dir, {});
                    });
            } catch (const std::system_error&) {
                // No thread to be had (a process limit): the goldens are read after the render.
            }
        });
    if (early_goldens.valid()) early = early_goldens.get();
    if (student.status != IsolatedStatus::Ok) {
        lab.status = labStatusOf(student.status);
        lab.message = student.message;
        lab.limit = student.limit;
        return finish();
    }

    // Goldens and hints live in the lab's folder, or under goldens_root when it is given; a
    // reference render kept from an earlier run lives in the cache, hints beside it.
    const UnloadableScenes unloadable = unloadableScenes(student.render.scenes);
    ReferenceImages ref;
    if (!stored_goldens) {
        const std::string cached =
            options.reference_cache ? options.reference_cache(spec, student.renderer) : std::string();
        if (!cached.empty()) {
            if (cached == guessed_cache && early.ok) {
                ref = std::move(early);
                for (const std::string& name : unloadable.names) ref.scenes.erase(name);
            } else {
                ref = grading_detail::loadGoldens(spec, (fs::path(cached) / id).string(), unloadable.names);
            }
            ref.source = "reference_cache";
            if (ref.ok) stored_dir = (fs::path(cached) / id).string();
        }
        // No cache, or an entry that cannot be read (removed under us): render it now.
        if (!ref.ok) ref = grading_detail::renderReference(spec, options.reference_root, options);
    } else if (early.ok) {
        ref = std::move(early);
        for (const std::string& name : unloadable.names) ref.scenes.erase(name);
    } else {
        ref = grading_detail::loadGoldens(spec, stored_dir, unloadable.names);
    }
    lab.reference_source = ref.source;
    if (!ref.ok) {
        lab.status = "crashed";
        lab.message = ref.error;
        return finish();
    }

    LabGrading grading(spec, id, options, stored_dir);
    grading.graded = gradedImages(spec);
    const std::string mismatch =
        referenceMismatch(student.render.scenes, ref, grading.graded, unloadable.names);
    if (!mismatch.empty()) {
        lab.status = "crashed";
        lab.message = mismatch;
        return finish();
    }

    grading.ancestors = passAncestors(spec);
    std::vector<std::vector<JudgedImage>> judged =
        judgeScenes(grading, student.render.scenes, ref, unloadable.names);
    bool all_passed = true;
    for (std::size_t s = 0; s < student.render.scenes.size(); ++s) {
        const SceneRender& scene = student.render.scenes[s];
        grader::ReportScene rs =
            gradeScene(grading, scene, std::move(judged[s]), unloadable.names.count(scene.scene) > 0);
        all_passed = all_passed && rs.status == "passed";
        lab.scenes.push_back(std::move(rs));
    }
    explainSceneFailures(grading, &lab);
    judgeOnReferenceInputs(grading, submission_dir, ref, &lab);
    std::vector<grader::ReportGoal> goals = goalVerdicts(spec, grading.checks, grading.isolated_checks);
    grading_detail::isolateGoals(spec, submission_dir, ref, options, &goals);
    applyGoalDependencies(spec, &goals);
    scoreGoals(spec, std::move(goals), &lab);

    lab.status = all_passed ? "passed" : "failed";
    if (!unloadable.message.empty()) lab.message += (lab.message.empty() ? "" : "; ") + unloadable.message;
    if (!grading.write_errors.empty())
        lab.message += (lab.message.empty() ? "" : "; ") + std::string("could not write images: ") +
                       joinReasons(grading.write_errors);
    if (!grading.hints_error.empty())
        lab.message += (lab.message.empty() ? "" : "; ") + std::string("known-mistake hints not used: ") +
                       grading.hints_error;
    return finish();
}

}  // namespace

grader::ReportDiagnostic toReportDiagnostic(const Diagnostic& d) {
    return {d.file,        d.line,        d.column,         d.severity, d.message,
            d.explanation, d.source_line, d.driver_message, d.follow_on};
}

grader::Report gradeSubmission(const std::string& submission_dir, const GradeOptions& options,
                               const LabCallback& on_lab) {
    grader::Report report;
    report.submission = submission_dir;
    report.backend = backendName(options.backend);
    const std::vector<std::string> ids = options.labs.empty() ? listLabIds(options.labs_root) : options.labs;
    // Every lab is parsed first; those the submission has a folder for are rendered by one child,
    // one after another (IsolatedRenderQueue), while the grader judges the lab before.
    std::vector<LabSpecResult> parsed;
    std::vector<IsolatedLabJob> jobs;
    std::vector<bool> queued;
    parsed.reserve(ids.size());  // the jobs point into it
    for (const std::string& id : ids) {
        parsed.push_back(parseLabSpec((fs::path(options.labs_root) / id).string()));
        std::error_code ec;
        std::string untouched;
        queued.push_back(parsed.back().ok && fs::is_directory(fs::path(submission_dir) / id, ec) &&
                         !grading_detail::untouchedStarter(parsed.back().spec, submission_dir, &untouched));
        if (queued.back())
            jobs.push_back({&parsed.back().spec, (fs::path(submission_dir) / id).string(),
                            studentRenderOptions(submission_dir, id, options)});
    }
    std::unique_ptr<IsolatedRenderQueue> queue;
    if (jobs.size() > 1) {
        queue = std::make_unique<IsolatedRenderQueue>(std::move(jobs), options.backend, options.limits);
        queue->start();
    }
    for (std::size_t i = 0; i < ids.size(); ++i) {
        const std::string& id = ids[i];
        grader::ReportLab lab = gradeLab(submission_dir, id, parsed[i], options,
                                         queued[i] ? queue.get() : nullptr, &report.renderer);
        report.score += lab.score;
        report.max_score += lab.max_score;
        report.labs.push_back(std::move(lab));
        if (on_lab) on_lab(report);
    }
    return report;
}

grader::Thresholds imageThresholds(const LabSpec& spec, const std::string& scene, const PassSpec& pass) {
    const SceneSpec* scene_spec = nullptr;
    for (const SceneSpec& candidate : spec.scenes)
        if (candidate.name == scene) scene_spec = &candidate;
    const GradingThresholds t =
        scene_spec ? scene_spec->thresholds.applyTo(pass.thresholds) : pass.thresholds;
    grader::Thresholds out;
    out.psnr_min_db = t.psnr_min_db;
    out.ssim_min = t.ssim_min;
    out.flip_mean_max = t.flip_mean_max;
    out.mismatch_max = t.mismatch_max;
    out.pixel_tolerance = t.pixel_tolerance;
    return out;
}

}  // namespace shaderlab
