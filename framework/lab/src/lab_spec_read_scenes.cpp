// Step 3 of the lab.json parser, for scenes: the glTF file, the camera and lights that replace
// the file's, uniform, threshold and repeat overrides, and "times", which expands one scene into
// one per time (name_t0, name_t1, ...). Whether the names, files and repeats refer to something is
// checked later (lab_spec_check_scenes.cpp, lab_spec_check_files.cpp).
#include <string>
#include <utility>
#include <vector>

#include "lab_spec_steps.h"

namespace shaderlab::lab_spec_detail {

namespace {

std::string scenePath(std::size_t i) { return joinIndex("scenes", i); }

}  // namespace

void Reader::readScene(const json& v, std::size_t i) {
    const std::string path = scenePath(i);
    SceneSpec s;
    s.path = path;
    s.base_name = v["name"];
    s.name = s.base_name;
    s.file = v.value("file", "");
    if (v.contains("camera")) readCamera(v["camera"], s.camera);
    if (v.contains("lights")) {
        std::vector<LightSpec> lights;
        const json& ls = v["lights"];
        for (std::size_t k = 0; k < ls.size(); ++k)
            lights.push_back(readLight(ls[k], joinIndex(joinKey(path, "lights"), k)));
        s.lights = std::move(lights);
    }
    if (v.contains("uniforms")) readUniforms(v["uniforms"], joinKey(path, "uniforms"), s.uniforms);
    if (v.contains("time")) s.time = v["time"];
    if (v.contains("repeats"))
        for (const auto& item : v["repeats"].items()) s.repeats[item.key()] = item.value();
    if (v.contains("thresholds")) {
        const json& t = v["thresholds"];
        ThresholdOverrides& o = s.thresholds;
        if (t.contains("psnr_min_db")) o.psnr_min_db = t["psnr_min_db"].get<float>();
        if (t.contains("ssim_min")) o.ssim_min = t["ssim_min"].get<float>();
        if (t.contains("flip_mean_max")) o.flip_mean_max = t["flip_mean_max"].get<float>();
        if (t.contains("mismatch_max")) o.mismatch_max = t["mismatch_max"].get<float>();
        if (t.contains("pixel_tolerance")) o.pixel_tolerance = t["pixel_tolerance"].get<float>();
    }
    if (v.contains("times")) {
        const json& times = v["times"];
        for (std::size_t k = 0; k < times.size(); ++k) {
            SceneSpec t = s;
            t.name = s.base_name + "_t" + std::to_string(k);
            t.time = times[k];
            t.path = joinIndex(joinKey(path, "times"), k);
            spec_.scenes.push_back(std::move(t));
        }
    } else {
        spec_.scenes.push_back(std::move(s));
    }
}

LightSpec Reader::readLight(const json& v, const std::string& path) {
    LightSpec l;
    l.type = v["type"];
    const bool point = l.type == "point";
    if (v.contains("position")) l.position = readVec3(v["position"]);
    if (v.contains("direction")) l.direction = readVec3(v["direction"]);
    if (v.contains("color")) l.color = readVec3(v["color"]);
    if (v.contains("intensity")) l.intensity = v["intensity"];
    if (point && !v.contains("position"))
        diag_.error(joinKey(path, "position"), "required for a point light");
    if (point && v.contains("direction"))
        diag_.error(joinKey(path, "direction"),
                    "a point light shines in every direction; give only \"position\"");
    if (!point && !v.contains("direction"))
        diag_.error(joinKey(path, "direction"), "required for a directional light");
    if (!point && v.contains("position"))
        diag_.error(joinKey(path, "position"),
                    "a directional light has no position (it is infinitely far); give only \"direction\"");
    if (!point && v.contains("direction") && glm::length(l.direction) == 0.0f)
        diag_.error(joinKey(path, "direction"), "must not be the zero vector");
    return l;
}

}  // namespace shaderlab::lab_spec_detail
