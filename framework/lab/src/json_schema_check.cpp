// JSON Schema validation with valijson, worded for people; see json_schema_check.h.
#include "shaderlab/lab/json_schema_check.h"

#include <algorithm>
#include <cmath>
#include <regex>
#include <set>
#include <valijson/adapters/nlohmann_json_adapter.hpp>
#include <valijson/schema.hpp>
#include <valijson/schema_parser.hpp>
#include <valijson/validation_results.hpp>
#include <valijson/validator.hpp>

#include "shaderlab/base/json_messages.h"

namespace shaderlab {

namespace {

using json = nlohmann::json;
using Nodes = std::vector<const json*>;

bool isWrapper(const std::string& description) {
    for (const char* prefix :
         {"Failed to validate against schema associated with", "Failed to validate item #",
          "Failed to validate against child schema", "Failed to validate against any child",
          "Failed to validate against additional properties schema"})
        if (description.rfind(prefix, 0) == 0) return true;
    return false;
}

bool typeIs(const std::string& type, const json& v) {
    if (type == "object") return v.is_object();
    if (type == "array") return v.is_array();
    if (type == "string") return v.is_string();
    if (type == "number") return v.is_number();
    if (type == "integer") return v.is_number_integer();
    if (type == "boolean") return v.is_boolean();
    if (type == "null") return v.is_null();
    return false;
}

std::string typeWords(const std::string& type) {
    if (type == "object") return "an object";
    if (type == "array") return "an array";
    if (type == "string") return "a string";
    if (type == "number") return "a number";
    if (type == "integer") return "an integer";
    if (type == "boolean") return "true or false";
    return type;
}

std::string listValues(const json& values) {
    std::string out;
    for (std::size_t i = 0; i < values.size(); ++i) {
        if (i) out += i + 1 == values.size() ? " or " : ", ";
        out += values[i].is_string() ? quoteJson(values[i].get<std::string>()) : values[i].dump();
    }
    return out;
}

std::string expectedOf(const json& node, const std::string& fallback) {
    const auto it = node.find("x-expected");
    return it != node.end() && it->is_string() ? it->get<std::string>() : fallback;
}

double numberOf(const json& v) { return v.get<double>(); }

class Explainer {
  public:
    explicit Explainer(const json& schema) : schema_(schema) {}

    const json& resolve(const json& node) const {
        const json* n = &node;
        for (int depth = 0; depth < 32; ++depth) {
            const auto ref = n->find("$ref");
            if (ref == n->end() || !ref->is_string()) return *n;
            const std::string r = ref->get<std::string>();
            if (r.empty() || r[0] != '#') return *n;
            n = &schema_.at(json::json_pointer(r.substr(1)));
        }
        return *n;
    }

    // Whether `node` could describe a value of v's JSON type (ignoring every other keyword).
    bool admitsType(const json& raw, const json& v) const {
        const json& node = resolve(raw);
        if (!node.is_object()) return true;
        if (const auto t = node.find("type"); t != node.end()) {
            if (t->is_string()) return typeIs(t->get<std::string>(), v);
            return std::any_of(t->begin(), t->end(), [&](const json& s) { return typeIs(s, v); });
        }
        if (const auto c = node.find("const"); c != node.end()) return sameKind(*c, v);
        if (const auto e = node.find("enum"); e != node.end())
            return std::any_of(e->begin(), e->end(), [&](const json& x) { return sameKind(x, v); });
        if (const auto a = node.find("allOf"); a != node.end())
            return std::all_of(a->begin(), a->end(), [&](const json& b) { return admitsType(b, v); });
        for (const char* key : {"oneOf", "anyOf"})
            if (const auto o = node.find(key); o != node.end())
                return std::any_of(o->begin(), o->end(), [&](const json& b) { return admitsType(b, v); });
        return true;
    }

    // The nodes that apply to `v`: references followed, allOf flattened, and of each oneOf/anyOf
    // the branches whose type admits v. A oneOf/anyOf with no such branch goes to `unmatched`.
    void applicable(const json& raw, const json& v, Nodes& out, Nodes& unmatched) const {
        const json& node = resolve(raw);
        if (!node.is_object()) return;
        out.push_back(&node);
        if (const auto a = node.find("allOf"); a != node.end())
            for (const json& b : *a) applicable(b, v, out, unmatched);
        for (const char* key : {"oneOf", "anyOf"}) {
            const auto o = node.find(key);
            if (o == node.end()) continue;
            bool any = false;
            for (const json& b : *o) {
                if (!admitsType(b, v)) continue;
                any = true;
                applicable(b, v, out, unmatched);
            }
            if (!any) unmatched.push_back(&node);
        }
    }

