// A lab's corpus file, tests/corpus/<lab>/cases.json (docs/corpus.schema.json): read, checked
// against the schema and then against the lab (goal ids, case folders, what each kind takes).
// Used by `corpus` to grade the cases, by `corpus add-case` to check what it writes and by
// `scene-sweep` to grade them on candidate scenes. Grades nothing; writes only a case's
// submission folder (materialise).
#pragma once

#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "shaderlab/lab/lab_spec.h"

namespace shaderlab::authoring {

struct Case {
    std::string name, kind, about, status;
    std::vector<std::string> fails, remove;  // remove: "delete"
    std::vector<std::string> whole;          // goals that must be judged on the whole shaders, with a note
    std::vector<std::string> given;          // starter-given code changed: "file: function" (judged_with)
    std::optional<std::pair<std::string, int>> diagnostic;
    double timeout_s = 0.0;
};

// docs/corpus.schema.json, compiled in.
const std::string& corpusSchemaText();

// Reads `file`, a cases.json of the lab `spec`, into `out`; false with every problem in `errors`
// ("<file>: <json path>: <problem>") when it is not a valid one.
bool loadCases(const std::filesystem::path& file, const LabSpec& spec, std::vector<Case>* out,
               std::vector<std::string>* errors);

// A mutant of the reference declared to compute what the reference does (cases.json
// "equivalent_mutants"): its id as mutants.h makes it, and why.
struct EquivalentMutant {
    std::string id, reason;
};

// The equivalent mutants a lab's cases.json declares (none when the file has no such list). False,
// with every problem in `errors`, when the file is not a valid cases.json or lists an id twice.
bool loadEquivalentMutants(const std::filesystem::path& file, std::vector<EquivalentMutant>* out,
                           std::vector<std::string>* errors);

// A submission folder for one case, `submission`/<lab>/: the reference's student files (from
// `reference_lab`), then the case's files (from `case_dir`) over them, then the deletions. False,
// with the reason, when a reference file cannot be copied.
bool materialise(const LabSpec& spec, const std::filesystem::path& reference_lab,
                 const std::filesystem::path& case_dir, const Case& c,
                 const std::filesystem::path& submission, std::string* error);

// The goals a mistake may fail: those it names, and every goal that rests on one of them
// (depends_on, followed through), since such a goal is not met because of it.
std::set<std::string> expectedFailures(const LabSpec& spec, const std::vector<std::string>& fails);

}  // namespace shaderlab::authoring
