// Step 3 of the lab.json parser: the top level of a lab (resolution, grading, targets, templates,
// goals) and its passes, with their program, draw, target and render state, each pass merged with
// the template it extends; and the small values read the same way everywhere (vectors, filters,
// uniforms, cameras). Inputs and scenes are read in lab_spec_read_inputs.cpp and
// lab_spec_read_scenes.cpp. The schema has checked every type by now; what is left to say here is
// what depends on several fields (a template's missing program, a template with "extends").
// Defaults that depend on other passes are the Validator's (lab_spec_check_*.cpp).
#include <initializer_list>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "lab_spec_steps.h"

namespace shaderlab::lab_spec_detail {

namespace {

template <typename E>
E pick(const std::string& s, std::initializer_list<std::pair<const char*, E>> choices) {
    for (const auto& [name, value] : choices)
        if (s == name) return value;
    return choices.begin()->second;  // the schema admits only the names above
}

}  // namespace

TextureFilter readFilter(const json& v) {
    return pick<TextureFilter>(v, {{"linear", TextureFilter::Linear},
                                   {"nearest", TextureFilter::Nearest},
                                   {"mipmap", TextureFilter::Mipmap}});
}

TextureWrap readWrap(const json& v) {
    return pick<TextureWrap>(v, {{"clamp", TextureWrap::ClampToEdge},
                                 {"repeat", TextureWrap::Repeat},
                                 {"mirror", TextureWrap::MirroredRepeat}});
}

glm::vec3 readVec3(const json& v) { return {v[0].get<float>(), v[1].get<float>(), v[2].get<float>()}; }
glm::vec4 readVec4(const json& v) {
    return {v[0].get<float>(), v[1].get<float>(), v[2].get<float>(), v[3].get<float>()};
}

void readUniforms(const json& v, const std::string& path, UniformList& out) {
    for (const auto& item : v.items()) out.push_back({item.key(), item.value(), joinKey(path, item.key())});
}

void readCamera(const json& v, CameraOverride& c) {
    if (v.contains("position")) c.position = readVec3(v["position"]);
    if (v.contains("target")) c.target = readVec3(v["target"]);
    if (v.contains("up")) c.up = readVec3(v["up"]);
    if (v.contains("fov_y_deg")) c.fov_y_deg = v["fov_y_deg"].get<float>();
    if (v.contains("near")) c.z_near = v["near"].get<float>();
    if (v.contains("far")) c.z_far = v["far"].get<float>();
    if (v.contains("projection"))
        c.projection = v["projection"] == "orthographic" ? Projection::Orthographic : Projection::Perspective;
    if (v.contains("height")) c.height = v["height"].get<float>();
    if (v.contains("light")) c.light = v["light"].get<int>();
}

namespace {

// A pass's target object, or a top-level target.
void readTarget(const json& v, const std::string& path, TargetSpec& t) {
    t.path = path;
    if (v.contains("name")) t.name = v["name"];
    if (v.contains("format"))
        t.format = pick<TargetFormat>(v["format"], {{"rgba32f", TargetFormat::RGBA32F},
                                                    {"rgba8", TargetFormat::RGBA8},
                                                    {"srgb8", TargetFormat::SRGB8},
                                                    {"rgba16f", TargetFormat::RGBA16F}});
    if (v.contains("type")) t.type = v["type"] == "cube" ? TargetType::Cube : TargetType::Texture2D;
    if (v.contains("size")) {
        t.width = v["size"][0];
        t.height = v["size"][1];
    }
    if (v.contains("scale")) t.scale = v["scale"];
    if (v.contains("attachments")) t.attachments = v["attachments"].get<std::vector<std::string>>();
    if (v.contains("depth"))
        t.depth = pick<DepthMode>(
            v["depth"],
            {{"buffer", DepthMode::Buffer}, {"none", DepthMode::None}, {"texture", DepthMode::Texture}});
    if (v.contains("filter")) t.filter = readFilter(v["filter"]);
    if (v.contains("wrap")) t.wrap = readWrap(v["wrap"]);
}

void readThresholds(const json& v, GradingThresholds& t) {
    if (v.contains("psnr_min_db")) t.psnr_min_db = v["psnr_min_db"];
    if (v.contains("ssim_min")) t.ssim_min = v["ssim_min"];
    if (v.contains("flip_mean_max")) t.flip_mean_max = v["flip_mean_max"];
    if (v.contains("mismatch_max")) t.mismatch_max = v["mismatch_max"];
    if (v.contains("pixel_tolerance")) t.pixel_tolerance = v["pixel_tolerance"];
}

// Templates and passes merge member by member one level into the blocks that are maps
// (uniforms, inputs, state, program, camera, thresholds); any other field of the pass replaces
// the template's.
json mergeTemplate(const json& base, const json& pass) {
    json out = base;
    for (const auto& item : pass.items()) {
        static const std::set<std::string> maps = {"uniforms", "inputs", "state",
                                                   "program",  "camera", "thresholds"};
        if (maps.count(item.key()) && out.contains(item.key()) && out[item.key()].is_object() &&
            item.value().is_object()) {
            for (const auto& member : item.value().items()) out[item.key()][member.key()] = member.value();
        } else {
            out[item.key()] = item.value();
        }
    }
    return out;
}

}  // namespace

void Reader::run() {
    spec_.schema = doc_["schema"];
    spec_.id = doc_["id"];
    spec_.title = doc_.value("title", "");
    if (doc_.contains("resolution")) {
        spec_.width = doc_["resolution"][0];
        spec_.height = doc_["resolution"][1];
    }
    if (doc_.contains("student_files"))
        spec_.student_files = doc_["student_files"].get<std::vector<std::string>>();
    if (doc_.contains("grading")) {
        const json& g = doc_["grading"];
        readThresholds(g, spec_.grading.thresholds);
        if (g.contains("points")) spec_.grading.points = g["points"];
        if (g.contains("margin_factor")) spec_.grading.margin_factor = g["margin_factor"];
    }
    if (doc_.contains("targets")) {
        for (const auto& item : doc_["targets"].items()) {
            TargetSpec t;
            readTarget(item.value(), joinKey("targets", item.key()), t);
            if (item.value().contains("name"))
                diag_.error(joinKey(joinKey("targets", item.key()), "name"),
                            "a target under \"targets\" is named by its key; leave \"name\" out");
            t.name = item.key();
            spec_.targets.push_back(std::move(t));
        }
    }
    if (doc_.contains("templates")) {
        for (const auto& item : doc_["templates"].items()) {
            for (const char* key : {"name", "extends", "repeat"}) {
                if (item.value().contains(key))
                    diag_.error(joinKey(joinKey("templates", item.key()), key),
                                std::string("a template cannot have \"") + key +
                                    "\" (it belongs to the passes that extend it)");
            }
        }
    }
    const json& passes = doc_["passes"];
    drafts_.resize(passes.size());
    for (std::size_t i = 0; i < passes.size(); ++i) readPass(passes[i], i);
    const json& scenes = doc_["scenes"];
    for (std::size_t i = 0; i < scenes.size(); ++i) readScene(scenes[i], i);
    if (doc_.contains("goals")) {
        const json& goals = doc_["goals"];
        for (std::size_t i = 0; i < goals.size(); ++i) {
            GoalSpec g;
            g.id = goals[i]["id"];
            g.title = goals[i]["title"];
            g.points = goals[i]["points"];
            if (goals[i].contains("scenes")) g.scenes = goals[i]["scenes"].get<std::vector<std::string>>();
            if (goals[i].contains("passes")) g.passes = goals[i]["passes"].get<std::vector<std::string>>();
            g.pipeline = goals[i].value("pipeline", false);
            if (goals[i].contains("depends_on"))
                g.depends_on = goals[i]["depends_on"].get<std::vector<std::string>>();
            for (const std::string& w : goals[i].value("work", std::vector<std::string>{})) {
                const std::size_t colon = w.find(':');
                g.work.push_back({w.substr(0, colon), colon == std::string::npos ? "" : w.substr(colon + 1)});
            }
            spec_.goals.push_back(std::move(g));
        }
        if (doc_.contains("grading") && doc_["grading"].contains("points"))
            diag_.error("grading.points",
                        "cannot be given with goals: the lab's points are the sum of its goals' points");
    }
}

void Reader::readPass(const json& raw, std::size_t i) {
    const std::string path = passPath(i);
    PassDraft& d = drafts_[i];
    d.dom = raw;
    bool template_found = true;
    if (raw.contains("extends")) {
        d.template_name = raw["extends"];
        const json* templates = doc_.contains("templates") ? &doc_["templates"] : nullptr;
        if (!templates || !templates->contains(d.template_name)) {
            std::vector<std::string> names;
            if (templates)
                for (const auto& item : templates->items()) names.push_back(item.key());
            diag_.error(joinKey(path, "extends"), "no template is called " + quoteJson(d.template_name) +
                                                      didYouMean(d.template_name, names));
            template_found = false;  // what it lacks may be the template's: say nothing of it
        } else {
            d.dom = mergeTemplate((*templates)[d.template_name], raw);
        }
    }
    const json& v = d.dom;
    const std::string from = d.template_name.empty() ? ""
                                                     : " (neither the pass nor its template " +
                                                           quoteJson(d.template_name) + " gives it)";
    PassSpec p;
    p.path = path;
    if (v.contains("name"))
        p.name = v["name"];
    else
        diag_.error(joinKey(path, "name"), "is required");
    if (!v.contains("program")) {
        if (template_found) diag_.error(joinKey(path, "program"), "is required" + from);
    } else {
        for (const char* stage : {"vertex", "fragment"}) {
            if (template_found && !v["program"].contains(stage))
                diag_.error(joinKey(joinKey(path, "program"), stage), "is required" + from);
        }
        p.program.vertex = v["program"].value("vertex", "");
        p.program.fragment = v["program"].value("fragment", "");
    }
    if (v.contains("draw")) {
        const json& draw = v["draw"];
        if (draw.is_string()) {
            p.draw = draw == "fullscreen" ? DrawKind::Fullscreen : DrawKind::Scene;
        } else {
            p.draw = DrawKind::Procedural;
            p.primitive = pick<Primitive>(draw["primitive"], {{"points", Primitive::Points},
                                                              {"lines", Primitive::Lines},
                                                              {"line_strip", Primitive::LineStrip},
                                                              {"triangles", Primitive::Triangles},
                                                              {"triangle_strip", Primitive::TriangleStrip}});
            p.vertex_count = draw["count"];
        }
    }
    if (v.contains("target")) {
        if (v["target"].is_string()) {
            d.target_ref = v["target"];
        } else {
            TargetSpec t;
            readTarget(v["target"], joinKey(path, "target"), t);
            if (t.name.empty()) t.name = p.name;
            d.own = std::move(t);
        }
    } else {
        TargetSpec t;
        t.name = p.name;
        t.path = path;
        d.own = std::move(t);
    }
    if (v.contains("inputs")) {
        for (const auto& item : v["inputs"].items())
            p.inputs.push_back(readInput(item.value(), item.key(), path));
    }
    if (v.contains("state")) readState(v["state"], joinKey(path, "state"), p.state, d);
    if (v.contains("uniforms")) readUniforms(v["uniforms"], joinKey(path, "uniforms"), p.uniforms);
    if (v.contains("camera")) readCamera(v["camera"], p.camera);
    if (v.contains("graded")) {
        if (v["graded"].is_boolean())
            d.graded_flag = v["graded"].get<bool>();
        else
            d.graded_list = v["graded"].get<std::vector<std::string>>();
    }
    if (v.contains("compare")) d.compare = v["compare"] == "hdr" ? CompareMode::Hdr : CompareMode::Display;
    if (v.contains("isolate")) p.isolate = v["isolate"].get<bool>();
    p.thresholds = spec_.grading.thresholds;
    if (v.contains("thresholds")) readThresholds(v["thresholds"], p.thresholds);
    if (v.contains("repeat")) {
        if (v["repeat"].is_number_integer()) {
            d.repeat_count = v["repeat"].get<int>();
        } else {
            d.repeat_count = v["repeat"]["count"].get<int>();
            d.repeat_from = v["repeat"]["from"];
        }
    }
    spec_.passes.push_back(std::move(p));
}

void Reader::readState(const json& v, const std::string& path, RenderState& s, PassDraft& d) {
    (void)path;
    if (v.contains("clear_color")) d.clear_color = v["clear_color"];
    if (v.contains("clear_depth")) d.clear_depth = v["clear_depth"].get<bool>();
    if (v.contains("depth_test")) d.depth_test = v["depth_test"].get<bool>();
    if (v.contains("depth_write")) d.depth_write = v["depth_write"].get<bool>();
    if (v.contains("depth_func"))
        s.depth_func = pick<DepthFunc>(v["depth_func"], {{"less", DepthFunc::Less},
                                                         {"never", DepthFunc::Never},
                                                         {"equal", DepthFunc::Equal},
                                                         {"lequal", DepthFunc::LessEqual},
                                                         {"greater", DepthFunc::Greater},
                                                         {"notequal", DepthFunc::NotEqual},
                                                         {"gequal", DepthFunc::GreaterEqual},
                                                         {"always", DepthFunc::Always}});
    if (v.contains("cull"))
        s.cull = pick<CullMode>(
            v["cull"], {{"back", CullMode::Back}, {"front", CullMode::Front}, {"none", CullMode::None}});
    if (v.contains("polygon_mode"))
        s.polygon_mode = pick<PolygonMode>(
            v["polygon_mode"],
            {{"fill", PolygonMode::Fill}, {"line", PolygonMode::Line}, {"point", PolygonMode::Point}});
    if (v.contains("line_width")) s.line_width = v["line_width"];
    if (v.contains("point_size")) s.point_size = v["point_size"];
    if (v.contains("blend"))
        s.blend = pick<BlendMode>(v["blend"], {{"none", BlendMode::None},
                                               {"alpha", BlendMode::Alpha},
                                               {"additive", BlendMode::Additive},
                                               {"premultiplied", BlendMode::Premultiplied}});
}

}  // namespace shaderlab::lab_spec_detail