    // Nodes describing the member `key` (objects) or element `index` (arrays) of a value
    // described by `nodes`.
    Nodes childNodes(const Nodes& nodes, const json& parent, const std::string& key,
                     std::size_t index) const {
        Nodes out;
        for (const json* n : nodes) {
            if (parent.is_object()) {
                const auto props = n->find("properties");
                if (props != n->end() && props->contains(key)) {
                    out.push_back(&(*props)[key]);
                    continue;
                }
                const auto extra = n->find("additionalProperties");
                if (extra != n->end() && extra->is_object()) out.push_back(&*extra);
            } else if (parent.is_array()) {
                const auto items = n->find("items");
                if (items != n->end() && items->is_object()) out.push_back(&*items);
            }
            (void)index;
        }
        return out;
    }

    // Whether `v` satisfies the simple keywords of `node` (type, const, enum, required): enough
    // for the "not" nodes a schema uses to forbid combinations.
    bool matchesSimply(const json& raw, const json& v) const {
        const json& node = resolve(raw);
        if (!admitsType(node, v)) return false;
        if (const auto c = node.find("const"); c != node.end() && *c != v) return false;
        if (const auto e = node.find("enum");
            e != node.end() && std::find(e->begin(), e->end(), v) == e->end())
            return false;
        if (const auto r = node.find("required"); r != node.end()) {
            if (!v.is_object()) return false;
            for (const json& k : *r)
                if (!v.contains(k.get<std::string>())) return false;
        }
        return true;
    }

    void explain(const Nodes& nodes, const Nodes& unmatched, const json& v, const std::string& path,
                 std::vector<SchemaProblem>& out) const {
        for (const json* n : unmatched)
            out.push_back(
                {path, "expected " + expectedOf(*n, "another kind of value") + ", got " + describeJson(v)});
        if (!unmatched.empty()) return;
        for (const json* n : nodes) local(*n, v, path, out);
    }

  private:
    static bool sameKind(const json& a, const json& b) {
        if (a.is_number() && b.is_number()) return true;
        return a.type() == b.type();
    }

    void add(std::vector<SchemaProblem>& out, const std::string& path, const std::string& problem) const {
        out.push_back({path, problem});
    }

    // The problems of `v` against the keywords of this one node.
    void local(const json& n, const json& v, const std::string& path, std::vector<SchemaProblem>& out) const {
        if (const auto t = n.find("type"); t != n.end()) {
            const bool ok = t->is_string() ? typeIs(t->get<std::string>(), v)
                                           : std::any_of(t->begin(), t->end(),
                                                         [&](const json& s) { return typeIs(s, v); });
            if (!ok) {
                add(out, path,
                    "expected " + expectedOf(n, t->is_string() ? typeWords(*t) : "another kind of value") +
                        ", got " + describeJson(v));
                return;
            }
        }
        if (const auto c = n.find("const"); c != n.end() && *c != v) {
            add(out, path, "expected " + expectedOf(n, c->dump()) + ", got " + describeJson(v));
            return;
        }
        if (const auto e = n.find("enum"); e != n.end() && std::find(e->begin(), e->end(), v) == e->end()) {
            std::string hint;
            if (v.is_string()) {
                std::vector<std::string> names;
                for (const json& x : *e)
                    if (x.is_string()) names.push_back(x);
                hint = didYouMean(v, names);
            }
            add(out, path, "expected one of " + listValues(*e) + ", got " + describeJson(v) + hint);
            return;
        }
        if (v.is_number()) numberRange(n, v, path, out);
        if (v.is_string()) stringRules(n, v, path, out);
        if (v.is_array()) arrayRules(n, v, path, out);
        if (v.is_object()) objectRules(n, v, path, out);
        if (const auto no = n.find("not"); no != n.end() && matchesSimply(*no, v)) {
            const auto m = no->find("x-message");
            const auto m2 = n.find("x-message");
            add(out, path,
                m != no->end()  ? m->get<std::string>()
                : m2 != n.end() ? m2->get<std::string>()
                                : describeJson(v) + " is not allowed here");
        }
    }

    void numberRange(const json& n, const json& v, const std::string& path,
                     std::vector<SchemaProblem>& out) const {
        const double x = numberOf(v);
        const auto lo = n.find("minimum"), xlo = n.find("exclusiveMinimum");
        const auto hi = n.find("maximum"), xhi = n.find("exclusiveMaximum");
        const bool has_lo = lo != n.end() || xlo != n.end(), has_hi = hi != n.end() || xhi != n.end();
        const double low = xlo != n.end() ? numberOf(*xlo) : lo != n.end() ? numberOf(*lo) : 0.0;
        const double high = xhi != n.end() ? numberOf(*xhi) : hi != n.end() ? numberOf(*hi) : 0.0;
        const bool low_ok = !has_lo || (xlo != n.end() ? x > low : x >= low);
        const bool high_ok = !has_hi || (xhi != n.end() ? x < high : x <= high);
        if (low_ok && high_ok) return;
        std::string rule;
        if (has_lo && has_hi) {
            rule = "must be in " + std::string(xlo != n.end() ? "(" : "[") + formatNumber(low) + ", " +
                   formatNumber(high) + (xhi != n.end() ? ")" : "]");
        } else if (has_lo) {
            rule = (xlo != n.end() ? "must be greater than " : "must be at least ") + formatNumber(low);
        } else {
            rule = (xhi != n.end() ? "must be less than " : "must be at most ") + formatNumber(high);
        }
        add(out, path, rule + ", got " + v.dump());
    }

