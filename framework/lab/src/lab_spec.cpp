// Turns a lab's lab.json into the typed, validated LabSpec of lab_spec.h.
//
// The work happens in separate steps:
//   1. load      read the file (size-capped), parse the JSON text, report syntax errors with a
//                line and column; refuse duplicate keys (the DOM would silently keep one), very
//                deep nesting and very long strings (both before any recursive code sees them);
//   2. schema    check the DOM against docs/lab.schema.json with a packaged validator
//                (json_schema_check.h): types, allowed values, ranges, names, unknown keys;
//   3. read      expand templates and walk the DOM into a LabSpec (types are known good now);
//   4. validate  what a schema cannot say: unique names, references between passes, targets,
//                attachments, scenes and goals, reads before writes, repeat groups, the disk;
//   5. complete  the defaults that depend on other fields (clears of later writers, the last
//                pass graded, implicit goals, compare modes).
// Every problem is collected as "<origin>: <json path>: <problem>"; steps 3-5 run only on a file
// the schema accepts, so one mistake gives one message rather than a cascade.
//
// It does not load scenes, images or shaders (the renderer does), and knows no lab by name.
#include "shaderlab/lab/lab_spec.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <set>
#include <system_error>
#include <utility>

#include "shaderlab/base/json_messages.h"
#include "shaderlab/lab/json_schema_check.h"
#include "shaderlab/base/paths.h"

namespace shaderlab {

extern const char* const kLabSchemaJson;  // generated from docs/lab.schema.json

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

constexpr std::size_t kMaxLabJsonBytes = std::size_t{1} << 20;
constexpr std::size_t kMaxDepth = 32;
constexpr std::size_t kMaxStringBytes = 4096;
constexpr int kMaxPixels = 4096;
// Bounds on the work one scene may ask for: passes times repeats (cube targets count six).
constexpr long kMaxPassRunsPerScene = 20000;
constexpr long kMaxPassRunsPerLab = 200000;
const char* const kCubeFaces[6] = {"px", "nx", "py", "ny", "pz", "nz"};

std::string passPath(std::size_t i) { return joinIndex("passes", i); }
std::string scenePath(std::size_t i) { return joinIndex("scenes", i); }

class Diagnostics {
  public:
    explicit Diagnostics(std::string origin) : origin_(std::move(origin)) {}
    void error(const std::string& path, const std::string& problem) {
        const std::string line =
            path.empty() ? origin_ + ": " + problem : origin_ + ": " + path + ": " + problem;
        if (std::find(errors_.begin(), errors_.end(), line) == errors_.end()) errors_.push_back(line);
    }
    bool any() const { return !errors_.empty(); }
    std::vector<std::string> take() { return std::move(errors_); }

