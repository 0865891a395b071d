// cases.json read and checked; see corpus_cases.h.
#include "shaderlab/authoring/corpus_cases.h"

#include <algorithm>
#include <nlohmann/json.hpp>

#include "shaderlab/base/json_messages.h"
#include "shaderlab/base/paths.h"
#include "shaderlab/lab/json_schema_check.h"

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace shaderlab {
extern const char* const kCorpusSchemaJson;  // generated from docs/corpus.schema.json
}

namespace shaderlab::authoring {

const std::string& corpusSchemaText() {
    static const std::string text = kCorpusSchemaJson;
    return text;
}

namespace {

// The checks the schema leaves to the framework, for case `i` read into `k`.
void checkCase(const json& c, const Case& k, const std::string& path, const LabSpec& spec,
               std::vector<std::string>* errors) {
    if (k.kind == "mistake" && k.fails.empty())
        errors->push_back(path + ".fails: a mistake names the goals it must fail (its learning goal)");
    if (k.kind == "broken" && !c.contains("status"))
        errors->push_back(path + ".status: a broken case names the status it must end with");
    if (k.kind == "alternative" && (c.contains("fails") || c.contains("status")))
        errors->push_back(path + ": an alternative must pass; it has no \"fails\" or \"status\"");
    std::vector<std::string> goal_ids;
    for (const GoalSpec& g : spec.goals) goal_ids.push_back(g.id);
    for (const char* key : {"fails", "whole"})
        if (c.contains(key))
            for (const json& g : c[key])
                if (std::find(goal_ids.begin(), goal_ids.end(), g.get<std::string>()) == goal_ids.end())
                    errors->push_back(path + "." + key + ": " + spec.id + " has no goal \"" +
                                      g.get<std::string>() + "\"" +
                                      didYouMean(g.get<std::string>(), goal_ids));
}

// cases.json read and checked against the schema; false (with the problems) when it is not one.
bool readCorpusFile(const fs::path& file, json* doc, std::vector<std::string>* errors) {
    const FileText t = readFile(file.string(), 1u << 20);
    if (!t.ok) {
        errors->push_back(file.string() + ": " + t.error);
        return false;
    }
    *doc = json::parse(t.text, nullptr, false);
    if (doc->is_discarded()) {
        errors->push_back(file.string() + ": not valid JSON");
        return false;
    }
    static const json schema = json::parse(corpusSchemaText());
    static const JsonSchemaChecker checker(schema);
    const std::size_t errors_before = errors->size();
    for (const SchemaProblem& p : checker.check(*doc))
        errors->push_back(file.string() + ": " + (p.path.empty() ? "" : p.path + ": ") + p.problem);
    return errors->size() == errors_before;
}

}  // namespace

bool loadEquivalentMutants(const fs::path& file, std::vector<EquivalentMutant>* out,
                           std::vector<std::string>* errors) {
    json doc;
    if (!readCorpusFile(file, &doc, errors)) return false;
    const std::size_t errors_before = errors->size();
    const json list = doc.value("equivalent_mutants", json::array());
    for (std::size_t i = 0; i < list.size(); ++i) {
        EquivalentMutant m{list[i]["id"], list[i]["reason"]};
        for (const EquivalentMutant& other : *out)
            if (other.id == m.id)
                errors->push_back(file.string() + ": equivalent_mutants[" + std::to_string(i) + "].id: \"" +
                                  m.id + "\" is listed twice");
        out->push_back(std::move(m));
    }
    return errors->size() == errors_before;
}

bool loadCases(const fs::path& file, const LabSpec& spec, std::vector<Case>* out,
               std::vector<std::string>* errors) {
    json doc;
    if (!readCorpusFile(file, &doc, errors)) return false;
    const std::size_t errors_before = errors->size();
    if (doc["lab"] != spec.id)
        errors->push_back(file.string() + ": lab: is " + doc["lab"].dump() + ", not " + spec.id);
    const json& cases = doc["cases"];
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const json& c = cases[i];
        const std::string path = file.string() + ": cases[" + std::to_string(i) + "]";
        Case k;
        k.name = c["name"];
        k.kind = c["kind"];
        k.about = c["about"];
        k.status = c.value("status", k.kind == "mistake"       ? "failed"
                                     : k.kind == "alternative" ? "passed"
                                                               : "");
        if (c.contains("fails")) k.fails = c["fails"].get<std::vector<std::string>>();
        if (c.contains("delete")) k.remove = c["delete"].get<std::vector<std::string>>();
        if (c.contains("whole")) k.whole = c["whole"].get<std::vector<std::string>>();
        if (c.contains("given")) k.given = c["given"].get<std::vector<std::string>>();
        if (c.contains("diagnostic")) k.diagnostic = {{c["diagnostic"]["file"], c["diagnostic"]["line"]}};
        k.timeout_s = c.value("timeout", 0.0);
        checkCase(c, k, path, spec, errors);
        std::error_code ec;
        if (!fs::is_directory(file.parent_path() / k.name, ec) && k.remove.empty())
            errors->push_back(path + ": no folder " + (file.parent_path() / k.name).string());
        for (const Case& other : *out)
            if (other.name == k.name) errors->push_back(path + ".name: \"" + k.name + "\" is listed twice");
        out->push_back(std::move(k));
    }
    return errors->size() == errors_before;
}

bool materialise(const LabSpec& spec, const fs::path& reference_lab, const fs::path& case_dir, const Case& c,
                 const fs::path& submission, std::string* error) {
    std::error_code ec;
    fs::remove_all(submission, ec);
    const fs::path lab = submission / spec.id;
    fs::create_directories(lab, ec);
    for (const std::string& f : spec.student_files) {
        fs::create_directories((lab / f).parent_path(), ec);
        fs::copy_file(reference_lab / f, lab / f, fs::copy_options::overwrite_existing, ec);
        if (ec) {
            *error = (reference_lab / f).string() + ": " + ec.message();
            return false;
        }
    }
    if (fs::is_directory(case_dir, ec)) {
        for (const auto& entry : fs::recursive_directory_iterator(case_dir)) {
            if (!entry.is_regular_file()) continue;
            const fs::path rel = fs::relative(entry.path(), case_dir);
            fs::create_directories((lab / rel).parent_path(), ec);
            fs::copy_file(entry.path(), lab / rel, fs::copy_options::overwrite_existing, ec);
        }
    }
    for (const std::string& f : c.remove) fs::remove(lab / f, ec);
    return true;
}

std::set<std::string> expectedFailures(const LabSpec& spec, const std::vector<std::string>& fails) {
    std::set<std::string> out(fails.begin(), fails.end());
    for (bool grew = true; grew;) {
        grew = false;
        for (const GoalSpec& g : spec.goals)
            if (!out.count(g.id) && std::any_of(g.depends_on.begin(), g.depends_on.end(),
                                                [&](const std::string& d) { return out.count(d) > 0; }))
                grew = out.insert(g.id).second;
    }
    return out;
}

}  // namespace shaderlab::authoring
