// Grading a submission lab by lab; see grading.h and docs/grading.md.
#include "shaderlab/grading/grading.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "grader/base/atomic_file.h"
#include "grader/metrics/heatmap.h"
#include "grader/reports/report_images.h"
#include "grader/metrics/scoring.h"
#include "shaderlab/lab/lab_catalog.h"
#include "shaderlab/lab/lab_spec.h"
#include "shaderlab/grading/mistake_hints.h"
#include "shaderlab/base/timings.h"

namespace fs = std::filesystem;

namespace shaderlab {

namespace {

struct ReferenceImages {
    bool ok = false;
    std::string source;  // "reference_solutions" | "goldens"
    std::string error;
    // scene -> graded passes in order
    std::map<std::string, std::vector<PassImage>> scenes;
};

// Renders the lab folder `id` of the submission `root` (student files must stay inside root).
IsolatedRender renderFrom(const LabSpec& spec, const std::string& root, Backend backend,
                          const IsolationLimits& limits,
                          const std::function<void(const std::string&)>& progress = {}) {
    RenderOptions options;
    options.containment_root = root;
    options.progress = progress;
    return renderLabIsolated(spec, (fs::path(root) / spec.id).string(), backend, limits, options);
}

// The report's closed set of lab statuses for a render that did not succeed: the isolated
// render's names, except that a GL error or broken scene (render_error) counts as crashed.
std::string labStatusOf(IsolatedStatus s) {
    return s == IsolatedStatus::RenderError ? "crashed" : isolatedStatusName(s);
}

// One graded image of every scene: a pass's attachment, in the order the renderer reads them.
struct GradedImage {
    const PassSpec* pass = nullptr;
    std::string attachment;
    std::string id;  // "shade", or "gbuffer.normal" when the target has several attachments
    bool hdr = false;
};

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

grader::Image coverageImage(const std::vector<std::uint8_t>& coverage, int w, int h) {
    grader::Image img(w, h, 1);
    for (std::size_t i = 0; i < img.pixels.size() && i < coverage.size(); ++i)
        img.pixels[i] = coverage[i] ? 1.0f : 0.0f;
    return img;
}

// `skip`: scenes whose file did not load, which have no goldens to compare with.
ReferenceImages loadGoldens(const LabSpec& spec, const std::string& lab_dir,
                            const std::set<std::string>& skip) {
    ReferenceImages ref;
    ref.source = "goldens";
    ScopedTiming timing("goldens", spec.id);
    const std::vector<GradedImage> graded = gradedImages(spec);
    for (const SceneSpec& scene : spec.scenes) {
        if (skip.count(scene.name)) continue;
        std::vector<PassImage>& passes = ref.scenes[scene.name];
        for (std::size_t i = 0; i < graded.size(); ++i) {
            const bool final_image = i + 1 == graded.size();
            PassImage img;
            img.pass = graded[i].pass->name;
            img.attachment = graded[i].attachment;
            img.graded = true;
            const std::string color_path =
                goldenPath(lab_dir, scene.name, graded[i].id, final_image, false, graded[i].hdr);
            const std::string cov_path = goldenPath(lab_dir, scene.name, graded[i].id, final_image, true);
            grader::Image cov;
            std::string err;
            const bool color_ok = graded[i].hdr ? grader::readHdr(color_path, &img.color, &err)
                                                : grader::readPng(color_path, &img.color, &err);
            if (!color_ok || !grader::readPng(cov_path, &cov, &err)) {
                ref.error = "no reference solution and no golden image: " + err +
                            " (run `shaderlab goldens` with the reference solutions)";
                return ref;
            }
            img.coverage.resize(cov.pixels.size() / static_cast<std::size_t>(cov.channels));
            for (std::size_t p = 0; p < img.coverage.size(); ++p)
                img.coverage[p] = cov.pixels[p * static_cast<std::size_t>(cov.channels)] > 0.5f ? 1 : 0;
            passes.push_back(std::move(img));
        }
    }
    ref.ok = true;
    return ref;
}

ReferenceImages renderReference(const LabSpec& spec, const std::string& reference_root,
                                const GradeOptions& options) {
    ReferenceImages ref;
    ref.source = "reference_solutions";
    ScopedTiming timing("render_child", spec.id, "reference");
    const IsolatedRender r = renderFrom(spec, reference_root, options.backend, options.limits);
    timing.stop();
    if (r.status != IsolatedStatus::Ok) {
        ref.error = std::string("the reference solution did not render (") + isolatedStatusName(r.status) +
                    "): " + r.message;
        return ref;
    }
    for (const SceneRender& s : r.render.scenes) ref.scenes[s.scene] = s.passes;
    ref.ok = true;
    return ref;
}

bool hasReference(const std::string& reference_root, const std::string& id) {
    std::error_code ec;
    return !reference_root.empty() && fs::is_directory(fs::path(reference_root) / id, ec);
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

// Writes one PNG and returns its path relative to the report folder (empty on failure, with
// the reason added to `errors`).
std::string writeImage(const grader::Image& img, const fs::path& out_dir, const fs::path& rel,
                       std::vector<std::string>* errors) {
    std::string err;
    // Folder by folder, refusing a link planted on the way (atomic_file.h); writePng refuses one
    // at the file's own name.
    if (!grader::createFoldersInside(out_dir.string(), rel.parent_path().string(), &err) ||
        !grader::writePng(img, (out_dir / rel).string(), &err)) {
        errors->push_back(err);
        return {};
    }
    return rel.generic_string();
}

// The reference picture when the reference is a stored golden PNG: the file itself, copied (its
// pixels are exactly the image compared), instead of encoding the same pixels again. Falls back
// to writing `img` when the copy fails.
std::string copyOrWriteImage(const std::string& golden, const grader::Image& img, const fs::path& out_dir,
                             const fs::path& rel, std::vector<std::string>* errors) {
    if (!golden.empty()) {
        // The same care as writeImage: no folder or file of the output written through a link.
        std::ifstream in(golden, std::ios::binary);
        std::ostringstream bytes;
        bytes << in.rdbuf();
        std::string err;
        if (in && grader::createFoldersInside(out_dir.string(), rel.parent_path().string(), &err) &&
            grader::writeFileAtomically((out_dir / rel).string(), bytes.str(), &err, false))
            return rel.generic_string();
        if (!err.empty()) {
            errors->push_back(err);
            return {};
        }
    }
    return writeImage(img, out_dir, rel, errors);
}

grader::ReportLab gradeLab(const std::string& submission_dir, const std::string& id,
                           const GradeOptions& options, std::string* renderer) {
    grader::ReportLab lab;
    lab.id = id;
    ScopedTiming lab_timing("lab", id);
    const auto t0 = std::chrono::steady_clock::now();
    auto finish = [&]() {
        lab.wall_ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        return lab;
    };

    const LabSpecResult parsed = parseLabSpec((fs::path(options.labs_root) / id).string());
    if (!parsed.ok) {
        lab.status = "crashed";
        lab.message = "the lab itself is broken: " + joinReasons(parsed.errors);
        return finish();
    }
    const LabSpec& spec = parsed.spec;
    lab.title = spec.title;
    lab.max_score = spec.grading.points;

    std::error_code ec;
    if (!fs::is_directory(fs::path(submission_dir) / id, ec)) {
        lab.status = "missing";
        lab.message =
            (fs::path(submission_dir) / id).string() + ": the submission has no folder for this lab";
        return finish();
    }

    // The student first: a submission that does not build needs no reference at all.
    // What was graded, named in the report: the student files of this lab in this folder.
    lab.folder = fs::absolute(fs::path(submission_dir) / id).lexically_normal().string();
    lab.files = spec.student_files;
    ScopedTiming student_timing("render_child", id, "student");
    const IsolatedRender student =
        renderFrom(spec, submission_dir, options.backend, options.limits,
                   options.progress ? std::function<void(const std::string&)>(
                                          [&](const std::string& event) { options.progress(id, event); })
                                    : std::function<void(const std::string&)>());
    student_timing.stop();
    if (!student.renderer.empty()) *renderer = student.renderer;
    for (const Diagnostic& d : student.render.diagnostics) lab.diagnostics.push_back(toReportDiagnostic(d));
    if (student.status != IsolatedStatus::Ok) {
        lab.status = labStatusOf(student.status);
        lab.message = student.message;
        lab.limit = student.limit;
        return finish();
    }

    // Goldens and hints live in the lab's folder, or under goldens_root when it is given.
    const std::string stored_dir =
        options.goldens_root.empty() ? spec.lab_dir : (fs::path(options.goldens_root) / id).string();
    std::set<std::string> unloadable;  // scenes whose file did not load: reported, not graded
    std::string unloadable_message;
    for (const SceneRender& scene : student.render.scenes) {
        if (scene.error.empty()) continue;
        unloadable.insert(scene.scene);
        unloadable_message += (unloadable_message.empty() ? "" : "; ") + std::string("scene '") +
                              scene.scene + "' did not load: " + scene.error;
    }
    const ReferenceImages ref = hasReference(options.reference_root, id)
                                    ? renderReference(spec, options.reference_root, options)
                                    : loadGoldens(spec, stored_dir, unloadable);
    lab.reference_source = ref.source;
    if (!ref.ok) {
        lab.status = "crashed";
        lab.message = ref.error;
        return finish();
    }

    const std::vector<GradedImage> graded = gradedImages(spec);
    const fs::path out_dir = options.out_dir;
    std::vector<std::string> write_errors;
    LabHints hints;
    std::string hints_error;  // the lab's fault: said in the lab's message, and grading goes on
    // Read at the first failing image: a lab that passes never needs its known-mistake pictures.
    bool hints_read = false;
    auto readHints = [&]() {
        if (!options.hints || hints_read) return;
        hints_read = true;
        ScopedTiming timing("hints", id, "load");
        loadLabHints((fs::path(stored_dir) / "hints").string(), &hints, &hints_error);
    };

    // The reference must match the lab as it is now; a mismatch (goldens older than lab.json)
    // is the lab's fault, never the student's.
    for (const SceneRender& scene : student.render.scenes) {
        if (unloadable.count(scene.scene)) continue;
        const auto it = ref.scenes.find(scene.scene);
        bool consistent = it != ref.scenes.end() && it->second.size() == graded.size() &&
                          scene.passes.size() == graded.size();
        for (std::size_t i = 0; consistent && i < scene.passes.size(); ++i)
            consistent = it->second[i].color.width == scene.passes[i].color.width &&
                         it->second[i].color.height == scene.passes[i].color.height &&
                         scene.passes[i].pass == graded[i].pass->name &&
                         scene.passes[i].attachment == graded[i].attachment;
        if (!consistent) {
            lab.status = "crashed";
            lab.message = "the reference images (" + ref.source + ") do not match lab.json for scene '" +
                          scene.scene + "': regenerate them with `shaderlab goldens`";
            return finish();
        }
    }

    // (scene, pass) -> every graded image of that pass passed
    std::map<std::pair<std::string, std::string>, bool> checks;
    // scene -> its first wrong image, for the known-mistake hints once every scene is judged
    std::map<std::string, FailingPicture> failing_pictures;
    const std::vector<std::set<std::size_t>> ancestors = passAncestors(spec);
    bool all_passed = true;
    for (const SceneRender& scene : student.render.scenes) {
        grader::ReportScene rs;
        rs.name = scene.scene;
        rs.render_ms = scene.render_ms;
        if (unloadable.count(scene.scene)) {
            // The lab's fault: said plainly, and the lab's other scenes are graded as usual.
            rs.status = "failed";
            rs.message =
                "the scene's file did not load, so this scene was not rendered (a problem of the lab, "
                "not of the submission): " +
                scene.error;
            all_passed = false;
            lab.scenes.push_back(std::move(rs));
            continue;
        }
        const auto ref_it = ref.scenes.find(scene.scene);
        std::vector<FailingImage> failing;
        // What each image looked like, for the known-mistake comparison once the scene is judged.
        std::vector<FailingPicture> pictures;
        for (std::size_t i = 0; i < scene.passes.size(); ++i) {
            const PassImage& mine = scene.passes[i];
            const PassImage& theirs = ref_it->second[i];
            const GradedImage& g = graded[i];
            const bool final_image = i + 1 == scene.passes.size();
            const grader::Thresholds thresholds = imageThresholds(spec, scene.scene, *g.pass);
            ScopedTiming metrics_timing("metrics", id, scene.scene);
            const grader::ImageVerdict v =
                grader::judgeImage(theirs.color, theirs.coverage, mine.color, mine.coverage, thresholds,
                                   g.hdr ? grader::ImageRange::Hdr : grader::ImageRange::Display);
            metrics_timing.stop();
            ScopedTiming images_timing("images", id, scene.scene);
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
            rp.width = mine.color.width;
            rp.height = mine.color.height;
            rp.worst_region = v.worst.tile;
            rp.non_finite_box = v.non_finite_box;
            const fs::path base = fs::path(id) / scene.scene;
            const std::string suffix = final_image ? "" : "." + g.id;
            // The pictures show what was compared: HDR images over the same scale.
            grader::Image shown_mine = mine.color, shown_theirs = theirs.color;
            if (g.hdr && v.hdr_scale > 1.0) {
                for (grader::Image* img : {&shown_mine, &shown_theirs})
                    for (std::size_t k = 0; k < img->pixels.size(); ++k)
                        if (img->channels < 4 || k % 4 != 3)  // colour only: alpha stays as drawn
                            img->pixels[k] = static_cast<float>(img->pixels[k] / v.hdr_scale);
            }
            // NaN and Inf show in magenta (a PNG would hold them as black or white).
            const grader::Image picture = grader::markNonFinite(shown_mine);
            rp.student_image =
                writeImage(picture, out_dir, base / ("student" + suffix + ".png"), &write_errors);
            const bool golden_png = ref.source == "goldens" && !g.hdr;
            rp.reference_image = copyOrWriteImage(
                golden_png ? goldenPath(stored_dir, scene.scene, g.id, final_image, false) : std::string(),
                shown_theirs, out_dir, base / ("reference" + suffix + ".png"), &write_errors);
            grader::HeatmapConfig hc;
            hc.outline = v.mismatches.empty() ? nullptr : &v.mismatches;
            const grader::Image heat =
                grader::diffHeatmap(v.flip_map, mine.color.width, mine.color.height, hc);
            if (!heat.empty())
                rp.diff_image = writeImage(heat, out_dir, base / ("diff" + suffix + ".png"), &write_errors);
            const grader::Image signed_picture = grader::signedDifference(shown_theirs, shown_mine);
            if (!signed_picture.empty())
                rp.signed_image =
                    writeImage(signed_picture, out_dir, base / ("signed" + suffix + ".png"), &write_errors);
            // A failing image gets a close-up: 32x32 pixels around the worst region of the
            // comparison (its 16x16 window and some context), or around the first NaN or Inf pixel
            // when nothing else differs.
            if (!v.passed) {
                grader::PixelBox region;
                if (!v.worst.tile.empty())
                    region = grader::windowAround(v.worst.centre.x, v.worst.centre.y, 32, mine.color.width,
                                                  mine.color.height);
                else if (!v.non_finite_first.empty())
                    region = grader::windowAround(v.non_finite_first[0].x, v.non_finite_first[0].y, 32,
                                                  mine.color.width, mine.color.height);
                if (!region.empty()) {
                    const int factor = std::max(1, 128 / std::max(region.width(), region.height()));
                    const grader::Image strip =
                        grader::sideBySide({grader::cropZoom(picture, region, factor),
                                            grader::cropZoom(shown_theirs, region, factor),
                                            grader::cropZoom(heat, region, factor)});
                    rp.zoom_region = region;
                    if (!strip.empty())
                        rp.zoom_image =
                            writeImage(strip, out_dir, base / ("zoom" + suffix + ".png"), &write_errors);
                }
            }
            images_timing.stop();
            // Only a failing image can be the one a known mistake explains.
            if (!v.passed) readHints();
            pictures.push_back(!v.passed && !hints.hints.empty()
                                   ? FailingPicture{g.id, picture, shown_theirs, v.graded}
                                   : FailingPicture{});
            auto& check = checks.emplace(std::make_pair(scene.scene, g.pass->name), true).first->second;
            check = check && v.passed;
            if (!v.passed) failing.push_back({i, v.reasons});
            if (final_image) {
                rs.metrics = rp.metrics;
                rs.frame_metrics = reportMetrics(v.frame, v);
                rs.worst_region = v.worst.tile;
                rs.non_finite_box = v.non_finite_box;
                rs.student_image = rp.student_image;
                rs.reference_image = rp.reference_image;
                rs.diff_image = rp.diff_image;
                rs.signed_image = rp.signed_image;
                rs.zoom_image = rp.zoom_image;
            }
            rs.passes.push_back(std::move(rp));
        }
        rs.status = failing.empty() ? "passed" : "failed";
        // Where to look first: the failing images no other failing image feeds (through the
        // targets their passes read and draw into). A later pass that uses a wrong image differs
        // as a consequence, and its numbers would point the student at the wrong place; two
        // independent tasks that both fail are both named.
        std::vector<const FailingImage*> roots;
        for (const FailingImage& f : failing) {
            const std::size_t pass = passIndex(spec, graded[f.image].pass->name);
            const bool fed_by_failure =
                std::any_of(failing.begin(), failing.end(), [&](const FailingImage& o) {
                    return ancestors[pass].count(passIndex(spec, graded[o.image].pass->name)) > 0;
                });
            if (!fed_by_failure) roots.push_back(&f);
        }
        if (!roots.empty()) rs.first_failing_pass = graded[roots.front()->image].id;
        if (scene.passes.size() == 1 && !failing.empty()) {
            rs.message = joinReasons(failing.front().reasons);
        } else if (roots.size() == 1 && failing.size() > 1) {
            rs.message = "first wrong pass: '" + rs.first_failing_pass +
                         "': " + joinReasons(roots.front()->reasons) +
                         " (later passes that use it differ too)";
        } else {
            for (const FailingImage* r : roots)
                rs.message += (rs.message.empty() ? "'" : "; '") + graded[r->image].id +
                              "': " + joinReasons(r->reasons);
        }
        if (!roots.empty() && !hints.hints.empty())
            failing_pictures[scene.scene] = std::move(pictures[roots.front()->image]);
        all_passed = all_passed && rs.status == "passed";
        lab.scenes.push_back(std::move(rs));
    }

    // A known mistake that draws every scene it fails the way the student did explains them.
    if (!failing_pictures.empty()) {
        ScopedTiming timing("hints", id, "explain");
        const std::map<std::string, grader::ReportHint> explained = explainFailures(hints, failing_pictures);
        for (grader::ReportScene& rs : lab.scenes) {
            const auto it = explained.find(rs.name);
            if (it != explained.end()) rs.hint = it->second;
        }
    }

    // Goals: met when every check of theirs passed. A goal's points are shared among its
    // scenes for the per-scene figures, so scene scores add up to the lab's.
    for (const GoalSpec& goal : spec.goals) {
        grader::ReportGoal rg;
        rg.id = goal.id;
        rg.title = goal.title;
        rg.points = goal.points;
        rg.scenes = goal.scenes;
        rg.met = true;
        for (const std::string& scene : goal.scenes) {
            for (const std::string& pass : goal.passes) {
                const auto it = checks.find({scene, pass});
                if (it == checks.end() || !it->second) {
                    rg.met = false;
                    rg.failing.push_back(scene + "/" + pass);
                }
            }
        }
        const double share =
            goal.scenes.empty() ? 0.0 : goal.points / static_cast<double>(goal.scenes.size());
        for (grader::ReportScene& rs : lab.scenes) {
            if (std::find(goal.scenes.begin(), goal.scenes.end(), rs.name) == goal.scenes.end()) continue;
            rs.max_score += share;
            if (rg.met) rs.score += share;
        }
        if (rg.met) lab.score += goal.points;
        lab.goals.push_back(std::move(rg));
    }
    lab.status = all_passed ? "passed" : "failed";
    if (!unloadable_message.empty()) lab.message = unloadable_message;
    if (!write_errors.empty())
        lab.message += (lab.message.empty() ? "" : "; ") + std::string("could not write images: ") +
                       joinReasons(write_errors);
    if (!hints_error.empty())
        lab.message +=
            (lab.message.empty() ? "" : "; ") + std::string("known-mistake hints not used: ") + hints_error;
    return finish();
}

}  // namespace

grader::ReportDiagnostic toReportDiagnostic(const Diagnostic& d) {
    return {d.file,        d.line,        d.column,         d.severity, d.message,
            d.explanation, d.source_line, d.driver_message, d.follow_on};
}

std::string goldenPath(const std::string& lab_dir, const std::string& scene, const std::string& image,
                       bool final_image, bool coverage, bool hdr) {
    std::string name = scene;
    if (!final_image) name += "." + image;
    name += coverage ? ".coverage.png" : hdr ? ".hdr" : ".png";
    return (fs::path(lab_dir) / "golden" / name).string();
}

grader::Report gradeSubmission(const std::string& submission_dir, const GradeOptions& options,
                               const LabCallback& on_lab) {
    grader::Report report;
    report.submission = submission_dir;
    report.backend = backendName(options.backend);
    const std::vector<std::string> ids = options.labs.empty() ? listLabIds(options.labs_root) : options.labs;
    for (const std::string& id : ids) {
        grader::ReportLab lab = gradeLab(submission_dir, id, options, &report.renderer);
        report.score += lab.score;
        report.max_score += lab.max_score;
        report.labs.push_back(std::move(lab));
        if (on_lab) on_lab(report);
    }
    return report;
}

std::vector<std::string> writeGoldens(const std::string& reference_root, const std::string& labs_root,
                                      const std::vector<std::string>& labs, Backend backend,
                                      const std::string& golden_root_override) {
    std::vector<std::string> errors;
    const std::vector<std::string> ids = labs.empty() ? listLabIds(labs_root) : labs;
    for (const std::string& id : ids) {
        const LabSpecResult parsed = parseLabSpec((fs::path(labs_root) / id).string());
        if (!parsed.ok) {
            errors.insert(errors.end(), parsed.errors.begin(), parsed.errors.end());
            continue;
        }
        const IsolatedRender r = renderFrom(parsed.spec, reference_root, backend, IsolationLimits{});
        if (r.status != IsolatedStatus::Ok) {
            errors.push_back(id + ": reference solution: " + isolatedStatusName(r.status) + ": " + r.message);
            continue;
        }
        const std::string lab_dir = golden_root_override.empty()
                                        ? parsed.spec.lab_dir
                                        : (fs::path(golden_root_override) / id).string();
        std::error_code ec;
        fs::remove_all(fs::path(lab_dir) / "golden", ec);  // stale goldens of renamed scenes go too
        fs::create_directories(fs::path(lab_dir) / "golden", ec);
        const std::vector<GradedImage> graded = gradedImages(parsed.spec);
        for (const SceneRender& s : r.render.scenes) {
            if (!s.error.empty()) errors.push_back(id + ": scene '" + s.scene + "': " + s.error);
            for (std::size_t i = 0; i < s.passes.size() && i < graded.size(); ++i) {
                const PassImage& p = s.passes[i];
                const bool final_image = i + 1 == s.passes.size();
                const GradedImage& g = graded[i];
                std::string err;
                const std::string color = goldenPath(lab_dir, s.scene, g.id, final_image, false, g.hdr);
                bool ok =
                    g.hdr ? grader::writeHdr(p.color, color, &err) : grader::writePng(p.color, color, &err);
                // An .hdr golden gets a PNG beside it for people and READMEs: its colours over
                // their largest value (when above 1), as the report shows HDR images.
                if (ok && g.hdr) {
                    grader::Image preview = p.color;
                    float peak = 1.0f;
                    for (std::size_t k = 0; k < preview.pixels.size(); ++k)
                        if (k % 4 != 3 && std::isfinite(preview.pixels[k]))
                            peak = std::max(peak, preview.pixels[k]);
                    for (std::size_t k = 0; k < preview.pixels.size(); ++k)
                        if (k % 4 != 3) preview.pixels[k] /= peak;
                    ok = grader::writePng(preview, color.substr(0, color.size() - 4) + ".preview.png", &err);
                }
                if (!ok || !grader::writePng(coverageImage(p.coverage, p.color.width, p.color.height),
                                             goldenPath(lab_dir, s.scene, g.id, final_image, true), &err))
                    errors.push_back(err);
            }
        }
    }
    return errors;
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

bool loadGoldenScene(const LabSpec& spec, const std::string& stored_dir, const std::string& scene,
                     std::vector<PassImage>* out, std::string* error) {
    LabSpec one = spec;
    one.scenes.erase(std::remove_if(one.scenes.begin(), one.scenes.end(),
                                    [&](const SceneSpec& s) { return s.name != scene; }),
                     one.scenes.end());
    if (one.scenes.empty()) {
        *error = "the lab has no scene '" + scene + "'";
        return false;
    }
    ReferenceImages ref = loadGoldens(one, stored_dir, {});
    if (!ref.ok) {
        *error = ref.error;
        return false;
    }
    *out = std::move(ref.scenes[scene]);
    return true;
}

}  // namespace shaderlab