  private:
    std::string origin_;
    std::vector<std::string> errors_;
};

// =============================================================================================
// Step 1: load

std::string lineColumn(const std::string& text, std::size_t byte) {
    const std::size_t at = std::min(byte == 0 ? 0 : byte - 1, text.size());
    std::size_t line = 1, line_start = 0;
    for (std::size_t i = 0; i < at; ++i) {
        if (text[i] == '\n') {
            ++line;
            line_start = i + 1;
        }
    }
    std::size_t column = 1;
    for (std::size_t i = line_start; i < at; ++i)
        if ((static_cast<unsigned char>(text[i]) & 0xC0) != 0x80) ++column;  // count code points
    return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

std::string syntaxProblem(const std::string& what) {
    const std::size_t at = what.find("parse error");
    if (at != std::string::npos) {
        const std::size_t colon = what.find(": ", at);
        if (colon != std::string::npos) return what.substr(colon + 2);
    }
    const std::size_t bracket = what.find("] ");
    return bracket == std::string::npos ? what : what.substr(bracket + 2);
}

// A SAX pass over the text before the DOM is built: keys repeated within one object (the DOM
// would keep only the last), nesting deeper than kMaxDepth and strings longer than
// kMaxStringBytes (the schema validator and regexes recurse on both).
class PreScan : public nlohmann::json_sax<json> {
  public:
    std::vector<std::pair<std::string, std::string>> problems;  // path, problem

    bool null() override { return scalar(); }
    bool boolean(bool) override { return scalar(); }
    bool number_integer(number_integer_t) override { return scalar(); }
    bool number_unsigned(number_unsigned_t) override { return scalar(); }
    bool number_float(number_float_t, const string_t&) override { return scalar(); }
    bool string(string_t& s) override {
        if (s.size() > kMaxStringBytes)
            problems.emplace_back(pathHere(), "a string of " + std::to_string(s.size()) +
                                                  " bytes is longer than the limit of " +
                                                  std::to_string(kMaxStringBytes));
        return scalar();
    }
    bool binary(binary_t&) override { return scalar(); }
    bool start_object(std::size_t) override { return open(true); }
    bool key(string_t& k) override {
        Frame& f = frames_.back();
        if (k.size() > kMaxStringBytes) {
            problems.emplace_back(pathOfTop(), "a key of " + std::to_string(k.size()) + " bytes is too long");
            return false;
        }
        if (!f.keys.insert(k).second)
            problems.emplace_back(joinKey(pathOfTop(), k),
                                  "duplicate key: it appears more than once in this object, and only the "
                                  "last one would count");
        f.key = k;
        return true;
    }
    bool end_object() override { return close(); }
    bool start_array(std::size_t) override { return open(false); }
    bool end_array() override { return close(); }
    bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override {
        return false;
    }

  private:
    struct Frame {
        bool is_object;
        std::set<std::string> keys;
        std::string key;
        std::size_t index = 0;
    };
    bool open(bool is_object) {
        if (frames_.size() >= kMaxDepth) {
            problems.emplace_back(pathOfTop(), "nested deeper than " + std::to_string(kMaxDepth) + " levels");
            return false;  // stop: the DOM must not be built either
        }
        frames_.push_back(Frame{is_object, {}, {}, 0});
        return true;
    }
    std::string pathOfTop() const {
        std::string path;
        for (std::size_t i = 0; i + 1 < frames_.size(); ++i)
            path = frames_[i].is_object ? joinKey(path, frames_[i].key) : joinIndex(path, frames_[i].index);
        return path;
    }
    std::string pathHere() const {
        if (frames_.empty()) return "";
        const Frame& f = frames_.back();
        return f.is_object ? joinKey(pathOfTop(), f.key) : joinIndex(pathOfTop(), f.index);
    }
    bool scalar() {
        if (!frames_.empty() && !frames_.back().is_object) ++frames_.back().index;
        return true;
    }
    bool close() {
        frames_.pop_back();
        return scalar();
    }
    std::vector<Frame> frames_;
};

bool loadJson(const std::string& text, Diagnostics& diag, json& out) {
    if (text.size() > kMaxLabJsonBytes) {
        diag.error("", "is " + std::to_string(text.size()) + " bytes, more than the limit of " +
                           std::to_string(kMaxLabJsonBytes) + " (1 MiB)");
        return false;
    }
    PreScan scan;
    bool syntax_ok = true;
    try {
        syntax_ok = json::sax_parse(text, &scan);
    } catch (const json::exception&) {
        syntax_ok = false;  // reported by the DOM parse below
    }
    for (const auto& [path, problem] : scan.problems) diag.error(path, problem);
    if (!syntax_ok && !scan.problems.empty()) return false;  // stopped for depth: do not build the DOM
    try {
        out = json::parse(text);
    } catch (const json::parse_error& e) {
        diag.error(lineColumn(text, e.byte), syntaxProblem(e.what()));
        return false;
    } catch (const json::exception& e) {
        // e.g. "number overflow parsing '1e999'": find the literal to point at it.
        const std::string what = e.what();
        std::string where;
        const std::size_t open = what.find('\'');
        const std::size_t close = open == std::string::npos ? open : what.find('\'', open + 1);
        if (close != std::string::npos) {
            const std::size_t at = text.find(what.substr(open + 1, close - open - 1));
            if (at != std::string::npos) where = lineColumn(text, at + 1);
        }
        diag.error(where, syntaxProblem(what));
        return false;
    }
    return !diag.any();
}

// =============================================================================================
// Step 2: schema

const json& labSchema() {
    static const json schema = json::parse(kLabSchemaJson);
    return schema;
}

const JsonSchemaChecker& labSchemaChecker() {
    static const JsonSchemaChecker checker(labSchema());
    return checker;
}

// =============================================================================================
// Step 3: read

template <typename E>
E pick(const std::string& s, std::initializer_list<std::pair<const char*, E>> choices) {
    for (const auto& [name, value] : choices)
        if (s == name) return value;
    return choices.begin()->second;  // the schema admits only the names above
}

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

void readThresholds(const json& v, GradingThresholds& t) {
    if (v.contains("psnr_min_db")) t.psnr_min_db = v["psnr_min_db"];
    if (v.contains("ssim_min")) t.ssim_min = v["ssim_min"];
    if (v.contains("flip_mean_max")) t.flip_mean_max = v["flip_mean_max"];
    if (v.contains("mismatch_max")) t.mismatch_max = v["mismatch_max"];
    if (v.contains("pixel_tolerance")) t.pixel_tolerance = v["pixel_tolerance"];
}

// What lab.json says of a pass before defaults that depend on other passes are filled in.
struct PassDraft {
    json dom;                       // the pass after its template was merged in
    std::string template_name;      // "" without extends
    std::string target_ref;         // a target named by string, or "" for an owned target
    std::optional<TargetSpec> own;  // owned target
    std::optional<json> clear_color;
    std::optional<bool> clear_depth, depth_test, depth_write, graded_flag;
    std::vector<std::string> graded_list;
    std::optional<CompareMode> compare;
    std::optional<int> repeat_count;
    std::string repeat_from;
};

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

class Reader {
  public:
    Reader(const json& doc, Diagnostics& diag, LabSpec& spec) : doc_(doc), diag_(diag), spec_(spec) {}

    void run() {
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
                if (goals[i].contains("scenes"))
                    g.scenes = goals[i]["scenes"].get<std::vector<std::string>>();
                if (goals[i].contains("passes"))
                    g.passes = goals[i]["passes"].get<std::vector<std::string>>();
                spec_.goals.push_back(std::move(g));
            }
            if (doc_.contains("grading") && doc_["grading"].contains("points"))
                diag_.error("grading.points",
                            "cannot be given with goals: the lab's points are the sum of its goals' points");
        }
    }

    std::vector<PassDraft>& drafts() { return drafts_; }

