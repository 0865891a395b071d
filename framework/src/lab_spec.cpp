// Turns a lab's lab.json into the typed, validated LabSpec of lab_spec.h.
//
// The work happens in four separate steps, each a group of functions below:
//   1. load      read the file (size-capped), parse the JSON text, report syntax errors with a
//                line and column, and refuse duplicate keys (the DOM would silently keep one);
//   2. read      walk the DOM into a LabSpec, checking what each field can say on its own: its
//                type, allowed values, range, name pattern, and unknown keys (with a suggestion);
//   3. validate  check what depends on several fields or on the disk: unique names, inputs and
//                draw_into referring to earlier passes, files that must exist inside the lab
//                folder or the labs root, the id matching the folder;
//   4. complete  fill the defaults that depend on other fields (title, student files, the last
//                pass graded, the target a draw_into pass shares).
// Every problem is collected (never just the first) as "<origin>: <json path>: <problem>".
//
// It does not load scenes, images or shaders (the renderer does), and knows no lab by name:
// everything lab-specific comes from the JSON. The format is documented in docs/lab-format.md;
// keep the two in step.
#include "shaderlab/lab_spec.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <glm/gtc/type_ptr.hpp>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <system_error>
#include <utility>

#include "shaderlab/paths.h"

namespace shaderlab {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using KeyList = std::vector<std::string>;

constexpr std::size_t kMaxLabJsonBytes = std::size_t{1} << 20;
// Largest target side we accept: far above what a lab needs, small enough that a typo such as
// 25600 fails here instead of as an out-of-memory error in the driver.
constexpr int kMaxPixels = 4096;
// OpenGL 3.3 guarantees 16 texture units to a fragment shader; more inputs could not be bound.
constexpr std::size_t kMaxInputs = 16;
// The renderer passes at most SL_MAX_LIGHTS (4) lights to shaders and would drop the rest.
constexpr std::size_t kMaxLights = 4;
// Uniforms the framework sets itself (docs/student-contract.md). A lab value of the same name
// would be applied after the framework's and silently replace it.
const std::vector<std::string> kFrameworkUniforms = {"u_model",
                                                     "u_view",
                                                     "u_projection",
                                                     "u_model_view",
                                                     "u_model_view_projection",
                                                     "u_normal_matrix",
                                                     "u_camera_position",
                                                     "u_light_count",
                                                     "u_light_position",
                                                     "u_light_color",
                                                     "u_base_color",
                                                     "u_time",
                                                     "u_resolution"};
constexpr std::size_t kMaxQuotedChars = 60;

// =============================================================================================
// Messages and JSON paths

// A string as it would appear in JSON, ASCII-only and shortened, so that odd bytes or very long
// values cannot garble a message.
std::string quote(const std::string& s) {
    std::string q = json(s).dump(-1, ' ', true, json::error_handler_t::replace);
    if (q.size() > kMaxQuotedChars) q = q.substr(0, kMaxQuotedChars - 4) + "...\"";
    return q;
}

std::string formatNumber(double d) {
    std::ostringstream s;
    s << d;
    return s.str();
}

// What a value is, for "expected X, got Y" messages.
std::string describe(const json& v) {
    switch (v.type()) {
        case json::value_t::null:
            return "null";
        case json::value_t::boolean:
            return v.get<bool>() ? "true" : "false";
        case json::value_t::string:
            return quote(v.get<std::string>());
        case json::value_t::array:
            if (v.empty()) return "an empty array";
            return "an array of " + std::to_string(v.size()) + (v.size() == 1 ? " element" : " elements");
        case json::value_t::object:
            return v.empty() ? "an empty object" : "an object";
        default:
            return v.is_number() ? v.dump() : "an unsupported value";
    }
}

// Names of passes, targets, scenes and lab ids: they become file names of output images, so
// they stay within a portable set of characters.
bool isPlainName(const std::string& s) {
    if (s.empty()) return false;
    return std::all_of(s.begin(), s.end(),
                       [](unsigned char c) { return std::isalnum(c) || c == '_' || c == '-'; });
}

std::string joinKey(const std::string& parent, const std::string& key) {
    // Keys that are not plain names (only possible for unknown keys or odd uniform names) are
    // shown quoted so the path stays unambiguous.
    if (!isPlainName(key)) return parent + "[" + quote(key) + "]";
    return parent.empty() ? key : parent + "." + key;
}

std::string joinIndex(const std::string& parent, std::size_t i) {
    return parent + "[" + std::to_string(i) + "]";
}

std::string passPath(std::size_t i) { return joinIndex("passes", i); }
std::string scenePath(std::size_t i) { return joinIndex("scenes", i); }

// Collects "<origin>: <path>: <problem>" lines; an empty path leaves that part out.
class Diagnostics {
  public:
    explicit Diagnostics(std::string origin) : origin_(std::move(origin)) {}
    void error(const std::string& path, const std::string& problem) {
        errors_.push_back(path.empty() ? origin_ + ": " + problem : origin_ + ": " + path + ": " + problem);
    }
    std::vector<std::string> take() { return std::move(errors_); }

