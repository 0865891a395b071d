// What the files of the grading library share and grading.h does not say: the graded images of
// a lab, where the reference images come from, and the report's pictures of one judged image.
// Private to framework/grading/src; nothing here is part of the library's interface.
#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "grader/metrics/scoring.h"
#include "grader/reports/report.h"
#include "shaderlab/grading/grading.h"
#include "shaderlab/lab/lab_spec.h"
#include "shaderlab/render/isolated_render.h"

namespace shaderlab::grading_detail {

// One graded image of every scene: a pass's attachment, in the order the renderer reads them.
struct GradedImage {
    const PassSpec* pass = nullptr;
    std::string attachment;
    std::string id;  // "shade", or "gbuffer.normal" when the target has several attachments
    bool hdr = false;
};

std::vector<GradedImage> gradedImages(const LabSpec& spec);

// Renders the lab folder `id` of the submission `root` (student files must stay inside root).
IsolatedRender renderFrom(const LabSpec& spec, const std::string& root, Backend backend,
                          const IsolationLimits& limits,
                          const std::function<void(const std::string&)>& progress = {},
                          const std::function<void()>& while_rendering = {});

struct ReferenceImages {
    bool ok = false;
    std::string source;  // "reference_solutions" (rendered now) | "goldens" | "reference_cache"
    std::string error;
    // scene -> graded passes in order
    std::map<std::string, std::vector<PassImage>> scenes;
};

// `skip`: scenes whose file did not load, which have no goldens to compare with.
ReferenceImages loadGoldens(const LabSpec& spec, const std::string& lab_dir,
                            const std::set<std::string>& skip);

ReferenceImages renderReference(const LabSpec& spec, const std::string& reference_root,
                                const GradeOptions& options);

bool hasReference(const std::string& reference_root, const std::string& id);

// Where the pictures of one judged image go, and where its reference came from.
struct PicturePlace {
    std::filesystem::path out_dir;  // the report folder
    std::string lab, scene;         // the pictures go to <lab>/<scene>/ in it
    bool final_image = false;       // student.png; another graded image: student.<image>.png
    std::string reference_source;   // ReferenceImages::source
    std::string stored_dir;         // where the lab's goldens are read from
};

// What the pictures showed: the images as compared (HDR images over the same scale), the
// student's with NaN and Inf in magenta.
struct ShownPictures {
    grader::Image student;
    grader::Image reference;
};

// Writes the report's pictures of one judged image (student, reference, FLIP heat map, signed
// difference, and a close-up when it failed) and names them in `rp`; a picture that cannot be
// written adds its reason to `errors` and is left unnamed.
ShownPictures writeReportPictures(const PicturePlace& place, const GradedImage& g,
                                  const grader::ImageVerdict& v, const grader::Image& mine,
                                  const grader::Image& theirs, grader::ReportPass* rp,
                                  std::vector<std::string>* errors);

// Pass isolation (pass_isolation.cpp): whether a pass of the lab is judged on the reference's
// inputs, and the submission's render of `scenes` with those passes reading the reference's
// images (RenderOptions::stand_ins).
bool isolatesAnyPass(const LabSpec& spec);
IsolatedRender renderOnReferenceInputs(const LabSpec& spec, const std::string& submission_dir,
                                       const ReferenceImages& ref, const std::vector<std::string>& scenes,
                                       const GradeOptions& options);

// Goal isolation (goal_isolation.cpp): each goal with work of its own that its checks on the
// whole shaders failed, judged again on renders of the reference with only that work taken from
// the submission; sets every goal's `judged` (and `judged_note` where it could not be done).
void isolateGoals(const LabSpec& spec, const std::string& submission_dir, const ReferenceImages& ref,
                  const GradeOptions& options, std::vector<grader::ReportGoal>* goals);

// Where the reference's student files are read for goal isolation (GradeOptions::isolation_root,
// else reference_root, else reference_solutions/ beside the labs); empty when there is none.
std::string isolationRoot(const GradeOptions& options);

}  // namespace shaderlab::grading_detail