  private:
    void readPass(const json& raw, std::size_t i) {
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
                p.primitive =
                    pick<Primitive>(draw["primitive"], {{"points", Primitive::Points},
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
        if (v.contains("compare"))
            d.compare = v["compare"] == "hdr" ? CompareMode::Hdr : CompareMode::Display;
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

    PassInput readInput(const json& v, const std::string& sampler, const std::string& pass_path) {
        PassInput in;
        in.sampler = sampler;
        in.path = joinKey(joinKey(pass_path, "inputs"), sampler);
        auto splitTarget = [&in](const std::string& ref) {
            const std::size_t dot = ref.find('.');
            in.source = InputSource::Target;
            in.target = ref.substr(0, dot);
            in.attachment = dot == std::string::npos ? "" : ref.substr(dot + 1);
        };
        if (v.is_string()) {
            splitTarget(v);
            return in;
        }
        int sources = 0;
        if (v.contains("target")) {
            splitTarget(v["target"]);
            ++sources;
        }
        if (v.contains("texture")) {
            in.source = InputSource::File;
            in.file = v["texture"];
            ++sources;
        }
        if (v.contains("cube")) {
            in.source = InputSource::Cube;
            const json& c = v["cube"];
            if (c.is_string()) {
                const std::string pattern = c;
                const std::size_t at = pattern.find("{face}");
                if (at == std::string::npos)
                    diag_.error(joinKey(in.path, "cube"),
                                "a single path must contain {face} (replaced by px, nx, py, ny, pz, nz)");
                else
                    for (const char* face : kCubeFaces)
                        in.cube_files.push_back(pattern.substr(0, at) + face + pattern.substr(at + 6));
            } else {
                in.cube_files = c.get<std::vector<std::string>>();
            }
            ++sources;
        }
        if (v.contains("generate")) {
            in.source = InputSource::Generated;
            const json& g = v["generate"];
            GeneratedTexture& t = in.generated;
            t.pattern = g["pattern"];
            const json& size = g["size"];
            t.width = size[0];
            t.height = size.size() > 1 ? size[1].get<int>() : 1;
            t.depth = size.size() > 2 ? size[2].get<int>() : 1;
            if (g.contains("colors"))
                for (const json& c : g["colors"]) t.colors.push_back(readVec4(c));
            if (g.contains("cells")) t.cells = g["cells"];
            if (g.contains("seed")) t.seed = g["seed"].get<std::uint32_t>();
            const std::size_t need = t.pattern == "checker"    ? 2
                                     : t.pattern == "gradient" ? 2
                                     : t.pattern == "constant" ? 1
                                                               : 0;
            if (t.colors.empty()) {
                if (t.pattern == "checker" || t.pattern == "gradient")
                    t.colors = {glm::vec4(0, 0, 0, 1), glm::vec4(1)};
                if (t.pattern == "constant") t.colors = {glm::vec4(1)};
            } else if (t.colors.size() < need || (t.pattern == "constant" && t.colors.size() != 1) ||
                       (t.pattern == "checker" && t.colors.size() != 2) || t.pattern == "noise") {
                diag_.error(
                    joinKey(joinKey(in.path, "generate"), "colors"),
                    t.pattern == "noise"
                        ? std::string("noise takes no colours (its values are uniform in [0, 1))")
                    : t.pattern == "gradient" ? std::string("a gradient needs at least two colour stops")
                    : t.pattern == "checker"  ? std::string("a checker takes exactly two colours")
                                              : std::string("a constant texture takes exactly one colour"));
            }
            const double texels = double(t.width) * t.height * t.depth;
            if (texels > 16.0 * 1024 * 1024)
                diag_.error(joinKey(joinKey(in.path, "generate"), "size"),
                            "has " + formatNumber(texels) + " texels; at most 16777216 are allowed");
            ++sources;
        }
        if (sources != 1)
            diag_.error(in.path, sources == 0
                                     ? "give one source: \"target\", \"texture\", \"cube\" or \"generate\""
                                     : "give only one source of \"target\", \"texture\", \"cube\" and "
                                       "\"generate\"");
        if (v.contains("layers") && in.source != InputSource::File)
            diag_.error(joinKey(in.path, "layers"), "only a \"texture\" file can be cut into layers");
        if (v.contains("srgb") && (in.source == InputSource::Target))
            diag_.error(
                joinKey(in.path, "srgb"),
                "applies to files and generated textures; a target's encoding is its format (\"srgb8\")");
        if (v.contains("layers")) in.layers = v["layers"];
        if (v.contains("filter")) in.filter = readFilter(v["filter"]);
        if (v.contains("wrap")) in.wrap = readWrap(v["wrap"]);
        in.srgb = v.value("srgb", false);
        return in;
    }

    void readState(const json& v, const std::string& path, RenderState& s, PassDraft& d) {
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

    void readScene(const json& v, std::size_t i) {
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

    LightSpec readLight(const json& v, const std::string& path) {
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
            diag_.error(
                joinKey(path, "position"),
                "a directional light has no position (it is infinitely far); give only \"direction\"");
        if (!point && v.contains("direction") && glm::length(l.direction) == 0.0f)
            diag_.error(joinKey(path, "direction"), "must not be the zero vector");
        return l;
    }

    const json& doc_;
    Diagnostics& diag_;
    LabSpec& spec_;
    std::vector<PassDraft> drafts_;
};

// =============================================================================================
// Step 4: validate

bool isSharedPath(const std::string& p) { return p.rfind("shared/", 0) == 0; }

class Validator {
  public:
    Validator(LabSpec& spec, std::vector<PassDraft>& drafts, Diagnostics& diag, bool check_disk)
        : spec_(spec), drafts_(drafts), diag_(diag), check_disk_(check_disk) {}

    void run() {
        if (check_disk_) checkId();
        collectTargets();
        resolvePassTargets();
        buildLoops();
        checkInputs();
        checkPassReferences();
        checkGraded();
        checkCameras();
        checkScenes();
        checkGoals();
        checkWork();
        if (check_disk_) checkFiles();
    }

  private:
    void checkId() {
        const std::string folder = fs::path(spec_.lab_dir).filename().string();
        if (spec_.id != folder)
            diag_.error("id", "is " + quoteJson(spec_.id) + " but the lab folder is " + quoteJson(folder) +
                                  "; they must be the same");
    }

    void collectTargets() {
        std::map<std::string, std::string> where;  // target name -> path
        for (const TargetSpec& t : spec_.targets) where[t.name] = t.path;
        for (std::size_t i = 0; i < spec_.passes.size(); ++i) {
            if (!drafts_[i].own) continue;
            TargetSpec& t = *drafts_[i].own;
            const auto it = where.find(t.name);
            if (it != where.end()) {
                diag_.error(t.path,
                            "declares target " + quoteJson(t.name) + ", which " + it->second +
                                " already declares; to draw into it, write \"target\": " + quoteJson(t.name));
                continue;
            }
            where[t.name] = t.path;
            spec_.targets.push_back(t);
        }
        for (TargetSpec& t : spec_.targets) {
            if (t.width == 0) {
                t.width = static_cast<int>(std::lround(spec_.width * t.scale));
                t.height = static_cast<int>(std::lround(spec_.height * t.scale));
                if (t.width < 1 || t.height < 1 || t.width > kMaxPixels || t.height > kMaxPixels)
                    diag_.error(joinKey(t.path, "scale"),
                                "gives a " + std::to_string(t.width) + "x" + std::to_string(t.height) +
                                    " target; each side must be from 1 to 4096 pixels");
            }
            if (t.type == TargetType::Cube && t.width != t.height)
                diag_.error(t.path, "a cube target must be square, got " + std::to_string(t.width) + "x" +
                                        std::to_string(t.height));
            if (t.type == TargetType::Cube && t.depth == DepthMode::Texture)
                diag_.error(joinKey(t.path, "depth"), "a cube target's depth cannot be sampled");
        }
    }

    void resolvePassTargets() {
        std::set<std::string> written;
        for (std::size_t i = 0; i < spec_.passes.size(); ++i) {
            PassSpec& p = spec_.passes[i];
            PassDraft& d = drafts_[i];
            p.target = d.own ? d.own->name : d.target_ref;
            const TargetSpec* t = spec_.findTarget(p.target);
            if (!t) {
                std::vector<std::string> names;
                for (const TargetSpec& x : spec_.targets) names.push_back(x.name);
                diag_.error(joinKey(p.path, "target"),
                            "no target is called " + quoteJson(p.target) + didYouMean(p.target, names));
                continue;
            }
            if (t->type == TargetType::Cube && p.draw == DrawKind::Scene)
                diag_.error(joinKey(p.path, "draw"),
                            "a scene draw cannot render into the cube target " + quoteJson(t->name) +
                                "; use \"fullscreen\" or a draw without a mesh (one per face, u_cube_face)");
            const bool first_writer = written.insert(p.target).second;
            resolveState(p, d, *t, first_writer);
        }
    }

    void resolveState(PassSpec& p, const PassDraft& d, const TargetSpec& t, bool first_writer) {
        const bool fullscreen = p.draw == DrawKind::Fullscreen;
        const bool has_depth = t.depth != DepthMode::None;
        p.state.depth_test = d.depth_test.value_or(!fullscreen && has_depth);
        p.state.depth_write = d.depth_write.value_or(!fullscreen && has_depth);
        p.state.clear_depth = d.clear_depth.value_or(first_writer && has_depth);
        if (!has_depth) {
            const std::string state = joinKey(p.path, "state");
            if (d.depth_test && *d.depth_test)
                diag_.error(joinKey(state, "depth_test"),
                            "target " + quoteJson(t.name) + " has no depth (\"depth\": \"none\")");
            if (d.depth_write && *d.depth_write)
                diag_.error(joinKey(state, "depth_write"),
                            "target " + quoteJson(t.name) + " has no depth (\"depth\": \"none\")");
        }
        const glm::vec4 black(0.0f, 0.0f, 0.0f, 1.0f);
        p.state.clear_colors.assign(t.attachments.size(),
                                    first_writer ? std::optional<glm::vec4>(black) : std::nullopt);
        if (!d.clear_color) return;
        const json& c = *d.clear_color;
        if (c.is_null()) {
            p.state.clear_colors.assign(t.attachments.size(), std::nullopt);
        } else if (c.is_array()) {
            p.state.clear_colors.assign(t.attachments.size(), readVec4(c));
        } else {
            for (const auto& item : c.items()) {
                const auto at = std::find(t.attachments.begin(), t.attachments.end(), item.key());
                if (at == t.attachments.end()) {
                    diag_.error(joinKey(joinKey(joinKey(p.path, "state"), "clear_color"), item.key()),
                                "target " + quoteJson(t.name) + " has no attachment " +
                                    quoteJson(item.key()) + didYouMean(item.key(), t.attachments));
                    continue;
                }
                p.state.clear_colors[static_cast<std::size_t>(at - t.attachments.begin())] =
                    item.value().is_null() ? std::nullopt : std::optional<glm::vec4>(readVec4(item.value()));
            }
        }
    }

    int passIndex(const std::string& name) const {
        for (std::size_t i = 0; i < spec_.passes.size(); ++i)
            if (spec_.passes[i].name == name) return static_cast<int>(i);
        return -1;
    }

    void buildLoops() {
        std::set<std::string> names;
        for (const PassSpec& p : spec_.passes) {
            if (p.name.empty()) continue;
            if (!names.insert(p.name).second)
                diag_.error(joinKey(p.path, "name"), "pass " + quoteJson(p.name) + " is listed twice");
        }
        for (std::size_t i = 0; i < spec_.passes.size(); ++i) {
            const PassDraft& d = drafts_[i];
            if (!d.repeat_count) continue;
            LoopSpec loop;
            loop.last = i;
            loop.first = i;
            loop.count = *d.repeat_count;
            loop.declared_by = spec_.passes[i].name;
            if (!d.repeat_from.empty()) {
                const int j = passIndex(d.repeat_from);
                if (j < 0 || static_cast<std::size_t>(j) > i) {
                    std::vector<std::string> earlier;
                    for (std::size_t k = 0; k <= i; ++k) earlier.push_back(spec_.passes[k].name);
                    diag_.error(
                        joinKey(joinKey(spec_.passes[i].path, "repeat"), "from"),
                        j < 0 ? "no pass is called " + quoteJson(d.repeat_from) +
                                    didYouMean(d.repeat_from, earlier)
                              : quoteJson(d.repeat_from) +
                                    " comes after this pass; \"from\" names the first pass of the group, "
                                    "which ends at this pass");
                } else {
                    loop.first = static_cast<std::size_t>(j);
                }
                // A bad "from" still leaves a repeated pass (alone), so its reads are judged as such.
            }
            bool overlap = false;
            for (std::size_t k = loop.first; k <= loop.last; ++k) {
                if (spec_.passes[k].loop >= 0) {
                    diag_.error(
                        joinKey(spec_.passes[i].path, "repeat"),
                        "overlaps the repeat group of pass " +
                            quoteJson(
                                spec_.loops[static_cast<std::size_t>(spec_.passes[k].loop)].declared_by) +
                            "; repeat groups cannot overlap or nest");
                    overlap = true;
                    break;
                }
            }
            if (overlap) continue;
            for (std::size_t k = loop.first; k <= loop.last; ++k)
                spec_.passes[k].loop = static_cast<int>(spec_.loops.size());
            spec_.loops.push_back(loop);
        }
    }

    void checkInputs() {
        for (std::size_t i = 0; i < spec_.passes.size(); ++i) {
            PassSpec& p = spec_.passes[i];
            std::set<std::string> uniform_names;
            for (const UniformSetting& u : p.uniforms) uniform_names.insert(u.name);
            for (const PassInput& in : p.inputs) {
                if (uniform_names.count(in.sampler))
                    diag_.error(in.path,
                                quoteJson(in.sampler) +
                                    " is both a sampler input and a uniform value of this pass; a sampler "
                                    "gets a texture, not a value");
                if (in.source != InputSource::Target) continue;
                const TargetSpec* t = spec_.findTarget(in.target);
                if (!t) {
                    std::vector<std::string> names;
                    for (const TargetSpec& x : spec_.targets) names.push_back(x.name);
                    diag_.error(in.path,
                                "no target is called " + quoteJson(in.target) + didYouMean(in.target, names));
                    continue;
                }
                if (in.attachment == "depth") {
                    if (in.target == p.target) {
                        diag_.error(in.path,
                                    "reads the depth of the target this pass draws into; depth is not "
                                    "ping-ponged, so draw the depth in an earlier pass");
                        continue;
                    }
                    if (t->depth != DepthMode::Texture)
                        diag_.error(in.path,
                                    "reads the depth of target " + quoteJson(t->name) +
                                        ", which cannot be sampled: give the target \"depth\": \"texture\"");
                } else if (!in.attachment.empty() && std::find(t->attachments.begin(), t->attachments.end(),
                                                               in.attachment) == t->attachments.end()) {
                    diag_.error(in.path, "target " + quoteJson(t->name) + " has no attachment " +
                                             quoteJson(in.attachment) +
                                             didYouMean(in.attachment, t->attachments));
                }
                checkReadOrder(i, in);
            }
        }
    }

    // "@<pass>.view_projection" and the like, anywhere in a uniform value of a pass or a scene:
    // the pass must exist.
    void checkPassReferences() {
        std::vector<std::string> names;
        for (const PassSpec& p : spec_.passes) names.push_back(p.name);
        const auto check = [&](const auto& self, const json& v, const std::string& path) -> void {
            if (v.is_string()) {
                const std::string s = v;
                const std::size_t dot = s.rfind('.');
                if (s.empty() || s[0] != '@' || dot == std::string::npos) return;
                const std::string pass = s.substr(1, dot - 1);
                if (passIndex(pass) < 0)
                    diag_.error(path, "no pass is called " + quoteJson(pass) + didYouMean(pass, names));
            } else if (v.is_array()) {
                for (std::size_t k = 0; k < v.size(); ++k) self(self, v[k], joinIndex(path, k));
            } else if (v.is_object()) {
                for (const auto& item : v.items()) self(self, item.value(), joinKey(path, item.key()));
            }
        };
        for (const PassSpec& p : spec_.passes)
            for (const UniformSetting& u : p.uniforms) check(check, u.value, u.path);
        for (const SceneSpec& s : spec_.scenes)
            for (const UniformSetting& u : s.uniforms) check(check, u.value, u.path);
    }

    // A pass reads what earlier passes wrote. Inside a repeat group a pass may also read what
    // the group writes later (or itself): the previous iteration's result, feedback.
    void checkReadOrder(std::size_t i, const PassInput& in) {
        const PassSpec& p = spec_.passes[i];
        std::vector<std::size_t> writers;
        for (std::size_t j = 0; j < spec_.passes.size(); ++j)
            if (spec_.passes[j].target == in.target) writers.push_back(j);
        if (writers.empty()) {
            diag_.error(in.path, "reads target " + quoteJson(in.target) + ", which no pass draws into");
            return;
        }
        if (writers.front() < i) return;
        if (p.loop >= 0) {
            const LoopSpec& l = spec_.loops[static_cast<std::size_t>(p.loop)];
            for (std::size_t j : writers)
                if (j >= l.first && j <= l.last) return;
        }
        const std::size_t j = writers.front();
        if (j == i)
            diag_.error(in.path,
                        "reads target " + quoteJson(in.target) +
                            ", which this pass draws into and no earlier pass drew: there is nothing "
                            "to read yet, unless the pass is repeated (it then reads the previous "
                            "iteration's result)");
        else
            diag_.error(in.path,
                        "reads target " + quoteJson(in.target) + ", which is first drawn by " + passPath(j) +
                            " (" + quoteJson(spec_.passes[j].name) +
                            ") after this pass: a cycle. A pass reads what earlier passes drew, unless "
                            "both are in one repeat group");
    }

    void checkGraded() {
        for (std::size_t i = 0; i < spec_.passes.size(); ++i) {
            PassSpec& p = spec_.passes[i];
            const PassDraft& d = drafts_[i];
            const bool last = i + 1 == spec_.passes.size();
            // Whether a pass is graded does not depend on its target (only which images are).
            if (last || !d.graded_list.empty() || d.graded_flag.value_or(false)) graded_.push_back(p.name);
            if (last && d.graded_flag && !*d.graded_flag)
                diag_.error(joinKey(p.path, "graded"),
                            "the last pass is the lab's result and is always graded; leave \"graded\" out");
            const TargetSpec* t = spec_.findTarget(p.target);
            if (!t) continue;
            if (!d.graded_list.empty()) {
                for (const std::string& a : d.graded_list) {
                    if (a == "depth") {
                        if (t->depth == DepthMode::None)
                            diag_.error(joinKey(p.path, "graded"),
                                        "target " + quoteJson(t->name) + " has no depth to grade");
                    } else if (std::find(t->attachments.begin(), t->attachments.end(), a) ==
                               t->attachments.end()) {
                        diag_.error(joinKey(p.path, "graded"), "target " + quoteJson(t->name) +
                                                                   " has no attachment " + quoteJson(a) +
                                                                   didYouMean(a, t->attachments));
                    }
                }
                p.graded = d.graded_list;
            } else if (last || d.graded_flag.value_or(false)) {  // "false" on the last pass is an error
                p.graded = t->attachments;
            }
            if (t->type == TargetType::Cube && !p.graded.empty() &&
                std::find(p.graded.begin(), p.graded.end(), "depth") != p.graded.end())
                diag_.error(joinKey(p.path, "graded"), "a cube target's depth cannot be graded");
            p.compare = d.compare.value_or(!p.graded.empty() && isFloatFormat(t->format) && !last
                                               ? CompareMode::Hdr
                                               : CompareMode::Display);
        }
    }

    void checkCameras() {
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
                diag_.error(
                    cam, "\"light\" places the camera at the light; leave \"position\" and \"target\" out");
        };
        for (const PassSpec& p : spec_.passes) check(p.camera, p.path);
        std::set<std::string> seen;
        for (const SceneSpec& s : spec_.scenes)
            if (seen.insert(s.path).second) check(s.camera, s.path.substr(0, s.path.find(".times")));
    }

    void checkScenes() {
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
                diag_.error(joinKey(base, "file"),
                            "is required: a pass draws the scene (\"draw\": \"scene\")");
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

    void checkGoals() {
        const std::vector<std::string>& graded = graded_;
        if (spec_.goals.empty()) {
            // One goal per scene, sharing the lab's points.
            const float share =
                spec_.grading.points / static_cast<float>(std::max<std::size_t>(1, spec_.scenes.size()));
            for (const SceneSpec& s : spec_.scenes) {
                GoalSpec g;
                g.id = s.name;
                g.title = "scene " + s.name;
                g.points = share;
                g.scenes = {s.name};
                g.passes = graded;
                g.implicit = true;
                spec_.goals.push_back(std::move(g));
            }
            return;
        }
        std::set<std::string> ids, covered;
        float total = 0.0f;
        bool references_ok = true;  // else which images the goals check is unknown: no more messages
        for (std::size_t i = 0; i < spec_.goals.size(); ++i) {
            GoalSpec& g = spec_.goals[i];
            const std::string path = joinIndex("goals", i);
            total += g.points;
            if (!ids.insert(g.id).second)
                diag_.error(joinKey(path, "id"), "goal " + quoteJson(g.id) + " is listed twice");
            std::vector<std::string> scenes;
            if (g.scenes.empty()) {
                for (const SceneSpec& s : spec_.scenes) scenes.push_back(s.name);
            } else {
                for (std::size_t k = 0; k < g.scenes.size(); ++k) {
                    const std::string& name = g.scenes[k];
                    bool found = false;
                    for (const SceneSpec& s : spec_.scenes) {
                        if (s.name == name || s.base_name == name) {
                            scenes.push_back(s.name);
                            found = true;
                        }
                    }
                    if (!found) {
                        std::vector<std::string> names;
                        for (const SceneSpec& s : spec_.scenes) names.push_back(s.base_name);
                        diag_.error(joinIndex(joinKey(path, "scenes"), k),
                                    "no scene is called " + quoteJson(name) + didYouMean(name, names));
                        references_ok = false;
                    }
                }
            }
            g.scenes = scenes;
            if (g.passes.empty()) {
                g.passes = graded;
            } else {
                for (std::size_t k = 0; k < g.passes.size(); ++k) {
                    const std::string& name = g.passes[k];
                    if (std::find(graded.begin(), graded.end(), name) == graded.end()) {
                        std::vector<std::string> all;
                        for (const PassSpec& p : spec_.passes) all.push_back(p.name);
                        diag_.error(
                            joinIndex(joinKey(path, "passes"), k),
                            passIndex(name) < 0
                                ? "no pass is called " + quoteJson(name) + didYouMean(name, all)
                                : "pass " + quoteJson(name) +
                                      " is not graded; mark it \"graded\": true to grade a goal on it");
                        references_ok = false;
                    }
                }
            }
            covered.insert(g.scenes.begin(), g.scenes.end());
        }
        spec_.grading.points = total;
        if (!references_ok) return;
        // Every graded image counts toward some goal: otherwise a lab could fail with full marks.
        for (const std::string& pass : graded) {
            std::vector<std::string> unchecked;
            for (const SceneSpec& s : spec_.scenes) {
                const bool checked =
                    std::any_of(spec_.goals.begin(), spec_.goals.end(), [&](const GoalSpec& g) {
                        return std::find(g.scenes.begin(), g.scenes.end(), s.name) != g.scenes.end() &&
                               std::find(g.passes.begin(), g.passes.end(), pass) != g.passes.end();
                    });
                if (!checked && covered.count(s.name)) unchecked.push_back(s.name);
            }
            if (!unchecked.empty()) {
                std::string list;
                for (const std::string& n : unchecked) list += (list.empty() ? "" : ", ") + quoteJson(n);
                diag_.error(spec_.findPass(pass)->path + ".graded",
                            "pass " + quoteJson(pass) + " is graded, but no goal checks it in scene " + list +
                                "; add it to a goal's \"passes\" or stop grading it");
            }
        }
        std::set<std::string> reported;
        for (const SceneSpec& s : spec_.scenes) {
            const std::string base = s.path.substr(0, s.path.find(".times"));
            if (!covered.count(s.name) && reported.insert(base).second)
                diag_.error(base, "scene " + quoteJson(s.base_name) +
                                      " is in no goal's \"scenes\": every graded scene must test some goal");
        }
    }

    void checkWork() {
        long total = 0;
        for (const SceneSpec& s : spec_.scenes) {
            long runs = 0;
            for (std::size_t i = 0; i < spec_.passes.size(); ++i) {
                const PassSpec& p = spec_.passes[i];
                long n = 1;
                if (p.loop >= 0) {
                    const LoopSpec& l = spec_.loops[static_cast<std::size_t>(p.loop)];
                    const auto it = s.repeats.find(l.declared_by);
                    n = it != s.repeats.end() ? it->second : l.count;
                }
                const TargetSpec* t = spec_.findTarget(p.target);
                if (t && t->type == TargetType::Cube) n *= 6;
                runs += n;
            }
            if (runs > kMaxPassRunsPerScene)
                diag_.error(s.path, "runs passes " + std::to_string(runs) + " times for one scene; at most " +
                                        std::to_string(kMaxPassRunsPerScene) +
                                        " are allowed (lower \"repeat\")");
            total += runs;
        }
        if (total <= kMaxPassRunsPerLab) return;
        diag_.error("scenes", "together run passes " + std::to_string(total) + " times; at most " +
                                  std::to_string(kMaxPassRunsPerLab) + " are allowed");
    }

    // A file named in lab.json: a regular file inside the lab folder, or inside labs/shared for
    // shared/... paths.
    void checkFile(const std::string& path, const std::string& file) {
        const bool shared = isSharedPath(file);
        const PathResult r = resolveInside(shared ? spec_.labs_root : spec_.lab_dir, file);
        if (!r.ok) diag_.error(path, r.error);
    }

    void checkFiles() {
        std::error_code ec;
        if (fs::exists(fs::path(spec_.lab_dir) / "shared", ec))
            diag_.error(
                "",
                "the lab folder has a sub-folder \"shared\", which would hide the course's shared folder "
                "(labs/shared/) from its paths; rename it");
        for (const PassSpec& p : spec_.passes) {
            checkFile(joinKey(joinKey(p.path, "program"), "vertex"), p.program.vertex);
            checkFile(joinKey(joinKey(p.path, "program"), "fragment"), p.program.fragment);
            for (const PassInput& in : p.inputs) {
                if (in.source == InputSource::File) checkFile(joinKey(in.path, "texture"), in.file);
                for (std::size_t k = 0; k < in.cube_files.size(); ++k)
                    checkFile(joinIndex(joinKey(in.path, "cube"), k), in.cube_files[k]);
            }
        }
        for (std::size_t k = 0; k < spec_.student_files.size(); ++k) {
            const std::string& f = spec_.student_files[k];
            const std::string path = joinIndex("student_files", k);
            if (isSharedPath(f)) {
                diag_.error(path, "a shared file cannot be a student file (every lab would share one copy)");
                continue;
            }
            checkFile(path, f);
        }
        std::set<std::string> checked;
        for (const SceneSpec& s : spec_.scenes) {
            if (s.file.empty() || !checked.insert(s.path.substr(0, s.path.find(".times"))).second) continue;
            const PathResult r = resolveInside(spec_.labs_root, s.file);
            if (!r.ok) diag_.error(joinKey(s.path.substr(0, s.path.find(".times")), "file"), r.error);
        }
    }

    LabSpec& spec_;
    std::vector<PassDraft>& drafts_;
    Diagnostics& diag_;
    bool check_disk_;
    std::vector<std::string> graded_;  // names of the graded passes, in pass order
};

// =============================================================================================
// Step 5: complete

void complete(LabSpec& spec) {
    if (spec.title.empty()) spec.title = spec.id;
    if (spec.student_files.empty()) {
        for (const PassSpec& p : spec.passes) {
            for (const std::string* f : {&p.program.vertex, &p.program.fragment}) {
                if (isSharedPath(*f)) continue;
                if (std::find(spec.student_files.begin(), spec.student_files.end(), *f) ==
                    spec.student_files.end())
                    spec.student_files.push_back(*f);
            }
        }
    }
}

LabSpecResult parse(const std::string& text, const std::string& origin, const std::string& lab_dir,
                    bool check_disk) {
    LabSpecResult result;
    Diagnostics diag(origin);
    LabSpec& spec = result.spec;
    std::error_code ec;
    fs::path dir = fs::absolute(lab_dir, ec).lexically_normal();
    if (dir.has_filename() == false) dir = dir.parent_path();
    spec.lab_dir = dir.string();
    spec.labs_root = dir.parent_path().string();

    json doc;
    if (!loadJson(text, diag, doc)) {
        result.errors = diag.take();
        return result;
    }
    for (const SchemaProblem& p : labSchemaChecker().check(doc)) diag.error(p.path, p.problem);
    if (diag.any()) {
        result.errors = diag.take();
        return result;
    }
    Reader reader(doc, diag, spec);
    reader.run();
    std::vector<PassDraft>& drafts = reader.drafts();
    Validator validator(spec, drafts, diag, check_disk);
    if (!diag.any()) validator.run();
    if (!diag.any()) complete(spec);
    result.errors = diag.take();
    result.ok = result.errors.empty();
    return result;
}

}  // namespace

bool isFloatFormat(TargetFormat f) { return f == TargetFormat::RGBA16F || f == TargetFormat::RGBA32F; }

GradingThresholds ThresholdOverrides::applyTo(GradingThresholds t) const {
    if (psnr_min_db) t.psnr_min_db = *psnr_min_db;
    if (ssim_min) t.ssim_min = *ssim_min;
    if (flip_mean_max) t.flip_mean_max = *flip_mean_max;
    if (mismatch_max) t.mismatch_max = *mismatch_max;
    if (pixel_tolerance) t.pixel_tolerance = *pixel_tolerance;
    return t;
}

bool CameraOverride::any() const {
    return position || target || up || fov_y_deg || z_near || z_far || projection || height || light;
}

const TargetSpec* LabSpec::findTarget(const std::string& name) const {
    for (const TargetSpec& t : targets)
        if (t.name == name) return &t;
    return nullptr;
}

const PassSpec* LabSpec::findPass(const std::string& name) const {
    for (const PassSpec& p : passes)
        if (p.name == name) return &p;
    return nullptr;
}

const std::string& labSchemaText() {
    static const std::string text = kLabSchemaJson;
    return text;
}

std::string sharedFolder(const std::string& labs_root) { return (fs::path(labs_root) / "shared").string(); }

std::string labFilePath(const LabSpec& spec, const std::string& path) {
    return (fs::path(isSharedPath(path) ? spec.labs_root : spec.lab_dir) / path).string();
}

LabSpecResult parseLabSpec(const std::string& lab_dir) {
    const fs::path file = fs::path(lab_dir) / "lab.json";
    const std::string origin = file.string();
    std::error_code ec;
    if (!fs::is_directory(lab_dir, ec)) {
        LabSpecResult r;
        r.errors.push_back(origin + ": the lab folder " + lab_dir + " does not exist");
        return r;
    }
    const FileText t = readFile(file.string(), kMaxLabJsonBytes);
    if (!t.ok) {
        // readFile names the file itself; the message names it once, as the origin.
        std::string problem = fs::exists(file, ec) ? t.error : "file not found";
        if (problem.rfind(origin + ": ", 0) == 0) problem.erase(0, origin.size() + 2);
        LabSpecResult r;
        r.errors.push_back(origin + ": " + problem);
        return r;
    }
    return parse(t.text, origin, lab_dir, true);
}

LabSpecResult parseLabSpecText(const std::string& json_text, const std::string& origin,
                               const std::string& lab_dir) {
    return parse(json_text, origin, lab_dir, true);
}

}  // namespace shaderlab
