// Validates a JSON document against a JSON Schema (draft 7) with valijson, and words each
// problem for a person: "<json path>: <problem>" with the expected form, the value found, and a
// suggestion for a misspelt key or enum value.
//
// valijson decides whether the document is valid and where it fails; it words its failures for
// the schema's author ("Failed to match against any enum values."). So for every location it
// reports, this checker looks at the value and the schema node there (following $ref, allOf, and
// the oneOf/anyOf branch whose type fits the value) and says what is wrong in terms of the
// document. Schema nodes may carry two annotations validators ignore: "x-expected" (how to name
// the expected form: "a name of 1 to 64 letters, ...") and "x-message" (the problem, for a
// failing "not"). Should it find nothing to say at a failing location, valijson's own words are
// kept, so a failure is never silently dropped.
//
// It does not check what a schema cannot say (references between fields, files on disk).
#pragma once

#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace shaderlab {

struct SchemaProblem {
    std::string path;  // "" for the document itself
    std::string problem;
};

class JsonSchemaChecker {
  public:
    // `schema` must stay alive as long as the checker.
    explicit JsonSchemaChecker(const nlohmann::json& schema);
    ~JsonSchemaChecker();
    JsonSchemaChecker(const JsonSchemaChecker&) = delete;
    JsonSchemaChecker& operator=(const JsonSchemaChecker&) = delete;

    // Every problem, in document order, each once.
    std::vector<SchemaProblem> check(const nlohmann::json& document) const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace shaderlab