    void stringRules(const json& n, const json& v, const std::string& path,
                     std::vector<SchemaProblem>& out) const {
        const std::string s = v.get<std::string>();
        if (const auto m = n.find("minLength"); m != n.end() && s.size() < m->get<std::size_t>()) {
            add(out, path, "must not be empty");
            return;
        }
        if (const auto m = n.find("maxLength"); m != n.end() && s.size() > m->get<std::size_t>()) {
            add(out, path, "is longer than " + std::to_string(m->get<std::size_t>()) + " characters");
            return;
        }
        if (const auto p = n.find("pattern"); p != n.end()) {
            const std::regex re(p->get<std::string>(), std::regex::ECMAScript);
            if (!std::regex_search(s, re))
                add(out, path,
                    "expected " + expectedOf(n, "text matching " + p->dump()) + ", got " + describeJson(v));
        }
    }

    void arrayRules(const json& n, const json& v, const std::string& path,
                    std::vector<SchemaProblem>& out) const {
        const auto lo = n.find("minItems"), hi = n.find("maxItems");
        const bool too_few = lo != n.end() && v.size() < lo->get<std::size_t>();
        const bool too_many = hi != n.end() && v.size() > hi->get<std::size_t>();
        if (too_few || too_many) {
            if (n.contains("x-expected")) {
                add(out, path, "expected " + expectedOf(n, "") + ", got " + describeJson(v));
            } else if (too_few && lo->get<std::size_t>() == 1) {
                add(out, path, "must not be empty");
            } else {
                add(out, path,
                    too_few ? "must have at least " + std::to_string(lo->get<std::size_t>()) +
                                  " elements, got " + std::to_string(v.size())
                            : "must have at most " + std::to_string(hi->get<std::size_t>()) +
                                  " elements, got " + std::to_string(v.size()));
            }
        }
        if (const auto u = n.find("uniqueItems"); u != n.end() && u->get<bool>()) {
            for (std::size_t i = 0; i < v.size(); ++i)
                for (std::size_t j = i + 1; j < v.size(); ++j)
                    if (v[i] == v[j]) add(out, joinIndex(path, j), describeJson(v[j]) + " is listed twice");
        }
    }

    void objectRules(const json& n, const json& v, const std::string& path,
                     std::vector<SchemaProblem>& out) const {
        if (const auto r = n.find("required"); r != n.end())
            for (const json& k : *r)
                if (!v.contains(k.get<std::string>())) add(out, joinKey(path, k), "is required");
        const auto props = n.find("properties");
        if (const auto extra = n.find("additionalProperties");
            extra != n.end() && extra->is_boolean() && !extra->get<bool>()) {
            std::vector<std::string> known;
            if (props != n.end())
                for (const auto& item : props->items()) known.push_back(item.key());
            for (const auto& item : v.items()) {
                if (std::find(known.begin(), known.end(), item.key()) != known.end()) continue;
                std::string hint = didYouMean(item.key(), known);
                if (hint.empty()) {
                    std::string list;
                    for (const std::string& k : known)
                        if (k[0] != '$') list += (list.empty() ? "" : ", ") + quoteJson(k);
                    hint = " (allowed here: " + list + ")";
                }
                add(out, joinKey(path, item.key()), "unknown key" + hint);
            }
        }
        if (const auto names = n.find("propertyNames"); names != n.end()) {
            for (const auto& item : v.items()) {
                const json key = item.key();
                Nodes nodes, unmatched;
                applicable(*names, key, nodes, unmatched);
                std::vector<SchemaProblem> key_problems;
                explain(nodes, unmatched, key, joinKey(path, item.key()), key_problems);
                for (SchemaProblem& p : key_problems) {
                    if (p.problem.rfind("expected ", 0) == 0)
                        p.problem = "the name must be " + p.problem.substr(9, p.problem.rfind(", got ") - 9);
                    else
                        p.problem = quoteJson(item.key()) + " " + p.problem;
                    out.push_back(std::move(p));
                }
            }
        }
        const auto lo = n.find("minProperties"), hi = n.find("maxProperties");
        if (lo != n.end() && v.size() < lo->get<std::size_t>())
            add(out, path,
                lo->get<std::size_t>() == 1 ? "must not be empty"
                                            : "must have at least " + lo->dump() + " entries");
        if (hi != n.end() && v.size() > hi->get<std::size_t>())
            add(out, path,
                "has " + std::to_string(v.size()) + " entries; at most " + hi->dump() + " are allowed");
    }

