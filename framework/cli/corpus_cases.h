// A lab's corpus file, tests/corpus/<lab>/cases.json (docs/corpus.schema.json): read, checked
// against the schema and then against the lab (goal ids, case folders, what each kind takes).
// Used by `corpus` to grade the cases and by `corpus add-case` to check what it writes. Grades
// nothing and writes nothing.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "shaderlab/lab/lab_spec.h"

namespace shaderlab::cli {

struct Case {
    std::string name, kind, about, status;
    std::vector<std::string> fails, remove;  // remove: "delete"
    std::optional<std::pair<std::string, int>> diagnostic;
    double timeout_s = 0.0;
};

// docs/corpus.schema.json, compiled in.
const std::string& corpusSchemaText();

// Reads `file`, a cases.json of the lab `spec`, into `out`; false with every problem in `errors`
// ("<file>: <json path>: <problem>") when it is not a valid one.
bool loadCases(const std::filesystem::path& file, const LabSpec& spec, std::vector<Case>* out,
               std::vector<std::string>* errors);

}  // namespace shaderlab::cli
