// The variations of a scene and the candidates they make; see scene_sweep.h.
#include "shaderlab/authoring/scene_sweep.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "shaderlab/base/json_messages.h"
#include "shaderlab/base/paths.h"

namespace shaderlab::authoring::sweep {

namespace {

// The fields of a lab.json scene a sweep may vary (docs/lab-format.md, "Scenes"); "name" is the
// sweep's own.
const std::vector<std::string> kSceneFields = {"file", "camera", "lights",  "uniforms",
                                               "time", "times",  "repeats", "thresholds"};

// Ranges and lists are for people: a few hundred values is already more than the cap allows.
constexpr long kMaxRangeValues = 1000;

struct Segment {
    std::string key;  // empty for an index
    std::size_t index = 0;
};

std::string trim(const std::string& s) {
    const std::size_t a = s.find_first_not_of(" \t\r\n");
    if (a == std::string::npos) return {};
    const std::size_t b = s.find_last_not_of(" \t\r\n");
    return s.substr(a, b - a + 1);
}

bool nameChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

// "lights[0].direction" -> lights, [0], direction; the first segment must be a scene field.
bool splitPath(const std::string& path, std::vector<Segment>* out, std::string* error) {
    std::size_t i = 0;
    const auto fail = [&](const std::string& what) {
        *error = path + ": " + what;
        return false;
    };
    if (path.empty()) return fail("no field named before '='");
    while (i < path.size()) {
        if (path[i] == '[') {
            const std::size_t close = path.find(']', i);
            const std::string digits = close == std::string::npos ? "" : path.substr(i + 1, close - i - 1);
            if (out->empty() || digits.empty() || digits.size() > 3 ||
                !std::all_of(digits.begin(), digits.end(), [](char c) { return std::isdigit(c) != 0; }))
                return fail("expected an index like [0] at character " + std::to_string(i + 1));
            out->push_back({"", static_cast<std::size_t>(std::stoul(digits))});
            i = close + 1;
            continue;
        }
        if (!out->empty()) {
            if (path[i] != '.')
                return fail("expected '.' or '[' at character " + std::to_string(i + 1) + ", got '" +
                            path.substr(i, 1) + "'");
            ++i;
        }
        const std::size_t start = i;
        while (i < path.size() && nameChar(path[i])) ++i;
        if (i == start) return fail("expected a field name at character " + std::to_string(start + 1));
        out->push_back({path.substr(start, i - start), 0});
    }
    const std::string& top = out->front().key;
    if (top == "name") return fail("the sweep names the candidates itself (c00, c01, ...)");
    if (std::find(kSceneFields.begin(), kSceneFields.end(), top) == kSceneFields.end()) {
        std::string fields;
        for (const std::string& f : kSceneFields) fields += (fields.empty() ? "" : ", ") + f;
        return fail("a scene has no field " + quoteJson(top) + didYouMean(top, kSceneFields) + "; it has " +
                    fields);
    }
    return true;
}

std::string pathText(const std::vector<Segment>& segs, std::size_t n) {
    std::string out;
    for (std::size_t k = 0; k < n && k < segs.size(); ++k)
        out += segs[k].key.empty() ? "[" + std::to_string(segs[k].index) + "]"
                                   : (out.empty() ? "" : ".") + segs[k].key;
    return out;
}

// Where `what` first appears in `text` outside brackets, braces and strings; npos if nowhere.
std::size_t findTopLevel(const std::string& text, const std::string& what) {
    int depth = 0;
    bool quoted = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (quoted) {
            if (c == '\\')
                ++i;
            else if (c == '"')
                quoted = false;
            continue;
        }
        if (c == '"') quoted = true;
        if (c == '[' || c == '{') ++depth;
        if (c == ']' || c == '}') --depth;
        if (depth == 0 && text.compare(i, what.size(), what) == 0) return i;
    }
    return std::string::npos;
}

// A number's or a vector's components; false when `v` is neither.
bool numbers(const ojson& v, std::vector<ojson>* out) {
    if (v.is_number()) {
        out->push_back(v);
        return true;
    }
    if (!v.is_array() || v.empty()) return false;
    for (const ojson& c : v) {
        if (!c.is_number()) return false;
        out->push_back(c);
    }
    return true;
}

// Six decimals: 0.1 steps print as 0.3, not 0.30000000000000004.
double rounded(double v) { return std::round(v * 1e6) / 1e6; }

bool parseRange(const std::string& path, const std::string& text, std::size_t dots, std::vector<ojson>* out,
                std::string* error) {
    const std::string from_text = trim(text.substr(0, dots));
    std::string rest = text.substr(dots + 2);
    const std::size_t colon = rest.rfind(':');
    const auto fail = [&](const std::string& what) {
        *error = path + "=" + text + ": " + what;
        return false;
    };
    if (colon == std::string::npos) return fail("a range needs its number of values: A..B:N (e.g. 4..64:4)");
    const std::string to_text = trim(rest.substr(0, colon)), n_text = trim(rest.substr(colon + 1));
    if (n_text.empty() || n_text.size() > 4 ||
        !std::all_of(n_text.begin(), n_text.end(), [](char c) { return std::isdigit(c) != 0; }) ||
        std::stol(n_text) < 2 || std::stol(n_text) > kMaxRangeValues)
        return fail("the number of values after ':' must be a whole number from 2 to " +
                    std::to_string(kMaxRangeValues) + ", got " + quoteJson(n_text));
    const long n = std::stol(n_text);
    const ojson from = ojson::parse(from_text, nullptr, false), to = ojson::parse(to_text, nullptr, false);
    std::vector<ojson> a, b;
    if (from.is_discarded() || !numbers(from, &a))
        return fail("the range's start " + quoteJson(from_text) + " is not a number or an array of numbers");
    if (to.is_discarded() || !numbers(to, &b))
        return fail("the range's end " + quoteJson(to_text) + " is not a number or an array of numbers");
    if (from.is_array() != to.is_array() || a.size() != b.size())
        return fail("the range's ends differ in shape: " + from.dump() + " and " + to.dump());
    for (long k = 0; k < n; ++k) {
        ojson v = ojson::array();
        for (std::size_t c = 0; c < a.size(); ++c) {
            const double x = a[c].get<double>(), y = b[c].get<double>();
            const bool whole = a[c].is_number_integer() && b[c].is_number_integer() &&
                               (b[c].get<long long>() - a[c].get<long long>()) % (n - 1) == 0;
            if (whole)
                v.push_back(a[c].get<long long>() +
                            (b[c].get<long long>() - a[c].get<long long>()) / (n - 1) * k);
            else
                v.push_back(rounded(x + (y - x) * static_cast<double>(k) / static_cast<double>(n - 1)));
        }
        out->push_back(from.is_array() ? v : v[0]);
    }
    return true;
}

}  // namespace

