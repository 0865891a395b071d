// Tests of the lab.json parser (framework/lab/src/lab_spec*.cpp) on several mistakes at once (each
// reported, and a schema problem stopping the later steps), on mistakes that do not fit the table
// of lab_spec_broken_test.cpp (limits on counts, links out of the lab folder, a lab folder's own
// shared folder), and on the messages docs/lab-format.md shows, word for word.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "lab_spec_fixture.h"
#include "shaderlab/lab/lab_spec.h"

namespace {

using namespace lab_spec_test;

// =============================================================================================
// Several mistakes at once, and mistakes that do not fit the table

using LabSpecErrors = LabSpecFixture;

TEST_F(LabSpecErrors, EverySchemaProblemIsReported) {
    json spec = json::parse(kBaseSpec);
    spec["schema"] = 3;
    spec["passes"][0]["state"] = {{"cull", "sideways"}};
    spec["passes"][2]["uniform"] = json::object();
    spec["scenes"][0]["camera"]["fov_y_deg"] = -5;
    spec["grading"]["ssim_min"] = 2;
    const LabSpecResult r = parseJson(spec);
    EXPECT_FALSE(r.ok);
    EXPECT_TRUE(hasError(r, "schema", "expected 2"));
    EXPECT_TRUE(hasError(r, "passes[0].state.cull", "got \"sideways\""));
    EXPECT_TRUE(hasError(r, "passes[2].uniform", "unknown key"));
    EXPECT_TRUE(hasError(r, "scenes[0].camera.fov_y_deg", "must be in (0, 180), got -5"));
    EXPECT_TRUE(hasError(r, "grading.ssim_min", "must be in [0, 1], got 2"));
    EXPECT_EQ(r.errors.size(), 5u) << allErrors(r);
}

TEST_F(LabSpecErrors, EveryProblemOfTheLaterStepsIsReported) {
    json spec = json::parse(kBaseSpec);
    spec["id"] = "02-toon";
    spec["passes"][4]["inputs"]["u_normal"] = "gbuf.normals";
    spec["passes"][2]["inputs"]["u_blurred"] = "half";
    spec["scenes"][1]["file"] = "scenes/torus.gltf";
    spec["targets"]["env"]["size"] = {32, 16};
    const LabSpecResult r = parseJson(spec);
    EXPECT_FALSE(r.ok);
    EXPECT_TRUE(hasError(r, "id", "but the lab folder is \"01-phong\""));
    EXPECT_TRUE(hasError(r, "passes[4].inputs.u_normal", "has no attachment \"normals\""));
    EXPECT_TRUE(hasError(r, "passes[2].inputs.u_blurred", "a cycle"));
    EXPECT_TRUE(hasError(r, "scenes[1].file", "file not found"));
    EXPECT_TRUE(hasError(r, "targets.env", "must be square"));
    EXPECT_EQ(r.errors.size(), 5u) << allErrors(r);
}

TEST_F(LabSpecErrors, ASchemaProblemStopsTheLaterSteps) {
    // The unknown target would be reported, but the schema problem comes first: no cascade of
    // messages about a document of the wrong shape.
    json spec = json::parse(kBaseSpec);
    spec["passes"][0]["state"] = {{"cull", "sideways"}};
    spec["passes"][4]["inputs"]["u_image"] = "nowhere";
    const LabSpecResult r = parseJson(spec);
    EXPECT_TRUE(hasError(r, "passes[0].state.cull", "sideways"));
    EXPECT_EQ(r.errors.size(), 1u) << allErrors(r);
}

TEST_F(LabSpecErrors, MoreThanSixteenInputsAreRefused) {
    json spec = json::parse(kBaseSpec);
    for (int i = 0; i < 17; ++i) spec["passes"][4]["inputs"]["u_t" + std::to_string(i)] = "half";
    const LabSpecResult r = parseJson(spec);
    EXPECT_FALSE(r.ok);
    EXPECT_TRUE(hasError(r, "passes[4].inputs", "has 19 entries; at most 16 are allowed"));
}

TEST_F(LabSpecErrors, MoreThanSixtyFourPassesAreRefused) {
    json spec = json::parse(kMinimalSpec);
    for (int i = 1; i < 65; ++i) {
        json p = spec["passes"][0];
        p["name"] = "p" + std::to_string(i);
        spec["passes"].push_back(p);
    }
    const LabSpecResult r = parseJson(spec);
    EXPECT_TRUE(hasError(r, "passes", "must have at most 64 elements, got 65"));
}

TEST_F(LabSpecErrors, ALabFolderWithItsOwnSharedFolderIsRefused) {
    writeFile(lab_ / "shared" / "fullscreen.vert", "// would hide labs/shared/fullscreen.vert\n");
    const LabSpecResult r = parseText(kBaseSpec);
    EXPECT_FALSE(r.ok);
    EXPECT_TRUE(hasError(r, "", "the lab folder has a sub-folder \"shared\""));
    EXPECT_EQ(r.errors.size(), 1u) << allErrors(r);
}

TEST_F(LabSpecErrors, AFileLinkedFromOutsideItsFolderIsRefused) {
    fs::create_symlink(root_ / "outside.frag", lab_ / "linked.frag");
    json spec = json::parse(kBaseSpec);
    spec["passes"][2]["program"]["fragment"] = "linked.frag";
    const LabSpecResult r = parseJson(spec);
    EXPECT_FALSE(r.ok);
    EXPECT_TRUE(hasError(r, "passes[2].program.fragment", "resolves outside"));

    fs::create_symlink(root_ / "outside.frag", labs_ / "shared" / "linked.vert");
    spec = json::parse(kBaseSpec);
    spec["templates"]["post"]["program"]["vertex"] = "shared/linked.vert";
    EXPECT_TRUE(hasError(parseJson(spec), "passes[1].program.vertex", "resolves outside"));

    fs::create_symlink(root_ / "outside.frag", labs_ / "scenes" / "linked.gltf");
    spec = json::parse(kBaseSpec);
    spec["scenes"][0]["file"] = "scenes/linked.gltf";
    EXPECT_TRUE(hasError(parseJson(spec), "scenes[0].file", "resolves outside"));
}

TEST_F(LabSpecErrors, AFileLinkedInsideItsFolderIsAccepted) {
    fs::create_symlink(lab_ / "phong.frag", lab_ / "linked.frag");
    json spec = json::parse(kBaseSpec);
    spec["passes"][2]["program"]["fragment"] = "linked.frag";
    const LabSpecResult r = parseJson(spec);
    EXPECT_TRUE(r.ok) << allErrors(r);
}

TEST_F(LabSpecErrors, MissingLabFolderIsReportedForText) {
    const fs::path missing = labs_ / "99-nothing";
    const LabSpecResult r = shaderlab::parseLabSpecText(kMinimalSpec, kOrigin, missing.string());
    EXPECT_FALSE(r.ok);
    EXPECT_TRUE(hasError(r, "id", "but the lab folder is \"99-nothing\""));
    EXPECT_EQ(fs::path(r.spec.lab_dir), missing);
}

// The messages docs/lab-format.md shows under "Messages", word for word (the lab differs, so
// the indices and names are those of small labs built to make each one).
TEST_F(LabSpecErrors, TheMessagesShownInTheDocsAreTheParsersWords) {
    const std::string origin = "labs/04-toon/lab.json";
    auto parseAs = [&](const json& doc) {
        return shaderlab::parseLabSpecText(doc.dump(2), origin, lab_.string());
    };
    auto exactly = [&](const LabSpecResult& r, const std::string& message) {
        for (const std::string& e : r.errors)
            if (e == origin + ": " + message) return ::testing::AssertionSuccess();
        return ::testing::AssertionFailure()
               << "no message \"" << origin << ": " << message << "\"; messages were:" << allErrors(r);
    };
    json spec = json::parse(kBaseSpec);
    spec["passes"][0]["state"] = {{"cull", "sideways"}};
    spec["passes"][0]["uniform"] = json::object();
    LabSpecResult r = parseAs(spec);
    EXPECT_TRUE(exactly(
        r, "passes[0].state.cull: expected one of \"back\", \"front\" or \"none\", got \"sideways\""));
    EXPECT_TRUE(exactly(r, "passes[0].uniform: unknown key (did you mean \"uniforms\"?)"));

    spec = json::parse(kBaseSpec);
    spec["passes"][2]["repeat"] = 0;
    EXPECT_TRUE(exactly(parseAs(spec), "passes[2].repeat: must be in [1, 10000], got 0"));

    spec = json::parse(kBaseSpec);
    spec["scenes"][1]["file"] = "scenes/torus.gltf";
    r = parseAs(spec);
    EXPECT_TRUE(
        exactly(r, "scenes[1].file: " + (labs_ / "scenes" / "torus.gltf").string() + ": file not found"));

    spec = json::parse(R"({"schema": 2, "id": "01-phong",
      "targets": {"gbuffer": {"attachments": ["albedo", "normal"]}},
      "passes": [
        {"name": "shade", "program": {"vertex": "phong.vert", "fragment": "phong.frag"}, "target": "gbuffer"},
        {"name": "outline", "program": {"vertex": "phong.vert", "fragment": "outline.frag"},
         "inputs": {"u_scene": "post", "u_normal": "gbuffer.normals"}},
        {"name": "post", "program": {"vertex": "shared/fullscreen.vert", "fragment": "post.frag"},
         "draw": "fullscreen"}],
      "scenes": [{"name": "sphere", "file": "scenes/sphere.gltf"}]})");
    r = parseAs(spec);
    EXPECT_TRUE(exactly(r,
                        "passes[1].inputs.u_scene: reads target \"post\", which is first drawn by passes[2] "
                        "(\"post\") after this pass: a cycle. A pass reads what earlier passes drew, unless "
                        "both are in one repeat group"));
    EXPECT_TRUE(exactly(r,
                        "passes[1].inputs.u_normal: target \"gbuffer\" has no attachment \"normals\" (did "
                        "you mean \"normal\"?)"));

    std::string text = "{\n";
    for (int line = 2; line < 12; ++line) text += "  \"k" + std::to_string(line) + "\": 0,\n";
    text += "      ,\n}\n";  // line 12, column 7: a comma where a key belongs
    r = shaderlab::parseLabSpecText(text, origin, lab_.string());
    ASSERT_EQ(r.errors.size(), 1u) << allErrors(r);
    EXPECT_EQ(r.errors[0], origin +
                               ": line 12, column 7: syntax error while parsing object key - unexpected ','; "
                               "expected string literal");
}

}  // namespace
