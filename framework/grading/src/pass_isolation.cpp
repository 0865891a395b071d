// Pass isolation (lab.json `isolate`, docs/grading.md "Pass isolation"): the submission rendered
// again with every isolated pass reading the reference's images of the graded passes before it,
// so a pass is judged on what it does and not on what it was given. Judging the images is
// grading.cpp's.
#include <algorithm>
#include <filesystem>

#include "grading_detail.h"
#include "shaderlab/base/timings.h"

namespace fs = std::filesystem;

namespace shaderlab::grading_detail {

bool isolatesAnyPass(const LabSpec& spec) {
    return std::any_of(spec.passes.begin(), spec.passes.end(), [](const PassSpec& p) { return p.isolate; });
}

IsolatedRender renderOnReferenceInputs(const LabSpec& spec, const std::string& submission_dir,
                                       const ReferenceImages& ref, const std::vector<std::string>& scenes,
                                       const GradeOptions& options) {
    // Only the images some isolated pass reads, as the goldens store them: a grade that renders
    // the reference and one that reads the goldens then give the pass the same values.
    std::set<std::pair<std::string, std::string>> wanted;  // (pass, attachment)
    for (std::size_t i = 0; i < spec.passes.size(); ++i) {
        if (!spec.passes[i].isolate) continue;
        for (const PassInput& in : spec.passes[i].inputs) {
            const StandInSource source = standInSource(spec, i, in);
            if (source.pass) wanted.insert({source.pass->name, source.attachment});
        }
    }
    RenderOptions render;
    render.containment_root = submission_dir;
    render.only_scenes = scenes;
    const bool stored = ref.source != "reference_solutions";  // read from PNG/RGBE files: already rounded
    for (const std::string& scene : scenes) {
        const auto it = ref.scenes.find(scene);
        if (it == ref.scenes.end()) continue;
        for (const PassImage& image : it->second) {
            if (!wanted.count({image.pass, image.attachment})) continue;
            StandIn stand_in{scene, image.pass, image.attachment, image.color};
            const PassSpec* pass = spec.findPass(image.pass);
            if (!stored) grader::quantizeAsStored(&stand_in.image, pass && pass->compare == CompareMode::Hdr);
            render.stand_ins.push_back(std::move(stand_in));
        }
    }
    ScopedTiming timing("render_child", spec.id, "isolated");
    return renderLabIsolated(spec, (fs::path(submission_dir) / spec.id).string(), options.backend,
                             options.limits, render);
}

}  // namespace shaderlab::grading_detail