bool parseValues(const std::string& path, const std::string& raw, std::vector<ojson>* out,
                 std::string* error) {
    const std::string text = trim(raw);
    if (text.empty()) {
        *error = path + "=: no values after '='";
        return false;
    }
    const std::size_t dots = findTopLevel(text, "..");
    if (dots != std::string::npos) return parseRange(path, text, dots, out, error);
    std::string rest = text;
    while (true) {
        const std::size_t comma = findTopLevel(rest, ",");
        const std::string item = trim(rest.substr(0, comma));
        if (item.empty()) {
            *error =
                path + "=" + text + ": an empty value in the list (two commas together, or one at an end)";
            return false;
        }
        ojson v = ojson::parse(item, nullptr, false);
        if (v.is_discarded()) {
            // A bare word is a string (a file name); what looks like JSON must be JSON.
            if (std::string("[{\"-0123456789").find(item[0]) != std::string::npos) {
                *error = path + "=" + text + ": " + quoteJson(item) + " is not valid JSON";
                return false;
            }
            v = item;
        }
        out->push_back(std::move(v));
        if (out->size() > static_cast<std::size_t>(kMaxRangeValues)) {
            *error = path + ": more than " + std::to_string(kMaxRangeValues) + " values";
            return false;
        }
        if (comma == std::string::npos) break;
        rest = rest.substr(comma + 1);
    }
    return true;
}

bool parseVary(const std::string& text, Variation* out, std::string* error) {
    const std::size_t eq = text.find('=');
    if (eq == std::string::npos) {
        *error = quoteJson(text) + ": expected PATH=VALUES, e.g. uniforms.u_shininess=4..64:4 or " +
                 "lights[0].direction=[1,-1,0],[0,-1,1]";
        return false;
    }
    out->path = trim(text.substr(0, eq));
    std::vector<Segment> segs;
    if (!splitPath(out->path, &segs, error)) return false;
    return parseValues(out->path, text.substr(eq + 1), &out->values, error);
}

