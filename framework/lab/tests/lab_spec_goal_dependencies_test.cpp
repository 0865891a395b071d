// Goals that rest on others (lab.json "depends_on", docs/lab-format.md "Goals"): what the parser
// keeps, and the mistakes it refuses with the path of the field.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "lab_spec_fixture.h"
#include "shaderlab/lab/lab_spec.h"

namespace {

using namespace lab_spec_test;
using GoalDependencies = LabSpecFixture;

json threeGoals() {
    json spec = json::parse(kBaseSpec);
    spec["goals"] = json::parse(R"([
      {"id": "shading", "title": "Shade", "points": 4, "passes": ["shade"]},
      {"id": "post", "title": "Blur", "points": 4, "passes": ["final"]},
      {"id": "together", "title": "Both on the teapot", "points": 2, "scenes": ["teapot"], "passes": ["final"]}
    ])");
    return spec;
}

TEST_F(GoalDependencies, AreKeptInTheSpec) {
    json spec = threeGoals();
    spec["goals"][2]["depends_on"] = {"shading", "post"};
    const LabSpecResult r = parseJson(spec);
    ASSERT_TRUE(r.ok) << allErrors(r);
    EXPECT_EQ(r.spec.goals[2].depends_on, (std::vector<std::string>{"shading", "post"}));
    EXPECT_TRUE(r.spec.goals[0].depends_on.empty());
}

TEST_F(GoalDependencies, AnUnknownGoalIsNamedWithASuggestion) {
    json spec = threeGoals();
    spec["goals"][2]["depends_on"] = {"shadin"};
    const LabSpecResult r = parseJson(spec);
    EXPECT_FALSE(r.ok);
    EXPECT_TRUE(hasError(r, "goals[2].depends_on[0]", "no goal is called \"shadin\""));
    EXPECT_TRUE(hasError(r, "goals[2].depends_on[0]", "shading"));
}

TEST_F(GoalDependencies, AGoalCannotRestOnItself) {
    json spec = threeGoals();
    spec["goals"][1]["depends_on"] = {"post"};
    const LabSpecResult r = parseJson(spec);
    EXPECT_FALSE(r.ok);
    EXPECT_TRUE(hasError(r, "goals[1].depends_on[0]", "cannot depend on itself"));
}

TEST_F(GoalDependencies, ACircleIsRefusedAndShown) {
    json spec = threeGoals();
    spec["goals"][0]["depends_on"] = {"together"};
    spec["goals"][1]["depends_on"] = {"shading"};
    spec["goals"][2]["depends_on"] = {"post"};
    const LabSpecResult r = parseJson(spec);
    EXPECT_FALSE(r.ok);
    EXPECT_TRUE(hasError(r, "goals", "circle: shading -> together -> post -> shading"));
}

TEST_F(GoalDependencies, TheSchemaRefusesAnEmptyOrRepeatedList) {
    json spec = threeGoals();
    spec["goals"][2]["depends_on"] = json::array();
    EXPECT_FALSE(parseJson(spec).ok);
    spec["goals"][2]["depends_on"] = {"post", "post"};
    EXPECT_FALSE(parseJson(spec).ok);
}

}  // namespace
