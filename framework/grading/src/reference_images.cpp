// Where the images a submission is compared with come from: the reference solution rendered in
// a child process, or the lab's stored goldens; and writing those goldens. It does not compare
// anything (grading.cpp does).
#include <algorithm>
#include <cmath>
#include <filesystem>

#include "grader/base/atomic_file.h"
#include "grader/metrics/image.h"
#include "grading_detail.h"
#include "shaderlab/base/timings.h"
#include "shaderlab/lab/lab_catalog.h"

namespace fs = std::filesystem;

namespace shaderlab {

namespace grading_detail {

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

}  // namespace grading_detail

using grading_detail::GradedImage;
using grading_detail::gradedImages;
using grading_detail::loadGoldens;
using grading_detail::ReferenceImages;
using grading_detail::renderFrom;

namespace {

grader::Image coverageImage(const std::vector<std::uint8_t>& coverage, int w, int h) {
    grader::Image img(w, h, 1);
    for (std::size_t i = 0; i < img.pixels.size() && i < coverage.size(); ++i)
        img.pixels[i] = coverage[i] ? 1.0f : 0.0f;
    return img;
}

}  // namespace

std::string goldenPath(const std::string& lab_dir, const std::string& scene, const std::string& image,
                       bool final_image, bool coverage, bool hdr) {
    std::string name = scene;
    if (!final_image) name += "." + image;
    name += coverage ? ".coverage.png" : hdr ? ".hdr" : ".png";
    return (fs::path(lab_dir) / "golden" / name).string();
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
        // Which renderer drew them: on the same one a fresh set must equal them to the bit, on
        // another (a newer Mesa) match them within the lab's thresholds (tests/goldens_test.cpp).
        std::string renderer_error;
        if (!grader::writeFileAtomically((fs::path(lab_dir) / "golden" / "renderer.txt").string(),
                                         r.renderer + "\n", &renderer_error))
            errors.push_back(id + ": " + renderer_error);
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