bool setPath(ojson* scene, const std::string& path, const ojson& value, std::string* error) {
    std::vector<Segment> segs;
    if (!splitPath(path, &segs, error)) return false;
    ojson* node = scene;
    for (std::size_t k = 0; k < segs.size(); ++k) {
        const Segment& s = segs[k];
        const bool last = k + 1 == segs.size();
        const std::string here = pathText(segs, k);
        if (!s.key.empty()) {
            if (!node->is_object()) {
                *error = path + ": " + here + " is " + describeJson(*node) + ", not an object";
                return false;
            }
            if (last) {
                if (value.is_null())
                    node->erase(s.key);
                else
                    (*node)[s.key] = value;
                return true;
            }
            if (!node->contains(s.key)) {
                const bool next_is_index = segs[k + 1].key.empty();
                if (next_is_index && (segs[k + 1].index != 0 || k + 2 < segs.size())) {
                    *error =
                        path + ": the base scene has no " + quoteJson(pathText(segs, k + 1)) +
                        (s.key == "lights" && k == 0
                             ? " (it is lit by its glTF file's lights): give it a \"lights\" list in "
                               "lab.json, or vary whole lights, e.g. lights[0]={\"type\": \"directional\", "
                               "\"direction\": [0, -1, 0]}"
                             : ": vary the whole element instead, " + pathText(segs, k + 2) + "=...");
                    return false;
                }
                (*node)[s.key] = next_is_index ? ojson::array() : ojson::object();
            }
            node = &(*node)[s.key];
            continue;
        }
        if (!node->is_array()) {
            *error = path + ": " + here + " is " + describeJson(*node) + ", not an array";
            return false;
        }
        if (s.index < node->size()) {
            if (last) {
                if (value.is_null())
                    node->erase(s.index);
                else
                    (*node)[s.index] = value;
                return true;
            }
            node = &(*node)[s.index];
            continue;
        }
        if (s.index == node->size() && last && !value.is_null()) {
            node->push_back(value);
            return true;
        }
        *error = path + ": " + here + " has " + std::to_string(node->size()) + " element" +
                 (node->size() == 1 ? "" : "s") + ", so [" + std::to_string(s.index) + "] " +
                 (last ? "would leave a gap" : "cannot be changed: vary the whole element to add it");
        return false;
    }
    return true;
}

ojson getPath(const ojson& scene, const std::string& path) {
    std::vector<Segment> segs;
    std::string error;
    if (!splitPath(path, &segs, &error)) return nullptr;
    const ojson* node = &scene;
    for (const Segment& s : segs) {
        if (!s.key.empty()) {
            if (!node->is_object() || !node->contains(s.key)) return nullptr;
            node = &(*node)[s.key];
        } else {
            if (!node->is_array() || s.index >= node->size()) return nullptr;
            node = &(*node)[s.index];
        }
    }
    return *node;
}

std::string compactJson(const ojson& v) {
    if (v.is_object()) {
        if (v.empty()) return "{}";
        std::string out = "{ ";
        bool first = true;
        for (auto it = v.begin(); it != v.end(); ++it) {
            out += (first ? "" : ", ") + ojson(it.key()).dump() + ": " + compactJson(it.value());
            first = false;
        }
        return out + " }";
    }
    if (v.is_array()) {
        std::string out = "[";
        for (std::size_t i = 0; i < v.size(); ++i) out += (i ? ", " : "") + compactJson(v[i]);
        return out + "]";
    }
    return v.dump();
}

namespace {

void readSweepVary(const ojson& vary, const std::string& file, SweepFile* out,
                   std::vector<std::string>* errors) {
    if (!vary.is_object()) {
        errors->push_back(file + ": vary: expected an object of PATH: VALUES, got " + describeJson(vary));
        return;
    }
    for (auto it = vary.begin(); it != vary.end(); ++it) {
        Variation v;
        std::string error;
        if (it.value().is_string()) {
            if (!parseVary(it.key() + "=" + it.value().get<std::string>(), &v, &error))
                errors->push_back(file + ": vary: " + error);
        } else {
            v.path = it.key();
            std::vector<Segment> segs;
            if (!splitPath(v.path, &segs, &error)) {
                errors->push_back(file + ": vary: " + error);
            } else if (it.value().is_array()) {
                v.values.assign(it.value().begin(), it.value().end());
                if (v.values.empty()) errors->push_back(file + ": vary." + v.path + ": an empty list");
            } else {
                v.values.push_back(it.value());
            }
        }
        out->vary.push_back(std::move(v));
    }
}

}  // namespace

