// The uniforms the framework sets itself (docs/student-contract.md) refused as lab uniforms, each
// with the reason: a lab value under such a name would replace the framework's. The list in
// docs/lab.schema.json is checked against the names the renderer sets (framework/render/src), so
// a uniform the renderer starts setting cannot be forgotten there.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "lab_spec_fixture.h"
#include "shaderlab/lab/lab_spec.h"

namespace {

using namespace lab_spec_test;
using FrameworkUniforms = LabSpecFixture;

std::set<std::string> refusedNames() {
    const json schema = json::parse(shaderlab::labSchemaText());
    std::set<std::string> refused;
    for (const json& part : schema.at("definitions").at("lab_uniform_name").at("allOf"))
        if (part.contains("not"))
            for (const json& n : part.at("not").at("enum")) refused.insert(n.get<std::string>());
    return refused;
}

json withPassUniform(const std::string& name) {
    json spec = json::parse(kBaseSpec);
    spec["passes"][2]["uniforms"][name] = 1.0;
    return spec;
}

TEST_F(FrameworkUniforms, AMaterialUniformIsRefusedWithTheReason) {
    const LabSpecResult r = parseJson(withPassUniform("u_normal_scale"));
    EXPECT_FALSE(r.ok);
    EXPECT_TRUE(
        hasError(r, "passes[2].uniforms.u_normal_scale",
                 "\"u_normal_scale\" is set by the framework itself (the drawn object's material, from "
                 "the scene's glTF file; docs/student-contract.md): a lab value would replace it, so "
                 "pick another name"));
}

TEST_F(FrameworkUniforms, ALightUniformIsRefusedInASceneToo) {
    json spec = json::parse(kBaseSpec);
    spec["scenes"][0]["uniforms"] = {{"u_light_range", {1.0, 2.0}}};
    const LabSpecResult r = parseJson(spec);
    EXPECT_FALSE(r.ok);
    EXPECT_TRUE(hasError(r, "scenes[0].uniforms.u_light_range", "(the scene's lights;"));
}

TEST_F(FrameworkUniforms, EachGroupSaysWhoseItIs) {
    const std::pair<const char*, const char*> cases[] = {
        {"u_model", "the drawn object's transform"},
        {"u_camera_position", "the camera's matrices and position"},
        {"u_light_cone", "the scene's lights"},
        {"u_has_normal_texture", "the drawn object's material"},
        {"u_emissive_texcoord", "the drawn object's material"},
        {"u_cube_face", "the repeat or cube face being drawn"},
    };
    for (const auto& [name, reason] : cases) {
        const LabSpecResult r = parseJson(withPassUniform(name));
        EXPECT_FALSE(r.ok) << name;
        EXPECT_TRUE(hasError(r, std::string("passes[2].uniforms.") + name, reason)) << name;
    }
}

TEST_F(FrameworkUniforms, ALabNameBesideThemIsKept) {
    for (const char* name : {"u_normal_strength", "u_light_matrix_2", "u_model_scale", "u_roughness_bias"}) {
        const LabSpecResult r = parseJson(withPassUniform(name));
        EXPECT_TRUE(r.ok) << name << allErrors(r);
    }
}

// Every "u_..." name the renderer's sources spell out is one the framework sets, so one a lab may
// not: a renderer that starts setting a new one fails here until the schema refuses it.
TEST(FrameworkUniformList, IsEveryNameTheRendererSets) {
    const std::set<std::string> refused = refusedNames();
    std::set<std::string> set_by_renderer;
    const std::regex literal(R"re("(u_[A-Za-z0-9_]+)")re");
    for (const auto& entry :
         fs::directory_iterator(fs::path(SHADERLAB_SOURCE_DIR) / "framework/render/src")) {
        std::ifstream in(entry.path(), std::ios::binary);
        std::ostringstream text;
        text << in.rdbuf();
        const std::string s = text.str();
        for (auto it = std::sregex_iterator(s.begin(), s.end(), literal); it != std::sregex_iterator(); ++it)
            set_by_renderer.insert((*it)[1]);
    }
    EXPECT_GE(set_by_renderer.size(), 30u);
    for (const std::string& n : set_by_renderer)
        EXPECT_TRUE(refused.count(n)) << n << " is set by framework/render/src but a lab may set it too";
    for (const std::string& n : refused)
        EXPECT_TRUE(set_by_renderer.count(n)) << n << " is refused but framework/render/src never sets it";
}

}  // namespace
