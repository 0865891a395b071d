// The real-world glTF files (tests/data/gltf_realworld/) drawn on llvmpipe: each beside its plain
// twin in one small lab, pictures compared pixel by pixel, with a scene that cannot load among
// them (it fails alone, with its reason); and the optional attributes and material uniforms
// (docs/scenes.md) as a shader reads them.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "gl_test_support.h"
#include "grader/metrics/image.h"
#include "shaderlab/lab/lab_spec.h"
#include "shaderlab/render/renderer.h"

namespace fs = std::filesystem;

namespace {

std::string realworld(const std::string& name) {
    return std::string(SHADERLAB_TEST_DATA) + "/gltf_realworld/" + name;
}

const char* const kVert = R"(#version 330 core
in vec3 a_position;
in vec3 a_normal;
uniform mat4 u_model_view_projection;
uniform mat3 u_normal_matrix;
out vec3 v_normal;
void main() { v_normal = u_normal_matrix * a_normal; gl_Position = u_model_view_projection * vec4(a_position, 1.0); }
)";
const char* const kFrag = R"(#version 330 core
in vec3 v_normal;
out vec4 o_color;
void main() { o_color = vec4(normalize(v_normal) * 0.5 + 0.5, 1.0); }
)";
// Reads the optional attributes, so they are uploaded and bound.
const char* const kAttributesVert = R"(#version 330 core
in vec3 a_position;
in vec4 a_color;
in vec4 a_tangent;
in vec2 a_texcoord1;
uniform mat4 u_model_view_projection;
out vec4 v_color;
void main() { v_color = vec4(a_color.rg, abs(a_tangent.x) * 0.5 + a_texcoord1.x, 1.0); gl_Position = u_model_view_projection * vec4(a_position, 1.0); }
)";
const char* const kAttributesFrag = R"(#version 330 core
in vec4 v_color;
uniform float u_metallic;
out vec4 o_color;
void main() { o_color = vec4(v_color.rgb, u_metallic); }
)";