bool readSweepFile(const std::string& path, SweepFile* out, std::vector<std::string>* errors) {
    const FileText t = readFile(path, 1u << 20);
    if (!t.ok) {
        errors->push_back(path + ": " + t.error);
        return false;
    }
    const ojson doc = ojson::parse(t.text, nullptr, false);
    if (doc.is_discarded() || !doc.is_object()) {
        errors->push_back(path + ": not a JSON object");
        return false;
    }
    const std::size_t before = errors->size();
    const std::vector<std::string> keys = {"scene", "goals", "mistakes", "vary", "candidates", "about"};
    for (auto it = doc.begin(); it != doc.end(); ++it)
        if (std::find(keys.begin(), keys.end(), it.key()) == keys.end())
            errors->push_back(path + ": " + it.key() + ": unknown key" + didYouMean(it.key(), keys) +
                              "; a sweep file has scene, goals, mistakes, vary, candidates and about");
    if (doc.contains("scene")) {
        if (doc["scene"].is_string())
            out->scene = doc["scene"].get<std::string>();
        else
            errors->push_back(path + ": scene: expected a scene's name, got " + describeJson(doc["scene"]));
    }
    for (const char* key : {"goals", "mistakes"}) {
        if (!doc.contains(key)) continue;
        std::vector<std::string>& names = std::string(key) == "goals" ? out->goals : out->mistakes;
        for (const ojson& g : doc[key].is_array() ? doc[key] : ojson::array({nullptr}))
            if (g.is_string())
                names.push_back(g.get<std::string>());
            else
                errors->push_back(path + ": " + key + ": expected an array of names");
    }
    if (doc.contains("vary")) readSweepVary(doc["vary"], path, out, errors);
    if (doc.contains("candidates")) {
        const ojson& list = doc["candidates"];
        for (std::size_t i = 0; list.is_array() && i < list.size(); ++i) {
            if (!list[i].is_object()) {
                errors->push_back(path + ": candidates[" + std::to_string(i) +
                                  "]: expected a scene object (the fields that differ from the base scene)");
                continue;
            }
            Patch p;
            p.scene = list[i];
            p.label = p.scene.contains("name") && p.scene["name"].is_string()
                          ? p.scene["name"].get<std::string>()
                          : "#" + std::to_string(i + 1);
            p.scene.erase("name");
            out->patches.push_back(std::move(p));
        }
        if (!list.is_array()) errors->push_back(path + ": candidates: expected an array of scene objects");
    }
    return errors->size() == before;
}

bool makeCandidates(const ojson& base, const std::vector<Variation>& vary, const std::vector<Patch>& patches,
                    std::size_t cap, std::vector<Candidate>* out, std::size_t* dropped, std::string* error) {
    // How many, before making any: "5 x 4 = 20".
    unsigned long long combos = vary.empty() ? 0 : 1;
    std::string product;
    for (const Variation& v : vary) {
        combos = std::min<unsigned long long>(combos * v.values.size(), 1ull << 40);
        product += (product.empty() ? "" : " x ") + std::to_string(v.values.size());
    }
    const unsigned long long total = combos + patches.size();
    if (total == 0) {
        *error =
            "nothing to sweep: give --vary PATH=VALUES, or a --sweep file with \"vary\" or \"candidates\"";
        return false;
    }
    if (total > cap) {
        std::string made = vary.empty() ? "" : "the variations make " + product;
        if (vary.size() > 1) made += " = " + std::to_string(combos);
        if (!patches.empty())
            made += (made.empty() ? "the sweep file lists " : " and the sweep file lists ") +
                    std::to_string(patches.size());
        *error = made + " candidates, more than the cap of " + std::to_string(cap) +
                 ": take fewer values (a coarse sweep first, then a finer one around the best), or raise "
                 "the cap with --max-candidates (at most 512; each candidate is drawn once per corpus case)";
        return false;
    }
    std::vector<std::pair<ojson, std::string>> scenes;  // without names, with labels
    ojson plain = base;
    plain.erase("name");
    scenes.emplace_back(plain, "base");
    for (unsigned long long k = 0; k < combos; ++k) {
        ojson scene = plain;
        unsigned long long rest = k;
        std::vector<std::size_t> pick(vary.size());
        for (std::size_t v = vary.size(); v-- > 0;) {
            pick[v] = static_cast<std::size_t>(rest % vary[v].values.size());
            rest /= vary[v].values.size();
        }
        for (std::size_t v = 0; v < vary.size(); ++v)
            if (!setPath(&scene, vary[v].path, vary[v].values[pick[v]], error)) return false;
        scenes.emplace_back(std::move(scene), "");
    }
    for (const Patch& p : patches) {
        ojson scene = plain;
        scene.merge_patch(p.scene);
        scenes.emplace_back(std::move(scene), p.label);
    }
    *dropped = 0;
    std::vector<std::pair<ojson, std::string>> kept;
    for (auto& s : scenes) {
        if (std::any_of(kept.begin(), kept.end(), [&](const auto& k) { return k.first == s.first; })) {
            ++*dropped;
            continue;
        }
        kept.push_back(std::move(s));
    }
    const int width = kept.size() <= 100 ? 2 : 3;
    out->clear();
    for (std::size_t i = 0; i < kept.size(); ++i) {
        Candidate c;
        std::string digits = std::to_string(i);
        c.id =
            "c" +
            std::string(static_cast<std::size_t>(width) - std::min<std::size_t>(digits.size(), width), '0') +
            digits;
        // "name" first, as lab.json writes scenes.
        c.scene = ojson::object({{"name", c.id}});
        for (auto it = kept[i].first.begin(); it != kept[i].first.end(); ++it) c.scene[it.key()] = it.value();
        c.base = i == 0;
        c.label = kept[i].second;
        out->push_back(std::move(c));
    }
    return true;
}

}  // namespace shaderlab::authoring::sweep
