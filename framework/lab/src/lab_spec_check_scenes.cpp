// Step 4 of the lab.json parser, for scenes and cameras: cameras that cannot look anywhere (a zero
// or parallel up, far before near, fields of the other projection), unique scene names, the scene
// file a scene draw needs, repeat overrides of passes that repeat, and uniform overrides that name
// a sampler.
#include <map>
#include <set>
#include <string>
#include <vector>

#include "lab_spec_steps.h"

namespace shaderlab::lab_spec_detail {

void Validator::checkCameras() {
    auto check = [this](const CameraOverride& c, const std::string& path) {
        const std::string cam = joinKey(path, "camera");
        if (c.up && glm::length(*c.up) == 0.0f)
            diag_.error(joinKey(cam, "up"), "must not be the zero vector");
        if (c.z_near && c.z_far && *c.z_far <= *c.z_near)
            diag_.error(joinKey(cam, "far"), "must be greater than near (" + formatNumber(*c.z_near) +
                                                 "), got " + formatNumber(*c.z_far));
        if (c.position && c.target) {
            const glm::vec3 forward = *c.target - *c.position;
            if (glm::length(forward) == 0.0f)
                diag_.error(joinKey(cam, "target"), "must differ from position");
            else if (c.up && glm::length(*c.up) > 0.0f &&
                     glm::length(glm::cross(glm::normalize(forward), glm::normalize(*c.up))) < 1e-6f)
                diag_.error(joinKey(cam, "up"),
                            "must not be parallel to the viewing direction (target - position)");
        }
        if (c.height && c.projection != Projection::Orthographic)
            diag_.error(joinKey(cam, "height"), "applies to \"projection\": \"orthographic\" only");
        if (c.fov_y_deg && c.projection == Projection::Orthographic)
            diag_.error(joinKey(cam, "fov_y_deg"),
                        "an orthographic camera has no field of view; give \"height\"");
        if (c.light && (c.position || c.target))
            diag_.error(cam,
                        "\"light\" places the camera at the light; leave \"position\" and \"target\" out");
    };
    for (const PassSpec& p : spec_.passes) check(p.camera, p.path);
    std::set<std::string> seen;
    for (const SceneSpec& s : spec_.scenes)
        if (seen.insert(s.path).second) check(s.camera, s.path.substr(0, s.path.find(".times")));
}

void Validator::checkScenes() {
    std::map<std::string, std::string> names;
    const bool draws_scene = std::any_of(spec_.passes.begin(), spec_.passes.end(),
                                         [](const PassSpec& p) { return p.draw == DrawKind::Scene; });
    std::set<std::string> checked;
    for (SceneSpec& s : spec_.scenes) {
        const std::string base = s.path.substr(0, s.path.find(".times"));
        const auto [it, fresh] = names.emplace(s.name, base);
        if (!fresh)
            diag_.error(joinKey(base, "name"),
                        "scene " + quoteJson(s.name) + " is also the name of " + it->second);
        if (!checked.insert(base).second) continue;
        if (draws_scene && s.file.empty())
            diag_.error(joinKey(base, "file"), "is required: a pass draws the scene (\"draw\": \"scene\")");
        for (const auto& [pass, count] : s.repeats) {
            const int j = passIndex(pass);
            if (j < 0 || !drafts_[static_cast<std::size_t>(j)].repeat_count) {
                std::vector<std::string> repeated;
                for (const LoopSpec& l : spec_.loops) repeated.push_back(l.declared_by);
                diag_.error(joinKey(joinKey(base, "repeats"), pass),
                            j < 0 ? "no pass is called " + quoteJson(pass) + didYouMean(pass, repeated)
                                  : "pass " + quoteJson(pass) + " has no \"repeat\" to change");
            }
            (void)count;
        }
        for (const UniformSetting& u : s.uniforms)
            for (const PassSpec& p : spec_.passes)
                for (const PassInput& in : p.inputs)
                    if (in.sampler == u.name)
                        diag_.error(u.path, quoteJson(u.name) + " is a sampler input of " + p.path +
                                                "; a sampler gets a texture, not a value");
    }
}

}  // namespace shaderlab::lab_spec_detail
