// Grading a submission lab by lab; see grading.h and docs/grading.md.
#include "shaderlab/grading.h"

#include <chrono>
#include <filesystem>
#include <map>

#include "grader/heatmap.h"
#include "grader/scoring.h"
#include "shaderlab/lab_catalog.h"
#include "shaderlab/lab_spec.h"

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
                          const IsolationLimits& limits) {
    RenderOptions options;
    options.containment_root = root;
    return renderLabIsolated(spec, (fs::path(root) / spec.id).string(), backend, limits, options);
}

// The report's closed set of lab statuses for a render that did not succeed: the isolated
// render's names, except that a GL error or broken scene (render_error) counts as crashed.
std::string labStatusOf(IsolatedStatus s) {
    return s == IsolatedStatus::RenderError ? "crashed" : isolatedStatusName(s);
}

std::vector<const PassSpec*> gradedPasses(const LabSpec& spec) {
    std::vector<const PassSpec*> out;
    for (const PassSpec& p : spec.passes)
        if (p.graded) out.push_back(&p);
    return out;
}

grader::Image coverageImage(const std::vector<std::uint8_t>& coverage, int w, int h) {
    grader::Image img(w, h, 1);
    for (std::size_t i = 0; i < img.pixels.size() && i < coverage.size(); ++i)
        img.pixels[i] = coverage[i] ? 1.0f : 0.0f;
    return img;
}