    const json& schema_;
};

}  // namespace

struct JsonSchemaChecker::Impl {
    explicit Impl(const json& s) : schema(s), explainer(s) {
        valijson::SchemaParser parser(valijson::SchemaParser::kDraft7);
        valijson::adapters::NlohmannJsonAdapter adapter(schema);
        parser.populateSchema(adapter, compiled);
    }
    const json& schema;
    valijson::Schema compiled;
    Explainer explainer;
};

JsonSchemaChecker::JsonSchemaChecker(const json& schema) : impl_(std::make_unique<Impl>(schema)) {}
JsonSchemaChecker::~JsonSchemaChecker() = default;

std::vector<SchemaProblem> JsonSchemaChecker::check(const json& document) const {
    valijson::Validator validator;
    valijson::ValidationResults results;
    valijson::adapters::NlohmannJsonAdapter adapter(document);
    if (validator.validate(impl_->compiled, adapter, &results)) return {};

    // Each location valijson names, once, in the order it reported them.
    std::vector<std::vector<std::string>> contexts;
    std::vector<std::pair<std::vector<std::string>, std::string>> leaf_errors;
    valijson::ValidationResults::Error error;
    auto addContext = [&contexts](const std::vector<std::string>& context) {
        if (std::find(contexts.begin(), contexts.end(), context) == contexts.end())
            contexts.push_back(context);
    };
    while (results.popError(error)) {
        addContext(error.context);
        // A member whose own value fails without a context of its own (valijson reports a key
        // refused by "propertyNames" only as a failure of the member that holds the object):
        // explain the member too.
        const std::string member = "Failed to validate against schema associated with property name '";
        if (error.description.rfind(member, 0) == 0 && error.description.size() > member.size() + 2) {
            std::vector<std::string> child = error.context;
            const std::size_t close = error.description.rfind('\'');
            child.push_back("[" + error.description.substr(member.size(), close - member.size()) + "]");
            addContext(child);
        }
        if (!isWrapper(error.description)) leaf_errors.emplace_back(error.context, error.description);
    }

    const Explainer& ex = impl_->explainer;
    std::vector<SchemaProblem> problems;
    std::set<std::pair<std::string, std::string>> seen;
    auto keep = [&](const SchemaProblem& p) {
        if (seen.insert({p.path, p.problem}).second) problems.push_back(p);
    };
    // Walks from the document root along a valijson context ("<root>", "[passes]", "[0]", ...),
    // tracking the value and the schema nodes that apply to it.
    auto locate = [&](const std::vector<std::string>& context, const json*& value, Nodes& nodes,
                      Nodes& unmatched, std::string& path) {
        value = &document;
        nodes.clear();
        unmatched.clear();
        ex.applicable(impl_->schema, *value, nodes, unmatched);
        path.clear();
        for (std::size_t i = 1; i < context.size(); ++i) {
            const std::string& step = context[i];
            const std::string key = step.size() >= 2 ? step.substr(1, step.size() - 2) : step;
            const json* child = nullptr;
            std::size_t index = 0;
            if (value->is_object() && value->contains(key)) {
                child = &(*value)[key];
                path = joinKey(path, key);
            } else if (value->is_array() && !key.empty() &&
                       std::all_of(key.begin(), key.end(), [](char c) { return c >= '0' && c <= '9'; })) {
                index = std::stoul(key);
                if (index >= value->size()) return false;
                child = &(*value)[index];
                path = joinIndex(path, index);
            } else {
                return false;
            }
            const Nodes child_nodes = ex.childNodes(nodes, *value, key, index);
            value = child;
            nodes.clear();
            unmatched.clear();
            for (const json* n : child_nodes) ex.applicable(*n, *value, nodes, unmatched);
        }
        return true;
    };
    for (const auto& context : contexts) {
        const json* value = nullptr;
        Nodes nodes, unmatched;
        std::string path;
        if (!locate(context, value, nodes, unmatched, path)) continue;
        std::vector<SchemaProblem> here;
        ex.explain(nodes, unmatched, *value, path, here);
        for (const SchemaProblem& p : here) keep(p);
    }
    if (problems.empty()) {
        // Nothing the explainer understood: valijson's own words, so nothing is lost.
        for (const auto& [context, description] : leaf_errors) {
            const json* value = nullptr;
            Nodes nodes, unmatched;
            std::string path;
            locate(context, value, nodes, unmatched, path);
            keep({path, description});
        }
        if (problems.empty()) keep({"", "does not match the lab.json schema"});
    }
    return problems;
}

}  // namespace shaderlab
