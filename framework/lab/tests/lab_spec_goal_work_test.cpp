// A goal's work (lab.json goals[].work, docs/lab-format.md "Goals"): student files and functions the
// starter declares, and no depends_on beside it.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "lab_spec_fixture.h"
#include "shaderlab/lab/lab_spec.h"

namespace {

using namespace lab_spec_test;
using GoalWork = LabSpecFixture;

json withWork(const json& work) {
    json spec = json::parse(kBaseSpec);
    spec["student_files"] = {"phong.vert", "phong.frag"};
    spec["goals"][0]["work"] = work;
    return spec;
}

TEST_F(GoalWork, FunctionsAndFilesAreKept) {
    writeFile(lab_ / "phong.frag", "vec3 diffuse(vec3 n, vec3 l) { return vec3(0.0); }\nvoid main() {}\n");
    const LabSpecResult r = parseJson(withWork({"phong.frag:diffuse", "phong.frag:main", "phong.vert"}));
    ASSERT_TRUE(r.ok) << allErrors(r);
    const std::vector<shaderlab::GoalWork>& w = r.spec.goals[0].work;
    ASSERT_EQ(w.size(), 3u);
    EXPECT_EQ(w[0].file, "phong.frag");
    EXPECT_EQ(w[0].function, "diffuse");
    EXPECT_EQ(w[2].file, "phong.vert");
    EXPECT_EQ(w[2].function, "");
    EXPECT_TRUE(r.spec.goals[1].work.empty());
}

TEST_F(GoalWork, AFileThatIsNotTheStudentsIsNamedWithASuggestion) {
    const LabSpecResult r = parseJson(withWork({"phong.fragg:diffuse"}));
    EXPECT_FALSE(r.ok);
    EXPECT_TRUE(hasError(r, "goals[0].work[0]", "\"phong.fragg\" is not one of the lab's student_files"));
    EXPECT_TRUE(hasError(r, "goals[0].work[0]", "phong.frag"));
}

TEST_F(GoalWork, AFunctionTheStarterLacksIsRefused) {
    writeFile(lab_ / "phong.frag", "// diffuse is only named in a comment\nvoid main() {}\n");
    const LabSpecResult r = parseJson(withWork({"phong.frag:diffuse"}));
    EXPECT_FALSE(r.ok);
    EXPECT_TRUE(hasError(r, "goals[0].work[0]", "the starter's phong.frag has no function `diffuse`"));
}

TEST_F(GoalWork, RestsOnNoOtherGoal) {
    json spec = withWork({"phong.vert"});
    spec["goals"][0]["depends_on"] = {"post"};
    spec["goals"][0]["pipeline"] = true;
    const LabSpecResult r = parseJson(spec);
    EXPECT_FALSE(r.ok);
    EXPECT_TRUE(hasError(r, "goals[0].depends_on", "rests on no other goal"));
    EXPECT_TRUE(hasError(r, "goals[0].pipeline", "not on the student's pipeline"));
}

TEST_F(GoalWork, TheSchemaRefusesMalformedEntries) {
    for (const json& bad : {json::array(), json{"phong.frag:"}, json{"phong.frag:1x"}, json{"a b.frag"},
                            json{"phong.frag", "phong.frag"}})
        EXPECT_FALSE(parseJson(withWork(bad)).ok) << bad.dump();
}

}  // namespace