class GltfRealWorldRender : public ::testing::Test {
  protected:
    void SetUp() override {
        std::string err;
        if (!shaderlab::testing::sharedContext(shaderlab::Backend::OSMesa, &err)) FAIL() << err;
        root_ = fs::temp_directory_path() / ("shaderlab_realworld_" + std::to_string(::getpid()) + "_" +
                                             ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(root_);
        lab_ = root_ / "labs" / "70-scenes";
        fs::create_directories(lab_);
        fs::create_directories(root_ / "labs" / "scenes");
        for (const auto& e : fs::directory_iterator(realworld("")))
            if (e.path().extension() != ".py" && e.path().extension() != ".md")
                fs::copy_file(e.path(), root_ / "labs" / "scenes" / e.path().filename());
        std::ofstream(lab_ / "scene.vert") << kVert;
        std::ofstream(lab_ / "scene.frag") << kFrag;
        std::ofstream(lab_ / "attributes.vert") << kAttributesVert;
        std::ofstream(lab_ / "attributes.frag") << kAttributesFrag;
    }
    void TearDown() override { fs::remove_all(root_); }

    shaderlab::LabRender render(const std::vector<std::string>& files, const std::string& vert = "scene.vert",
                                const std::string& frag = "scene.frag") {
        std::string scenes;
        for (const std::string& f : files)
            scenes += std::string(scenes.empty() ? "" : ", ") + "{\"name\": \"" + f.substr(0, f.find('.')) +
                      "\", \"file\": \"scenes/" + f + "\"}";
        std::ofstream(lab_ / "lab.json") << "{\"schema\": 2, \"id\": \"70-scenes\", \"resolution\": [64, "
                                            "64], \"passes\": [{\"name\": \"draw\", "
                                            "\"program\": {\"vertex\": \"" +
                                                vert + "\", \"fragment\": \"" + frag +
                                                "\"}, \"state\": {\"clear_color\": [0, 0, 0, 0], "
                                                "\"depth_test\": true, \"cull\": \"back\"}, "
                                                "\"graded\": true}], \"scenes\": [" +
                                                scenes + "]}";
        const shaderlab::LabSpecResult parsed = shaderlab::parseLabSpec(lab_.string());
        std::string errors;
        for (const std::string& e : parsed.errors) errors += "\n" + e;
        EXPECT_TRUE(parsed.ok) << errors;
        spec_ = parsed.spec;
        if (!parsed.ok) return {};
        return shaderlab::renderLab(spec_, lab_.string());
    }

    static const shaderlab::SceneRender* scene(const shaderlab::LabRender& r, const std::string& name) {
        for (const auto& s : r.scenes)
            if (s.scene == name) return &s;
        ADD_FAILURE() << "no scene " << name;
        return nullptr;
    }

    // Pixels whose colour differs by more than 0.1 in a channel, or whose coverage differs.
    static int differing(const shaderlab::SceneRender& a, const shaderlab::SceneRender& b) {
        if (a.passes.empty() || b.passes.empty()) return 1 << 30;
        const grader::Image& x = a.passes[0].color;
        const grader::Image& y = b.passes[0].color;
        int n = 0;
        for (int j = 0; j < x.height; ++j)
            for (int i = 0; i < x.width; ++i) {
                bool differs = a.passes[0].coverage[static_cast<std::size_t>(j * x.width + i)] !=
                               b.passes[0].coverage[static_cast<std::size_t>(j * x.width + i)];
                for (int c = 0; c < 3; ++c)
                    differs = differs || std::abs(x.at(i, j, c) - y.at(i, j, c)) > 0.1f;
                n += differs;
            }
        return n;
    }

    static int covered(const shaderlab::SceneRender& s) {
        int n = 0;
        for (auto c : s.passes.at(0).coverage) n += c != 0;
        return n;
    }

    fs::path root_, lab_;
    shaderlab::LabSpec spec_;
};

TEST_F(GltfRealWorldRender, EachFileDrawsLikeItsTwinAndABadSceneFailsAlone) {
    const auto r = render({"mirrored_cube.gltf", "mirrored_cube_twin.gltf", "interleaved_cube.glb",
                           "interleaved_cube_twin.gltf", "instanced_cubes.gltf", "instanced_cubes_twin.gltf",
                           "basisu_textures.gltf", "draco_cube.glb", "meshopt_cube.glb",
                           "meshopt_quantized_cube.glb", "compressed_cube_twin.glb", "double_sided_quad.gltf",
                           "strip_fan.gltf", "skinned_morphed_cube.gltf", "spot_light_ortho_camera.gltf"});
    ASSERT_EQ(r.status, shaderlab::RenderStatus::Ok) << r.message;
    ASSERT_EQ(r.scenes.size(), 15u);
    const auto* bad = scene(r, "basisu_textures");
    ASSERT_TRUE(bad);
    EXPECT_NE(bad->error.find("requires extension 'KHR_texture_basisu'"), std::string::npos) << bad->error;
    EXPECT_TRUE(bad->passes.empty());
    for (const auto& s : r.scenes) {
        if (s.scene != "basisu_textures") {
            EXPECT_TRUE(s.error.empty() && s.passes.size() == 1) << s.scene << s.error;
        }
    }

    const auto pair = [&](const char* a, const char* b, int allowed) {
        const auto *x = scene(r, a), *y = scene(r, b);
        if (!x || !y) return;
        EXPECT_GT(covered(*x), 200) << a;
        EXPECT_LE(differing(*x, *y), allowed) << a << " vs " << b;
    };
    pair("mirrored_cube", "mirrored_cube_twin", 0);
    pair("interleaved_cube", "interleaved_cube_twin", 0);
    pair("instanced_cubes", "instanced_cubes_twin", 0);
    // Quantized positions and normals (Draco: 11 and 8 bits) move edges by about a pixel.
    pair("draco_cube", "compressed_cube_twin", 64);
    pair("meshopt_cube", "compressed_cube_twin", 0);
    pair("meshopt_quantized_cube", "compressed_cube_twin", 64);
    // Seen from behind and culled "back", the double-sided quad still covers the middle.
    if (const auto* s = scene(r, "double_sided_quad")) {
        EXPECT_EQ(s->passes.at(0).coverage.at(32 * 64 + 32), 1);
    }
    if (const auto* s = scene(r, "strip_fan")) {
        EXPECT_GT(covered(*s), 600);
    }
    if (const auto* s = scene(r, "skinned_morphed_cube")) {
        EXPECT_GT(covered(*s), 200);
    }
    // The file's orthographic camera (2 units tall) looking at the unit cube face on: a square
    // half the image high, whatever the distance.
    if (const auto* s = scene(r, "spot_light_ortho_camera")) {
        EXPECT_NEAR(covered(*s), 32 * 32, 2 * 64);
    }
    // The loader's warnings reach the lab author, naming the scene file.
    bool skin_warning = false, error_named = false;
    for (const auto& d : r.diagnostics) {
        skin_warning =
            skin_warning || (d.file == "../scenes/skinned_morphed_cube.gltf" && d.severity == "warning" &&
                             d.message.find("bind pose") != std::string::npos);
        error_named = error_named || (d.file == "../scenes/basisu_textures.gltf" && d.severity == "error");
    }
    EXPECT_TRUE(skin_warning);
    EXPECT_TRUE(error_named);
}

TEST_F(GltfRealWorldRender, OptionalAttributesAndMaterialUniformsReachTheShader) {
    const auto r =
        render({"pbr_material_cube.gltf", "mirrored_cube_twin.gltf"}, "attributes.vert", "attributes.frag");
    ASSERT_EQ(r.status, shaderlab::RenderStatus::Ok) << r.message;
    ASSERT_EQ(r.scenes.size(), 2u);
    const grader::Image& pbr = r.scenes[0].passes.at(0).color;
    const auto& cov = r.scenes[0].passes.at(0).coverage;
    bool seen_vertex_colour = false;
    for (int j = 0; j < 64; ++j)
        for (int i = 0; i < 64; ++i) {
            if (!cov[static_cast<std::size_t>(j * 64 + i)]) continue;
            EXPECT_NEAR(pbr.at(i, j, 0), 1.0f, 1e-3f);   // COLOR_0 red is 255 everywhere
            EXPECT_NEAR(pbr.at(i, j, 3), 0.25f, 1e-3f);  // u_metallic
            seen_vertex_colour = seen_vertex_colour || pbr.at(i, j, 1) > 0.05f;
        }
    EXPECT_TRUE(seen_vertex_colour);
    // A mesh without the attributes reads the documented constants: colour white, tangent +x,
    // TEXCOORD_1 zero; the default material is metallic 1.
    const grader::Image& plain = r.scenes[1].passes.at(0).color;
    EXPECT_NEAR(plain.at(32, 32, 0), 1.0f, 1e-3f);
    EXPECT_NEAR(plain.at(32, 32, 1), 1.0f, 1e-3f);
    EXPECT_NEAR(plain.at(32, 32, 2), 0.5f, 1e-3f);
    EXPECT_NEAR(plain.at(32, 32, 3), 1.0f, 1e-3f);
}

}  // namespace