ReferenceImages loadGoldens(const LabSpec& spec) {
    ReferenceImages ref;
    ref.source = "goldens";
    const auto graded = gradedPasses(spec);
    for (const SceneSpec& scene : spec.scenes) {
        std::vector<PassImage>& passes = ref.scenes[scene.name];
        for (std::size_t i = 0; i < graded.size(); ++i) {
            const bool final_image = i + 1 == graded.size();
            PassImage img;
            img.pass = graded[i]->name;
            img.graded = true;
            const std::string color_path = goldenPath(spec.lab_dir, scene.name, img.pass, final_image, false);
            const std::string cov_path = goldenPath(spec.lab_dir, scene.name, img.pass, final_image, true);
            grader::Image cov;
            std::string err;
            if (!grader::readPng(color_path, &img.color, &err) || !grader::readPng(cov_path, &cov, &err)) {
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
    const IsolatedRender r = renderFrom(spec, reference_root, options.backend, options.limits);
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
    std::error_code ec;
    fs::create_directories((out_dir / rel).parent_path(), ec);
    std::string err;
    if (!grader::writePng(img, (out_dir / rel).string(), &err)) {
        errors->push_back(err);
        return {};
    }
    return rel.generic_string();
}

grader::ReportLab gradeLab(const std::string& submission_dir, const std::string& id,
                           const GradeOptions& options, std::string* renderer) {
    grader::ReportLab lab;
    lab.id = id;
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
    const IsolatedRender student = renderFrom(spec, submission_dir, options.backend, options.limits);
    if (!student.renderer.empty()) *renderer = student.renderer;
    for (const Diagnostic& d : student.render.diagnostics)
        lab.diagnostics.push_back({d.file, d.line, d.column, d.severity, d.message});
    if (student.status != IsolatedStatus::Ok) {
        lab.status = labStatusOf(student.status);
        lab.message = student.message;
        return finish();
    }

    const ReferenceImages ref = hasReference(options.reference_root, id)
                                    ? renderReference(spec, options.reference_root, options)
                                    : loadGoldens(spec);
    lab.reference_source = ref.source;
    if (!ref.ok) {
        lab.status = "crashed";
        lab.message = ref.error;
        return finish();
    }

    grader::Thresholds thresholds;
    thresholds.psnr_min_db = spec.grading.psnr_min_db;
    thresholds.ssim_min = spec.grading.ssim_min;
    thresholds.flip_mean_max = spec.grading.flip_mean_max;
    thresholds.mismatch_max = spec.grading.mismatch_max;
    thresholds.pixel_tolerance = spec.grading.pixel_tolerance;
    const double scene_points = spec.scenes.empty() ? 0.0
                                                    : static_cast<double>(spec.grading.points) /
                                                          static_cast<double>(spec.scenes.size());
    const fs::path out_dir = options.out_dir;
    std::vector<std::string> write_errors;

    // The reference must match the lab as it is now; a mismatch (goldens older than lab.json)
    // is the lab's fault, never the student's.
    for (const SceneRender& scene : student.render.scenes) {
        const auto it = ref.scenes.find(scene.scene);
        bool consistent = it != ref.scenes.end() && it->second.size() == scene.passes.size();
        for (std::size_t i = 0; consistent && i < scene.passes.size(); ++i)
            consistent = it->second[i].color.width == scene.passes[i].color.width &&
                         it->second[i].color.height == scene.passes[i].color.height;
        if (!consistent) {
            lab.status = "crashed";
            lab.message = "the reference images (" + ref.source + ") do not match lab.json for scene '" +
                          scene.scene + "': regenerate them with `shaderlab goldens`";
            return finish();
        }
    }

    bool all_passed = true;
    for (const SceneRender& scene : student.render.scenes) {
        grader::ReportScene rs;
        rs.name = scene.scene;
        rs.max_score = scene_points;
        rs.render_ms = scene.render_ms;
        const auto ref_it = ref.scenes.find(scene.scene);
        bool non_finite = false;
        for (std::size_t i = 0; i < scene.passes.size(); ++i) {
            const PassImage& mine = scene.passes[i];
            const PassImage& theirs = ref_it->second[i];
            const bool final_image = i + 1 == scene.passes.size();
            const grader::ImageVerdict v =
                grader::judgeImage(theirs.color, theirs.coverage, mine.color, mine.coverage, thresholds);
            grader::ReportPass rp;
            rp.name = mine.pass;
            rp.passed = v.passed;
            rp.reasons = v.reasons;
            rp.metrics = reportMetrics(v.covered, v);
            const fs::path base = fs::path(id) / scene.scene;
            const std::string suffix = final_image ? "" : "." + mine.pass;
            rp.student_image =
                writeImage(mine.color, out_dir, base / ("student" + suffix + ".png"), &write_errors);
            rp.reference_image =
                writeImage(theirs.color, out_dir, base / ("reference" + suffix + ".png"), &write_errors);
            grader::HeatmapConfig hc;
            hc.outline = v.mismatches.empty() ? nullptr : &v.mismatches;
            const grader::Image heat =
                grader::diffHeatmap(v.flip_map, mine.color.width, mine.color.height, hc);
            if (!heat.empty())
                rp.diff_image = writeImage(heat, out_dir, base / ("diff" + suffix + ".png"), &write_errors);
            if (!v.passed && rs.first_failing_pass.empty()) rs.first_failing_pass = mine.pass;
            // NaN or Inf in any graded pass fails the scene, even when later passes hide it.
            non_finite = non_finite || v.nan_count > 0 || v.inf_count > 0;
            if (final_image) {
                rs.status = v.passed && !non_finite ? "passed" : "failed";
                rs.score = non_finite ? 0.0 : grader::scenePoints(v, scene_points);
                rs.metrics = rp.metrics;
                rs.frame_metrics = reportMetrics(v.frame, v);
                rs.worst_region = v.worst.tile;
                rs.non_finite_box = v.non_finite_box;
                rs.student_image = rp.student_image;
                rs.reference_image = rp.reference_image;
                rs.diff_image = rp.diff_image;
                rs.message = joinReasons(v.reasons);
                if (non_finite && v.nan_count == 0 && v.inf_count == 0)
                    rs.message = "NaN or Inf in an earlier pass. " + rs.message;
                if (!rs.first_failing_pass.empty() && scene.passes.size() > 1)
                    rs.message = "first wrong pass: '" + rs.first_failing_pass + "'. " + rs.message;
            }
            rs.passes.push_back(std::move(rp));
        }
        all_passed = all_passed && rs.status == "passed";
        lab.score += rs.score;
        lab.scenes.push_back(std::move(rs));
    }
    lab.status = all_passed ? "passed" : "failed";
    if (!write_errors.empty()) lab.message = "could not write images: " + joinReasons(write_errors);
    return finish();
}

}  // namespace

std::string goldenPath(const std::string& lab_dir, const std::string& scene, const std::string& pass,
                       bool final_image, bool coverage) {
    std::string name = scene;
    if (!final_image) name += "." + pass;
    name += coverage ? ".coverage.png" : ".png";
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
        for (const SceneRender& s : r.render.scenes) {
            for (std::size_t i = 0; i < s.passes.size(); ++i) {
                const PassImage& p = s.passes[i];
                const bool final_image = i + 1 == s.passes.size();
                std::string err;
                if (!grader::writePng(p.color, goldenPath(lab_dir, s.scene, p.pass, final_image, false),
                                      &err) ||
                    !grader::writePng(coverageImage(p.coverage, p.color.width, p.color.height),
                                      goldenPath(lab_dir, s.scene, p.pass, final_image, true), &err))
                    errors.push_back(err);
            }
        }
    }
    return errors;
}

}  // namespace shaderlab