  private:
    std::string origin_;
    std::vector<std::string> errors_;
};

std::string lowercase(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

std::size_t editDistance(const std::string& a, const std::string& b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (std::size_t i = 0; i < a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i + 1;
        for (std::size_t j = 0; j < b.size(); ++j) {
            const std::size_t above = row[j + 1];
            row[j + 1] = std::min({above + 1, row[j] + 1, diagonal + (a[i] == b[j] ? 0 : 1)});
            diagonal = above;
        }
    }
    return row[b.size()];
}

// The candidate a mistyped word most likely meant, or "" when none is close: a few edits away
// (more for longer words), or one word a prefix of the other ("fov" for "fov_y_deg").
std::string closestMatch(const std::string& word, const std::vector<std::string>& candidates) {
    const std::string w = lowercase(word);
    const std::size_t allowed = std::max<std::size_t>(1, w.size() / 4 + 1);
    std::string best;
    std::size_t best_distance = std::numeric_limits<std::size_t>::max();
    for (const std::string& candidate : candidates) {
        const std::string c = lowercase(candidate);
        std::size_t d = editDistance(w, c);
        const bool prefix = std::min(w.size(), c.size()) >= 3 && (c.rfind(w, 0) == 0 || w.rfind(c, 0) == 0);
        if (d > allowed && !prefix) continue;
        if (prefix) d = std::min(d, allowed);
        if (d < best_distance) {
            best = candidate;
            best_distance = d;
        }
    }
    return best;
}

std::string didYouMean(const std::string& word, const std::vector<std::string>& candidates) {
    const std::string match = closestMatch(word, candidates);
    return match.empty() ? "" : " (did you mean " + quote(match) + "?)";
}

// =============================================================================================
// Step 1: load: text to JSON DOM

// nlohmann reports a 1-based byte index of the last character it read (n+1 at the end of the
// input); turn it into a line and a column counted in characters (UTF-8 code points).
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
    for (std::size_t i = line_start; i < at; ++i) {
        if ((static_cast<unsigned char>(text[i]) & 0xC0) != 0x80) ++column;  // skip continuation bytes
    }
    return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

// The part of nlohmann's message after its own "[json.exception...] parse error at ...: " prefix.
std::string syntaxProblem(const std::string& what) {
    const std::size_t at = what.find("parse error");
    if (at != std::string::npos) {
        const std::size_t colon = what.find(": ", at);
        if (colon != std::string::npos) return what.substr(colon + 2);
    }
    const std::size_t bracket = what.find("] ");
    return bracket == std::string::npos ? what : what.substr(bracket + 2);
}

// A SAX pass that only looks for keys repeated within one object. The DOM parser keeps the last
// value of a repeated key, which would silently drop, say, the first of two "uniforms" blocks.
class DuplicateKeyFinder : public nlohmann::json_sax<json> {
  public:
    std::vector<std::string> duplicates;  // JSON paths of repeated keys

    bool null() override { return scalar(); }
    bool boolean(bool) override { return scalar(); }
    bool number_integer(number_integer_t) override { return scalar(); }
    bool number_unsigned(number_unsigned_t) override { return scalar(); }
    bool number_float(number_float_t, const string_t&) override { return scalar(); }
    bool string(string_t&) override { return scalar(); }
    bool binary(binary_t&) override { return scalar(); }
    bool start_object(std::size_t) override {
        frames_.push_back(Frame{true, {}, {}, 0});
        return true;
    }
    bool key(string_t& k) override {
        Frame& f = frames_.back();
        if (!f.keys.insert(k).second) duplicates.push_back(joinKey(pathOfTop(), k));
        f.key = k;
        return true;
    }
    bool end_object() override { return endContainer(); }
    bool start_array(std::size_t) override {
        frames_.push_back(Frame{false, {}, {}, 0});
        return true;
    }
    bool end_array() override { return endContainer(); }
    bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override {
        return false;  // the DOM parse already reported it
    }

  private:
    struct Frame {
        bool is_object;
        std::set<std::string> keys;
        std::string key;        // current member, for objects
        std::size_t index = 0;  // current element, for arrays
    };

    // The path of the innermost open container: each enclosing frame contributes the member or
    // element it is currently inside.
    std::string pathOfTop() const {
        std::string path;
        for (std::size_t i = 0; i + 1 < frames_.size(); ++i) {
            path = frames_[i].is_object ? joinKey(path, frames_[i].key) : joinIndex(path, frames_[i].index);
        }
        return path;
    }
    bool scalar() {
        if (!frames_.empty() && !frames_.back().is_object) ++frames_.back().index;
        return true;
    }
    bool endContainer() {
        frames_.pop_back();
        return scalar();  // the finished container is one element of its parent
    }

    std::vector<Frame> frames_;
};

// Parses `text`; false when there is no usable DOM. Duplicate keys are reported but do not stop
// the rest of the checks.
bool loadJson(const std::string& text, Diagnostics& diag, json& out) {
    if (text.size() > kMaxLabJsonBytes) {
        diag.error("", "is " + std::to_string(text.size()) + " bytes, more than the limit of " +
                           std::to_string(kMaxLabJsonBytes) + " (1 MiB)");
        return false;
    }
    try {
        out = json::parse(text);
    } catch (const json::parse_error& e) {
        diag.error(lineColumn(text, e.byte), syntaxProblem(e.what()));
        return false;
    } catch (const json::exception& e) {
        // e.g. "number overflow parsing '1e999'": no position in the exception, so find the
        // quoted literal in the text to point at it.
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
    DuplicateKeyFinder finder;
    json::sax_parse(text, &finder);
    for (const std::string& path : finder.duplicates) {
        diag.error(
            path,
            "duplicate key: it appears more than once in this object, and only the last one would count");
    }
    return true;
}

// =============================================================================================
// Step 2: read: DOM to typed spec, checking each field on its own

// Allowed numeric interval, with its own wording for messages.
struct Range {
    double lo = -std::numeric_limits<double>::infinity();
    double hi = std::numeric_limits<double>::infinity();
    bool lo_open = false, hi_open = false;

    static Range any() { return {}; }
    static Range closed(double l, double h) { return {l, h, false, false}; }
    static Range openClosed(double l, double h) { return {l, h, true, false}; }
    static Range open(double l, double h) { return {l, h, true, true}; }
    static Range above(double l) { return {l, std::numeric_limits<double>::infinity(), true, false}; }
    static Range atLeast(double l) { return {l, std::numeric_limits<double>::infinity(), false, false}; }

    bool contains(double x) const { return (lo_open ? x > lo : x >= lo) && (hi_open ? x < hi : x <= hi); }
    std::string text() const {
        if (std::isinf(hi)) return (lo_open ? "greater than " : "at least ") + formatNumber(lo);
        return std::string("in ") + (lo_open ? "(" : "[") + formatNumber(lo) + ", " + formatNumber(hi) +
               (hi_open ? ")" : "]");
    }
};

template <class E>
using Choices = std::vector<std::pair<const char*, E>>;

const Choices<DrawKind> kDrawKinds = {{"scene", DrawKind::Scene}, {"fullscreen", DrawKind::Fullscreen}};
const Choices<TargetFormat> kFormats = {
    {"rgba8", TargetFormat::RGBA8}, {"rgba16f", TargetFormat::RGBA16F}, {"rgba32f", TargetFormat::RGBA32F}};
const Choices<TextureFilter> kFilters = {{"nearest", TextureFilter::Nearest},
                                         {"linear", TextureFilter::Linear}};
const Choices<TextureWrap> kWraps = {{"clamp", TextureWrap::ClampToEdge},
                                     {"repeat", TextureWrap::Repeat},
                                     {"mirror", TextureWrap::MirroredRepeat}};
const Choices<DepthFunc> kDepthFuncs = {
    {"less", DepthFunc::Less}, {"lequal", DepthFunc::LessEqual}, {"always", DepthFunc::Always}};
const Choices<CullMode> kCullModes = {
    {"back", CullMode::Back}, {"front", CullMode::Front}, {"none", CullMode::None}};
const Choices<PolygonMode> kPolygonModes = {{"fill", PolygonMode::Fill}, {"line", PolygonMode::Line}};
const Choices<BlendMode> kBlendModes = {
    {"none", BlendMode::None}, {"alpha", BlendMode::Alpha}, {"additive", BlendMode::Additive}};
const Choices<std::string> kLightTypes = {{"point", "point"}, {"directional", "directional"}};

const KeyList kTopKeys = {"schema",        "id",     "title",  "resolution",
                          "student_files", "passes", "scenes", "grading"};
const KeyList kPassKeys = {"name",      "program", "draw",     "inputs", "target",
                           "draw_into", "state",   "uniforms", "graded"};
const KeyList kProgramKeys = {"vertex", "fragment"};
const KeyList kInputKeys = {"sampler", "pass", "texture", "filter", "wrap"};
const KeyList kTargetKeys = {"name", "format", "size", "scale", "filter", "wrap"};
const KeyList kStateKeys = {"clear_color", "clear_depth",  "depth_test", "depth_write", "depth_func",
                            "cull",        "polygon_mode", "line_width", "blend"};
const KeyList kSceneKeys = {"name", "file", "camera", "lights", "uniforms", "time"};
const KeyList kCameraKeys = {"position", "target", "up", "fov_y_deg", "near", "far"};
const KeyList kLightKeys = {"type", "position", "direction", "color", "intensity"};
const KeyList kGradingKeys = {"points",        "psnr_min_db",  "ssim_min",
                              "flip_mean_max", "mismatch_max", "pixel_tolerance"};
const KeyList kUniformObjectKeys = {"int", "bool"};

// Typed access to DOM values. Each reader reports what is wrong with the value at `path` and
// returns false, leaving `out` untouched so the spec keeps its default there.
class FieldReader {
  public:
    explicit FieldReader(Diagnostics& diag) : diag_(diag) {}

    void error(const std::string& path, const std::string& problem) { diag_.error(path, problem); }
    void typeError(const std::string& path, const std::string& expected, const json& got) {
        error(path, "expected " + expected + ", got " + describe(got));
    }

    static const json* find(const json& obj, const char* key) {
        const auto it = obj.find(key);
        return it == obj.end() ? nullptr : &*it;
    }

    const json* require(const json& obj, const std::string& path, const char* key) {
        const json* v = find(obj, key);
        if (!v) error(joinKey(path, key), "required field is missing");
        return v;
    }

    // `v` must be an object, and every key must be in `allowed` (catches typos, which would
    // otherwise silently fall back to a default). False only when `v` is not an object at all.
    bool object(const json& v, const std::string& path, const KeyList& allowed) {
        if (!v.is_object()) {
            typeError(path, "an object", v);
            return false;
        }
        for (const auto& item : v.items()) {
            if (std::find(allowed.begin(), allowed.end(), item.key()) != allowed.end()) continue;
            const std::string suggestion = closestMatch(item.key(), allowed);
            if (!suggestion.empty()) {
                error(joinKey(path, item.key()), "unknown key (did you mean " + quote(suggestion) + "?)");
            } else {
                std::string list;
                for (const std::string& k : allowed) list += (list.empty() ? "" : ", ") + k;
                error(joinKey(path, item.key()), "unknown key; allowed here: " + list);
            }
        }
        return true;
    }

    bool array(const json& v, const std::string& path, const std::string& of) {
        if (v.is_array()) return true;
        typeError(path, "an array of " + of, v);
        return false;
    }

    // Strings are never empty in a lab.json: an empty name or path is always a mistake.
    bool string(const json& v, const std::string& path, std::string& out) {
        if (!v.is_string()) {
            typeError(path, "a string", v);
            return false;
        }
        if (v.get_ref<const std::string&>().empty()) {
            error(path, "must not be empty");
            return false;
        }
        out = v.get<std::string>();
        return true;
    }

    bool name(const json& v, const std::string& path, std::string& out) {
        std::string s;
        if (!string(v, path, s)) return false;
        if (!isPlainName(s)) {
            error(path, quote(s) + " is not a valid name: use only letters, digits, '_' and '-'");
            return false;
        }
        out = s;
        return true;
    }

    // A GLSL uniform name (samplers and uniforms).
    bool glslName(const json& v, const std::string& path, std::string& out) {
        std::string s;
        if (!string(v, path, s)) return false;
        const std::string problem = glslNameProblem(s);
        if (!problem.empty()) {
            error(path, problem);
            return false;
        }
        out = s;
        return true;
    }

    static std::string glslNameProblem(const std::string& s) {
        const auto ok_first = [](unsigned char c) { return std::isalpha(c) || c == '_'; };
        const auto ok_rest = [](unsigned char c) { return std::isalnum(c) || c == '_'; };
        if (s.empty() || !ok_first(static_cast<unsigned char>(s[0])) ||
            !std::all_of(s.begin(), s.end(),
                         [&](char c) { return ok_rest(static_cast<unsigned char>(c)); })) {
            return quote(s) +
                   " is not a valid GLSL identifier (letters, digits and '_', not starting with a digit)";
        }
        if (s.rfind("gl_", 0) == 0) return quote(s) + ": names starting with \"gl_\" are reserved by GLSL";
        if (std::find(kFrameworkUniforms.begin(), kFrameworkUniforms.end(), s) != kFrameworkUniforms.end()) {
            return quote(s) + " is set by the framework (docs/student-contract.md); choose another name" +
                   (s == "u_time" ? " (a scene's \"time\" sets u_time)" : "");
        }
        return "";
    }

    bool boolean(const json& v, const std::string& path, bool& out) {
        if (!v.is_boolean()) {
            typeError(path, "true or false", v);
            return false;
        }
        out = v.get<bool>();
        return true;
    }

    // Any JSON number that fits a finite 32-bit float and lies in `range`.
    bool number(const json& v, const std::string& path, float& out, const Range& range = Range::any()) {
        if (!v.is_number()) {
            typeError(path, "a number", v);
            return false;
        }
        const double d = v.get<double>();
        if (!std::isfinite(d) || std::fabs(d) > static_cast<double>(std::numeric_limits<float>::max())) {
            error(path, v.dump() + " is too large for a 32-bit float");
            return false;
        }
        if (!range.contains(d)) {
            error(path, "must be " + range.text() + ", got " + v.dump());
            return false;
        }
        out = static_cast<float>(d);
        return true;
    }

    bool integer(const json& v, const std::string& path, int& out, const Range& range = Range::any()) {
        if (!v.is_number_integer()) {
            typeError(path, "an integer", v);
            return false;
        }
        const bool fits =
            v.is_number_unsigned()
                ? v.get<std::uint64_t>() <= static_cast<std::uint64_t>(std::numeric_limits<int>::max())
                : v.get<std::int64_t>() >= std::numeric_limits<int>::min() &&
                      v.get<std::int64_t>() <= std::numeric_limits<int>::max();
        if (!fits) {
            error(path, v.dump() + " does not fit a 32-bit integer");
            return false;
        }
        const int i = v.get<int>();
        if (!range.contains(i)) {
            error(path, "must be " + range.text() + ", got " + v.dump());
            return false;
        }
        out = i;
        return true;
    }

    // Exactly `count` numbers; writes `out` only when all of them are valid.
    bool numbers(const json& v, const std::string& path, std::size_t count, float* out,
                 const Range& range = Range::any()) {
        if (!v.is_array() || v.size() != count) {
            typeError(path, "an array of " + std::to_string(count) + " numbers", v);
            return false;
        }
        std::vector<float> values(count);
        bool ok = true;
        for (std::size_t i = 0; i < count; ++i) ok = number(v[i], joinIndex(path, i), values[i], range) && ok;
        if (ok) std::copy(values.begin(), values.end(), out);
        return ok;
    }

    bool vec3(const json& v, const std::string& path, glm::vec3& out, const Range& range = Range::any()) {
        return numbers(v, path, 3, glm::value_ptr(out), range);
    }

    template <class E>
    bool choice(const json& v, const std::string& path, const Choices<E>& choices, E& out) {
        if (v.is_string()) {
            for (const auto& [text, value] : choices) {
                if (v.get_ref<const std::string&>() == text) {
                    out = value;
                    return true;
                }
            }
        }
        std::string list;
        for (const auto& choice_entry : choices)
            list += (list.empty() ? "\"" : ", \"") + std::string(choice_entry.first) + "\"";
        error(path, "expected one of " + list + ", got " + describe(v));
        return false;
    }

    // Shorthands for optional fields: read obj[key] when present, keep the default otherwise.
    void optBool(const json& obj, const std::string& path, const char* key, bool& out) {
        if (const json* v = find(obj, key)) boolean(*v, joinKey(path, key), out);
    }
    void optNumber(const json& obj, const std::string& path, const char* key, float& out,
                   const Range& range = Range::any()) {
        if (const json* v = find(obj, key)) number(*v, joinKey(path, key), out, range);
    }
    template <class E>
    void optChoice(const json& obj, const std::string& path, const char* key, const Choices<E>& choices,
                   E& out) {
        if (const json* v = find(obj, key)) choice(*v, joinKey(path, key), choices, out);
    }
    template <class E>
    void optChoice(const json& obj, const std::string& path, const char* key, const Choices<E>& choices,
                   std::optional<E>& out) {
        E value{};
        if (const json* v = find(obj, key); v && choice(*v, joinKey(path, key), choices, value)) out = value;
    }

  private:
    Diagnostics& diag_;
};

// What the read step saw that the typed spec cannot express (whether a field was written at
// all), needed by the validate and complete steps.
struct ReadNotes {
    bool title_given = false;
    bool student_files_given = false;
    std::vector<std::optional<bool>> graded_given;  // per pass, as written
    std::vector<bool> scene_file_given;             // per scene
};

// [width, height], each a whole number of pixels in [1, 4096].
void readSize(FieldReader& r, const json& v, const std::string& path, int& width, int& height) {
    if (!v.is_array() || v.size() != 2) {
        r.typeError(path, "an array of 2 integers [width, height]", v);
        return;
    }
    int w = 0, h = 0;
    const Range range = Range::closed(1, kMaxPixels);
    const bool ok_w = r.integer(v[0], joinIndex(path, 0), w, range);
    const bool ok_h = r.integer(v[1], joinIndex(path, 1), h, range);
    if (ok_w && ok_h) {
        width = w;
        height = h;
    }
}

void readStringList(FieldReader& r, const json& v, const std::string& path, std::vector<std::string>& out) {
    if (!r.array(v, path, "strings")) return;
    out.assign(v.size(), std::string());
    for (std::size_t i = 0; i < v.size(); ++i) r.string(v[i], joinIndex(path, i), out[i]);
}

bool readUniformValue(FieldReader& r, const json& v, const std::string& path, UniformValue& out) {
    if (v.is_number()) {
        float f = 0.0f;
        if (!r.number(v, path, f)) return false;
        out = f;
        return true;
    }
    if (v.is_array()) {
        const std::size_t n = v.size();
        if (n != 2 && n != 3 && n != 4 && n != 9 && n != 16) {
            r.error(path,
                    "expected 2, 3 or 4 numbers (a vector) or 9 or 16 numbers (a column-major matrix), got " +
                        describe(v));
            return false;
        }
        float a[16] = {};
        if (!r.numbers(v, path, n, a)) return false;
        if (n == 2) out = glm::vec2(a[0], a[1]);
        if (n == 3) out = glm::vec3(a[0], a[1], a[2]);
        if (n == 4) out = glm::vec4(a[0], a[1], a[2], a[3]);
        if (n == 9) {
            glm::mat3 m(1.0f);
            for (int c = 0; c < 3; ++c)
                for (int row = 0; row < 3; ++row) m[c][row] = a[c * 3 + row];
            out = m;
        }
        if (n == 16) {
            glm::mat4 m(1.0f);
            for (int c = 0; c < 4; ++c)
                for (int row = 0; row < 4; ++row) m[c][row] = a[c * 4 + row];
            out = m;
        }
        return true;
    }
    if (v.is_object()) {
        if (!r.object(v, path, kUniformObjectKeys)) return false;
        const json* as_int = FieldReader::find(v, "int");
        const json* as_bool = FieldReader::find(v, "bool");
        if (as_int && as_bool) {
            r.error(path, "give either \"int\" or \"bool\", not both");
            return false;
        }
        if (as_int) {
            int i = 0;
            if (!r.integer(*as_int, joinKey(path, "int"), i)) return false;
            out = i;
            return true;
        }
        if (as_bool) {
            bool b = false;
            if (!r.boolean(*as_bool, joinKey(path, "bool"), b)) return false;
            out = b;
            return true;
        }
        if (v.empty())
            r.error(path, "expected {\"int\": <integer>} or {\"bool\": true|false}, got an empty object");
        return false;  // unknown keys were reported by object()
    }
    r.typeError(path, "a number, an array of 2, 3, 4, 9 or 16 numbers, {\"int\": n} or {\"bool\": b}", v);
    return false;
}

void readUniforms(FieldReader& r, const json& v, const std::string& path, UniformMap& out) {
    if (!v.is_object()) {
        r.typeError(path, "an object of uniform name: value", v);
        return;
    }
    for (const auto& item : v.items()) {
        const std::string at = joinKey(path, item.key());
        const std::string problem = FieldReader::glslNameProblem(item.key());
        if (!problem.empty()) {
            r.error(at, problem);
            continue;
        }
        UniformValue value;
        if (readUniformValue(r, item.value(), at, value)) out[item.key()] = value;
    }
}

void readProgram(FieldReader& r, const json& v, const std::string& path, ProgramSpec& out) {
    if (!r.object(v, path, kProgramKeys)) return;
    if (const json* f = r.require(v, path, "vertex")) r.string(*f, joinKey(path, "vertex"), out.vertex);
    if (const json* f = r.require(v, path, "fragment")) r.string(*f, joinKey(path, "fragment"), out.fragment);
}

void readInput(FieldReader& r, const json& v, const std::string& path, PassInput& out) {
    if (!r.object(v, path, kInputKeys)) return;
    if (const json* f = r.require(v, path, "sampler")) r.glslName(*f, joinKey(path, "sampler"), out.sampler);
    const json* pass = FieldReader::find(v, "pass");
    const json* texture = FieldReader::find(v, "texture");
    if (pass && texture) {
        r.error(path, "give either \"pass\" or \"texture\", not both");
    } else if (!pass && !texture) {
        r.error(path,
                "needs \"pass\" (the target of an earlier pass) or \"texture\" (an image file in the lab "
                "folder)");
    } else if (pass) {
        r.name(*pass, joinKey(path, "pass"), out.from_pass);
    } else {
        r.string(*texture, joinKey(path, "texture"), out.texture_file);
    }
    r.optChoice(v, path, "filter", kFilters, out.filter);
    r.optChoice(v, path, "wrap", kWraps, out.wrap);
}

void readTarget(FieldReader& r, const json& v, const std::string& path, TargetSpec& out) {
    if (!r.object(v, path, kTargetKeys)) return;
    if (const json* f = FieldReader::find(v, "name")) r.name(*f, joinKey(path, "name"), out.name);
    r.optChoice(v, path, "format", kFormats, out.format);
    r.optChoice(v, path, "filter", kFilters, out.filter);
    r.optChoice(v, path, "wrap", kWraps, out.wrap);
    const json* size = FieldReader::find(v, "size");
    const json* scale = FieldReader::find(v, "scale");
    if (size && scale) {
        r.error(joinKey(path, "scale"),
                "cannot be combined with \"size\": give the target either a size in pixels or a scale of the "
                "lab resolution");
    } else if (size) {
        readSize(r, *size, joinKey(path, "size"), out.width, out.height);
    } else if (scale) {
        r.number(*scale, joinKey(path, "scale"), out.scale, Range::openClosed(0, 4));
    }
}

void readState(FieldReader& r, const json& v, const std::string& path, RenderState& out) {
    if (!r.object(v, path, kStateKeys)) return;
    if (const json* f = FieldReader::find(v, "clear_color")) {
        const std::string at = joinKey(path, "clear_color");
        glm::vec4 c(0.0f);
        if (f->is_null()) {
            out.clear_color.reset();
        } else if (!f->is_array()) {
            r.typeError(at, "an array of 4 numbers (RGBA) or null", *f);
        } else if (r.numbers(*f, at, 4, glm::value_ptr(c))) {
            out.clear_color = c;
        }
    }
    r.optBool(v, path, "clear_depth", out.clear_depth);
    r.optBool(v, path, "depth_test", out.depth_test);
    r.optBool(v, path, "depth_write", out.depth_write);
    r.optChoice(v, path, "depth_func", kDepthFuncs, out.depth_func);
    r.optChoice(v, path, "cull", kCullModes, out.cull);
    r.optChoice(v, path, "polygon_mode", kPolygonModes, out.polygon_mode);
    r.optNumber(v, path, "line_width", out.line_width, Range::openClosed(0, 16));
    r.optChoice(v, path, "blend", kBlendModes, out.blend);
}

void readPass(FieldReader& r, const json& v, const std::string& path, PassSpec& out,
              std::optional<bool>& graded) {
    if (!r.object(v, path, kPassKeys)) return;
    if (const json* f = r.require(v, path, "name")) r.name(*f, joinKey(path, "name"), out.name);
    if (const json* f = r.require(v, path, "program"))
        readProgram(r, *f, joinKey(path, "program"), out.program);
    r.optChoice(v, path, "draw", kDrawKinds, out.draw);

    const json* target = FieldReader::find(v, "target");
    const json* draw_into = FieldReader::find(v, "draw_into");
    out.target.name = out.name;  // the default; an explicit "name" below replaces it
    if (target && draw_into) {
        r.error(joinKey(path, "draw_into"),
                "cannot be combined with \"target\": a pass either owns a target or draws into an earlier "
                "pass's");
    } else if (target) {
        readTarget(r, *target, joinKey(path, "target"), out.target);
    } else if (draw_into) {
        r.name(*draw_into, joinKey(path, "draw_into"), out.draw_into);
    }

    // A pass that draws over another pass's image must not wipe it: no clears unless asked for.
    if (draw_into) {
        out.state.clear_color.reset();
        out.state.clear_depth = false;
    }
    if (const json* f = FieldReader::find(v, "state")) readState(r, *f, joinKey(path, "state"), out.state);

    if (const json* f = FieldReader::find(v, "inputs")) {
        const std::string at = joinKey(path, "inputs");
        if (r.array(*f, at, "objects")) {
            if (f->size() > kMaxInputs) {
                r.error(at, "has " + std::to_string(f->size()) + " inputs; at most " +
                                std::to_string(kMaxInputs) + " can be bound at once");
            }
            out.inputs.resize(f->size());
            for (std::size_t i = 0; i < f->size(); ++i)
                readInput(r, (*f)[i], joinIndex(at, i), out.inputs[i]);
        }
    }
    if (const json* f = FieldReader::find(v, "uniforms"))
        readUniforms(r, *f, joinKey(path, "uniforms"), out.uniforms);
    if (const json* f = FieldReader::find(v, "graded")) {
        bool b = false;
        if (r.boolean(*f, joinKey(path, "graded"), b)) {
            out.graded = b;
            graded = b;
        }
    }
}

void readCamera(FieldReader& r, const json& v, const std::string& path, CameraOverride& out) {
    if (!r.object(v, path, kCameraKeys)) return;
    glm::vec3 value(0.0f);
    if (const json* f = FieldReader::find(v, "position"); f && r.vec3(*f, joinKey(path, "position"), value))
        out.position = value;
    if (const json* f = FieldReader::find(v, "target"); f && r.vec3(*f, joinKey(path, "target"), value))
        out.target = value;
    if (const json* f = FieldReader::find(v, "up"); f && r.vec3(*f, joinKey(path, "up"), value)) {
        if (value == glm::vec3(0.0f))
            r.error(joinKey(path, "up"), "must not be the zero vector");
        else
            out.up = value;
    }
    float x = 0.0f;
    if (const json* f = FieldReader::find(v, "fov_y_deg");
        f && r.number(*f, joinKey(path, "fov_y_deg"), x, Range::open(0, 180)))
        out.fov_y_deg = x;
    if (const json* f = FieldReader::find(v, "near");
        f && r.number(*f, joinKey(path, "near"), x, Range::above(0)))
        out.z_near = x;
    if (const json* f = FieldReader::find(v, "far");
        f && r.number(*f, joinKey(path, "far"), x, Range::above(0)))
        out.z_far = x;

    // Relations inside the camera object; a camera that breaks them has no valid view matrix or
    // projection, which would show up much later as a black or NaN image.
    if (out.z_near && out.z_far && *out.z_far <= *out.z_near) {
        r.error(joinKey(path, "far"), "must be greater than near (" + formatNumber(*out.z_near) + "), got " +
                                          formatNumber(*out.z_far));
    }
    if (out.position && out.target) {
        const glm::vec3 dir = *out.target - *out.position;
        if (dir == glm::vec3(0.0f)) {
            r.error(joinKey(path, "target"),
                    "must differ from position: the camera would have no view direction");
        } else if (out.up && glm::length(glm::cross(glm::normalize(dir), glm::normalize(*out.up))) < 1e-4f) {
            r.error(joinKey(path, "up"),
                    "is parallel to the view direction (target - position), so the camera's orientation is "
                    "undefined");
        }
    }
}

void readLight(FieldReader& r, const json& v, const std::string& path, LightSpec& out) {
    if (!r.object(v, path, kLightKeys)) return;
    bool type_ok = false;
    if (const json* f = r.require(v, path, "type"))
        type_ok = r.choice(*f, joinKey(path, "type"), kLightTypes, out.type);
    const json* position = FieldReader::find(v, "position");
    const json* direction = FieldReader::find(v, "direction");
    if (position) r.vec3(*position, joinKey(path, "position"), out.position);
    if (direction) {
        glm::vec3 d(0.0f);
        if (r.vec3(*direction, joinKey(path, "direction"), d)) {
            if (d == glm::vec3(0.0f))
                r.error(joinKey(path, "direction"), "must not be the zero vector");
            else
                out.direction = d;
        }
    }
    if (type_ok && out.type == "point") {
        if (!position) r.error(joinKey(path, "position"), "required for a point light");
        if (direction) {
            r.error(joinKey(path, "direction"),
                    "only applies to directional lights (a point light shines in all directions)");
        }
    } else if (type_ok) {
        if (!direction) r.error(joinKey(path, "direction"), "required for a directional light");
        if (position)
            r.error(joinKey(path, "position"),
                    "only applies to point lights (a directional light has no position)");
    }
    if (const json* f = FieldReader::find(v, "color"))
        r.vec3(*f, joinKey(path, "color"), out.color, Range::atLeast(0));
    r.optNumber(v, path, "intensity", out.intensity, Range::atLeast(0));
}

void readScene(FieldReader& r, const json& v, const std::string& path, SceneSpec& out, bool& file_given) {
    if (!r.object(v, path, kSceneKeys)) return;
    if (const json* f = r.require(v, path, "name")) r.name(*f, joinKey(path, "name"), out.name);
    if (const json* f = FieldReader::find(v, "file")) {
        file_given = true;
        r.string(*f, joinKey(path, "file"), out.file);
    }
    if (const json* f = FieldReader::find(v, "camera"))
        readCamera(r, *f, joinKey(path, "camera"), out.camera);
    if (const json* f = FieldReader::find(v, "lights")) {
        const std::string at = joinKey(path, "lights");
        if (r.array(*f, at, "objects")) {
            if (f->size() > kMaxLights) {
                r.error(at, "has " + std::to_string(f->size()) + " lights; shaders receive at most " +
                                std::to_string(kMaxLights) + " (SL_MAX_LIGHTS)");
            }
            std::vector<LightSpec> lights(f->size());
            for (std::size_t i = 0; i < f->size(); ++i) readLight(r, (*f)[i], joinIndex(at, i), lights[i]);
            out.lights = std::move(lights);
        }
    }
    if (const json* f = FieldReader::find(v, "uniforms"))
        readUniforms(r, *f, joinKey(path, "uniforms"), out.uniforms);
    r.optNumber(v, path, "time", out.time);
}

void readGrading(FieldReader& r, const json& v, const std::string& path, GradingSpec& out) {
    if (!r.object(v, path, kGradingKeys)) return;
    r.optNumber(v, path, "points", out.points, Range::above(0));
    r.optNumber(v, path, "psnr_min_db", out.psnr_min_db, Range::closed(0, 100));
    r.optNumber(v, path, "ssim_min", out.ssim_min, Range::closed(0, 1));
    r.optNumber(v, path, "flip_mean_max", out.flip_mean_max, Range::closed(0, 1));
    r.optNumber(v, path, "mismatch_max", out.mismatch_max, Range::closed(0, 1));
    r.optNumber(v, path, "pixel_tolerance", out.pixel_tolerance, Range::closed(0, 1));
}

void readLab(FieldReader& r, const json& root, LabSpec& spec, ReadNotes& notes) {
    if (!r.object(root, "", kTopKeys)) return;
    if (const json* f = r.require(root, "", "schema")) {
        int schema = 0;
        if (r.integer(*f, "schema", schema)) {
            if (schema != 1)
                r.error("schema",
                        "unsupported version " + std::to_string(schema) + "; this framework reads version 1");
            else
                spec.schema = schema;
        }
    }
    if (const json* f = r.require(root, "", "id")) r.name(*f, "id", spec.id);
    if (const json* f = FieldReader::find(root, "title")) {
        notes.title_given = true;
        r.string(*f, "title", spec.title);
    }
    if (const json* f = FieldReader::find(root, "resolution"))
        readSize(r, *f, "resolution", spec.width, spec.height);
    if (const json* f = FieldReader::find(root, "student_files")) {
        notes.student_files_given = true;
        readStringList(r, *f, "student_files", spec.student_files);
        if (f->is_array() && f->empty()) {
            r.error("student_files",
                    "must list at least one file (leave the field out to use the program files)");
        }
    }
    if (const json* f = r.require(root, "", "passes"); f && r.array(*f, "passes", "objects")) {
        if (f->empty()) r.error("passes", "must list at least one pass");
        spec.passes.resize(f->size());
        notes.graded_given.resize(f->size());
        for (std::size_t i = 0; i < f->size(); ++i) {
            readPass(r, (*f)[i], passPath(i), spec.passes[i], notes.graded_given[i]);
        }
    }
    if (const json* f = r.require(root, "", "scenes"); f && r.array(*f, "scenes", "objects")) {
        if (f->empty()) r.error("scenes", "must list at least one scene (every lab renders once per scene)");
        spec.scenes.resize(f->size());
        notes.scene_file_given.assign(f->size(), false);
        for (std::size_t i = 0; i < f->size(); ++i) {
            bool file_given = false;
            readScene(r, (*f)[i], scenePath(i), spec.scenes[i], file_given);
            notes.scene_file_given[i] = file_given;
        }
    }
    if (const json* f = FieldReader::find(root, "grading")) readGrading(r, *f, "grading", spec.grading);
}

// =============================================================================================
// Step 3: validate: relations between fields, and the files on disk.
// Fields left empty by the read step (missing or invalid, already reported) are skipped here,
// so one mistake yields one message.

// Where the lab lives, derived from the lab_dir argument.
struct LabLocation {
    std::string dir;          // absolute, normalised, no trailing separator
    std::string root;         // its parent: the labs root
    std::string folder_name;  // what the id must equal
    bool exists = false;
};

LabLocation locateLab(const std::string& lab_dir) {
    LabLocation loc;
    if (lab_dir.empty()) return loc;
    std::error_code ec;
    fs::path p = fs::absolute(lab_dir, ec).lexically_normal();
    if (ec) return loc;
    if (!p.has_filename()) p = p.parent_path();  // "labs/01-phong/" normalises with a trailing '/'
    loc.dir = p.string();
    loc.root = p.parent_path().string();
    loc.folder_name = p.filename().string();
    loc.exists = fs::is_directory(p, ec);
    return loc;
}

// Index of the pass named `name`, or -1.
int findPass(const LabSpec& spec, const std::string& name) {
    for (std::size_t i = 0; i < spec.passes.size(); ++i) {
        if (spec.passes[i].name == name) return static_cast<int>(i);
    }
    return -1;
}

// Index of the pass that owns the target named `name` (passes drawing into another own none).
int findTargetOwner(const LabSpec& spec, const std::string& name) {
    for (std::size_t i = 0; i < spec.passes.size(); ++i) {
        const PassSpec& p = spec.passes[i];
        if (p.draw_into.empty() && p.target.name == name) return static_cast<int>(i);
    }
    return -1;
}

// Index of the pass whose target pass `i` renders into: `i` itself when it owns one, else the
// owner reached by following draw_into; -1 when the chain is broken. Every step must go to an
// earlier pass, so the walk always ends.
int renderTargetOwner(const LabSpec& spec, std::size_t i) {
    std::size_t at = i;
    while (!spec.passes[at].draw_into.empty()) {
        const int into = findPass(spec, spec.passes[at].draw_into);
        if (into < 0 || static_cast<std::size_t>(into) >= at) return -1;
        at = static_cast<std::size_t>(into);
    }
    return static_cast<int>(at);
}

std::string passLabel(const LabSpec& spec, int i) {
    const std::string& name = spec.passes[static_cast<std::size_t>(i)].name;
    return passPath(static_cast<std::size_t>(i)) + (name.empty() ? "" : " (" + quote(name) + ")");
}

void validateIdentity(const LabSpec& spec, const LabLocation& loc, Diagnostics& diag) {
    if (spec.id.empty() || loc.folder_name.empty()) return;
    if (spec.id != loc.folder_name) {
        diag.error("id", quote(spec.id) + " does not match the lab folder's name " + quote(loc.folder_name));
    }
}

void validateUniqueNames(const LabSpec& spec, Diagnostics& diag) {
    std::map<std::string, std::size_t> passes, targets, scenes;
    for (std::size_t i = 0; i < spec.passes.size(); ++i) {
        const std::string& name = spec.passes[i].name;
        if (name.empty()) continue;
        const auto [it, fresh] = passes.emplace(name, i);
        if (!fresh)
            diag.error(passPath(i) + ".name",
                       "duplicate pass name " + quote(name) + ", already used by " + passPath(it->second));
    }
    for (std::size_t i = 0; i < spec.passes.size(); ++i) {
        const PassSpec& p = spec.passes[i];
        if (!p.draw_into.empty() || p.target.name.empty()) continue;
        const std::string at = passPath(i) + ".target.name";
        const auto [it, fresh] = targets.emplace(p.target.name, i);
        if (!fresh) {
            diag.error(at, "target name " + quote(p.target.name) + " is already the target of " +
                               passPath(it->second));
            continue;
        }
        // Inputs name targets, and a target's name defaults to its pass's: a target named after
        // a different pass would make {"pass": "x"} ambiguous to the reader.
        const auto other = passes.find(p.target.name);
        if (other != passes.end() && other->second != i) {
            diag.error(at, "target name " + quote(p.target.name) + " is the name of another pass, " +
                               passPath(other->second) + "; inputs would be ambiguous");
        }
    }
    for (std::size_t i = 0; i < spec.scenes.size(); ++i) {
        const std::string& name = spec.scenes[i].name;
        if (name.empty()) continue;
        const auto [it, fresh] = scenes.emplace(name, i);
        if (!fresh)
            diag.error(scenePath(i) + ".name",
                       "duplicate scene name " + quote(name) + ", already used by " + scenePath(it->second));
    }
}

// Why input `name` of pass `i` does not name an earlier target.
std::string badInputReason(const LabSpec& spec, std::size_t i, const std::string& name) {
    const int owner = findTargetOwner(spec, name);
    if (owner == static_cast<int>(i)) {
        return quote(name) + " is this pass's own target; a pass can only read the targets of earlier passes";
    }
    if (owner > static_cast<int>(i)) {
        return quote(name) + " is the target of " + passLabel(spec, owner) +
               ", which runs after this pass; inputs can only read the targets of earlier passes";
    }
    const int pass = findPass(spec, name);
    if (pass >= 0 && !spec.passes[static_cast<std::size_t>(pass)].draw_into.empty()) {
        const int writes_to = renderTargetOwner(spec, static_cast<std::size_t>(pass));
        const std::string into =
            writes_to >= 0
                ? "the target " + quote(spec.passes[static_cast<std::size_t>(writes_to)].target.name)
                : quote(spec.passes[static_cast<std::size_t>(pass)].draw_into);
        return "pass " + quote(name) + " has no target of its own (it draws into " + into +
               "); inputs name targets";
    }
    if (pass >= 0) {
        return "pass " + quote(name) + " names its target " +
               quote(spec.passes[static_cast<std::size_t>(pass)].target.name) +
               "; inputs name targets, so use that";
    }
    std::vector<std::string> earlier;
    for (std::size_t k = 0; k < i; ++k) {
        if (spec.passes[k].draw_into.empty() && !spec.passes[k].target.name.empty())
            earlier.push_back(spec.passes[k].target.name);
    }
    return "no pass has a target named " + quote(name) + didYouMean(name, earlier);
}

void validatePassReferences(const LabSpec& spec, Diagnostics& diag) {
    for (std::size_t i = 0; i < spec.passes.size(); ++i) {
        const PassSpec& pass = spec.passes[i];
        const std::string base = passPath(i);
        for (std::size_t j = 0; j < pass.inputs.size(); ++j) {
            const std::string& name = pass.inputs[j].from_pass;
            if (name.empty()) continue;
            const std::string at = base + ".inputs[" + std::to_string(j) + "].pass";
            const int owner = findTargetOwner(spec, name);
            if (owner < 0 || owner >= static_cast<int>(i)) {
                diag.error(at, badInputReason(spec, i, name));
            } else if (renderTargetOwner(spec, i) == owner) {
                // Sampling the texture being rendered to is undefined behaviour in OpenGL.
                diag.error(at,
                           "reads target " + quote(name) +
                               ", which this pass draws into; a pass cannot sample the image it renders to");
            }
        }
        if (pass.draw_into.empty()) continue;
        const std::string at = base + ".draw_into";
        const int into = findPass(spec, pass.draw_into);
        if (into < 0) {
            std::vector<std::string> earlier;
            for (std::size_t k = 0; k < i; ++k) earlier.push_back(spec.passes[k].name);
            diag.error(at, "no pass is named " + quote(pass.draw_into) + didYouMean(pass.draw_into, earlier));
        } else if (into == static_cast<int>(i)) {
            diag.error(at, "a pass cannot draw into itself");
        } else if (into > static_cast<int>(i)) {
            diag.error(at, passLabel(spec, into) +
                               " runs after this pass; a pass can only draw into an earlier pass's target");
        }
    }
}

// Sampler names within a pass must be distinct and must not also be set as plain uniforms.
void validateSamplers(const LabSpec& spec, Diagnostics& diag) {
    for (std::size_t i = 0; i < spec.passes.size(); ++i) {
        const PassSpec& pass = spec.passes[i];
        std::map<std::string, std::size_t> seen;
        for (std::size_t j = 0; j < pass.inputs.size(); ++j) {
            const std::string& sampler = pass.inputs[j].sampler;
            if (sampler.empty()) continue;
            const std::string at = passPath(i) + ".inputs[" + std::to_string(j) + "].sampler";
            const auto [it, fresh] = seen.emplace(sampler, j);
            if (!fresh) {
                diag.error(at, "sampler " + quote(sampler) + " is already bound by inputs[" +
                                   std::to_string(it->second) + "]");
            } else if (pass.uniforms.count(sampler)) {
                diag.error(at, "sampler " + quote(sampler) + " is also set in this pass's uniforms");
            }
        }
    }
    for (std::size_t s = 0; s < spec.scenes.size(); ++s) {
        for (const auto& entry : spec.scenes[s].uniforms) {
            for (std::size_t i = 0; i < spec.passes.size(); ++i) {
                const auto& inputs = spec.passes[i].inputs;
                const bool is_sampler = std::any_of(inputs.begin(), inputs.end(), [&](const PassInput& in) {
                    return in.sampler == entry.first;
                });
                if (is_sampler) {
                    diag.error(joinKey(scenePath(s) + ".uniforms", entry.first),
                               "is a sampler of " + passLabel(spec, static_cast<int>(i)) +
                                   " and cannot be set as a value");
                    break;
                }
            }
        }
    }
}

// Scaled targets must come out between 1 and 4096 pixels per side at the lab resolution.
void validateTargetSizes(const LabSpec& spec, Diagnostics& diag) {
    for (std::size_t i = 0; i < spec.passes.size(); ++i) {
        const TargetSpec& t = spec.passes[i].target;
        if (!spec.passes[i].draw_into.empty() || t.width > 0) continue;
        const double w = static_cast<double>(t.scale) * spec.width;
        const double h = static_cast<double>(t.scale) * spec.height;
        if (w < 1.0 || h < 1.0 || w > kMaxPixels || h > kMaxPixels) {
            diag.error(passPath(i) + ".target.scale",
                       formatNumber(t.scale) + " of the lab resolution " + std::to_string(spec.width) + "x" +
                           std::to_string(spec.height) + " gives " + formatNumber(w) + "x" + formatNumber(h) +
                           " pixels; each side must be between 1 and " + std::to_string(kMaxPixels));
        }
    }
}

void validateScenes(const LabSpec& spec, const ReadNotes& notes, Diagnostics& diag) {
    int scene_pass = -1;
    for (std::size_t i = 0; i < spec.passes.size() && scene_pass < 0; ++i) {
        if (spec.passes[i].draw == DrawKind::Scene) scene_pass = static_cast<int>(i);
    }
    if (scene_pass < 0) return;  // fullscreen-only labs may list scenes without files
    for (std::size_t s = 0; s < spec.scenes.size(); ++s) {
        if (s < notes.scene_file_given.size() && !notes.scene_file_given[s]) {
            diag.error(scenePath(s) + ".file",
                       "required field is missing: " + passLabel(spec, scene_pass) + " draws the scene");
        }
    }
}

// Empty when `rel` is an acceptable relative path, else the problem. resolveInside() refuses
// escapes too, but naming ".." here gives a clearer message than "resolves outside".
std::string relativePathProblem(const std::string& rel, const std::string& relative_to) {
    const fs::path p(rel);
    if (p.is_absolute()) return quote(rel) + " is an absolute path; give a path relative to " + relative_to;
    for (const fs::path& part : p) {
        if (part == "..") return quote(rel) + " must not contain \"..\"; give a path inside " + relative_to;
    }
    return "";
}

// Checks that `rel` names an existing regular file inside `root`.
void checkFile(const std::string& root, const std::string& rel, const std::string& path,
               const std::string& relative_to, Diagnostics& diag) {
    if (rel.empty()) return;
    const std::string problem = relativePathProblem(rel, relative_to);
    if (!problem.empty()) {
        diag.error(path, problem);
        return;
    }
    const PathResult found = resolveInside(root, rel);
    if (!found.ok) diag.error(path, found.error);
}

void validateFiles(const LabSpec& spec, const ReadNotes& notes, const LabLocation& loc, Diagnostics& diag) {
    if (!loc.exists) return;  // reported once by the caller
    const std::string lab_folder = "the lab folder";
    for (std::size_t i = 0; i < spec.passes.size(); ++i) {
        const PassSpec& pass = spec.passes[i];
        const std::string base = passPath(i);
        checkFile(loc.dir, pass.program.vertex, base + ".program.vertex", lab_folder, diag);
        checkFile(loc.dir, pass.program.fragment, base + ".program.fragment", lab_folder, diag);
        for (std::size_t j = 0; j < pass.inputs.size(); ++j) {
            checkFile(loc.dir, pass.inputs[j].texture_file,
                      base + ".inputs[" + std::to_string(j) + "].texture", lab_folder, diag);
        }
    }
    if (notes.student_files_given) {
        std::map<std::string, std::size_t> seen;
        for (std::size_t i = 0; i < spec.student_files.size(); ++i) {
            const std::string& file = spec.student_files[i];
            if (file.empty()) continue;
            const std::string at = joinIndex("student_files", i);
            const auto [it, fresh] = seen.emplace(fs::path(file).lexically_normal().string(), i);
            if (!fresh) {
                diag.error(at, quote(file) + " is already listed as student_files[" +
                                   std::to_string(it->second) + "]");
                continue;
            }
            checkFile(loc.dir, file, at, lab_folder, diag);
        }
    }
    for (std::size_t s = 0; s < spec.scenes.size(); ++s) {
        const std::string& file = spec.scenes[s].file;
        if (file.empty()) continue;
        const std::string at = scenePath(s) + ".file";
        const std::string ext = lowercase(fs::path(file).extension().string());
        if (ext != ".gltf" && ext != ".glb") {
            diag.error(at, quote(file) + " is not a glTF file (expected a .gltf or .glb extension)");
            continue;
        }
        checkFile(loc.root, file, at, "the labs root", diag);
    }
}

void validateGradedFlag(const LabSpec& spec, const ReadNotes& notes, Diagnostics& diag) {
    if (spec.passes.empty() || notes.graded_given.size() != spec.passes.size()) return;
    const std::optional<bool>& last = notes.graded_given.back();
    if (last && !*last) {
        diag.error(
            passPath(spec.passes.size() - 1) + ".graded",
            "the last pass is always graded (its image is the lab's result); remove \"graded\": false");
    }
}

// =============================================================================================
// Step 4: complete: defaults that depend on other fields

void completeSpec(LabSpec& spec, const ReadNotes& notes) {
    if (!notes.title_given) spec.title = spec.id;
    if (!notes.student_files_given) {
        // The files a submission provides are, unless listed, exactly the shaders the passes use.
        for (const PassSpec& pass : spec.passes) {
            for (const std::string* file : {&pass.program.vertex, &pass.program.fragment}) {
                if (file->empty()) continue;
                if (std::find(spec.student_files.begin(), spec.student_files.end(), *file) ==
                    spec.student_files.end())
                    spec.student_files.push_back(*file);
            }
        }
    }
    if (!spec.passes.empty()) spec.passes.back().graded = true;
    // A pass drawing into another carries a copy of the description of the target it ends up
    // in (following chains), so its size and format are known without following references.
    for (std::size_t i = 0; i < spec.passes.size(); ++i) {
        PassSpec& pass = spec.passes[i];
        if (pass.draw_into.empty()) continue;
        const int owner = renderTargetOwner(spec, i);
        if (owner >= 0 && owner != static_cast<int>(i))
            pass.target = spec.passes[static_cast<std::size_t>(owner)].target;
    }
}

}  // namespace

LabSpecResult parseLabSpecText(const std::string& json_text, const std::string& origin,
                               const std::string& lab_dir) {
    LabSpecResult result;
    Diagnostics diag(origin);
    const LabLocation loc = locateLab(lab_dir);
    result.spec.lab_dir = loc.dir;
    result.spec.labs_root = loc.root;
    if (lab_dir.empty()) {
        diag.error("", "no lab folder given, so file references cannot be checked");
    } else if (!loc.exists) {
        diag.error("", "the lab folder " + lab_dir + " does not exist");
    }

    json root;
    if (loadJson(json_text, diag, root)) {
        FieldReader reader(diag);
        ReadNotes notes;
        readLab(reader, root, result.spec, notes);

        validateIdentity(result.spec, loc, diag);
        validateUniqueNames(result.spec, diag);
        validatePassReferences(result.spec, diag);
        validateSamplers(result.spec, diag);
        validateTargetSizes(result.spec, diag);
        validateScenes(result.spec, notes, diag);
        validateFiles(result.spec, notes, loc, diag);
        validateGradedFlag(result.spec, notes, diag);

        completeSpec(result.spec, notes);
    }
    result.errors = diag.take();
    result.ok = result.errors.empty();
    return result;
}

LabSpecResult parseLabSpec(const std::string& lab_dir) {
    const std::string origin = (fs::path(lab_dir) / "lab.json").string();
    std::error_code ec;
    std::string problem;
    if (!fs::is_directory(lab_dir, ec)) {
        problem = origin + ": file not found (the lab folder " + lab_dir + " does not exist)";
    } else {
        const FileText file = readFile(origin, kMaxLabJsonBytes);
        if (file.ok) return parseLabSpecText(file.text, origin, lab_dir);
        problem = file.error;  // already "<path>: <problem>"
    }
    LabSpecResult result;
    const LabLocation loc = locateLab(lab_dir);
    result.spec.lab_dir = loc.dir;
    result.spec.labs_root = loc.root;
    result.errors.push_back(problem);
    return result;
}

}  // namespace shaderlab
