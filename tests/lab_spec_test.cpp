// Tests of the lab.json parser (framework/src/lab_spec.cpp): a valid spec becomes the expected
// typed values, defaults included; every kind of mistake is refused with a message naming the
// JSON path and the problem; all mistakes are reported together; syntax errors name a line and
// column. Each test builds its own lab folder under the temp directory; nothing here renders.
#include "shaderlab/lab_spec.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <variant>
#include <vector>

namespace fs = std::filesystem;
using nlohmann::json;
using shaderlab::LabSpecResult;

namespace {

const char* const kOrigin = "labs/01-phong/lab.json";

// A valid three-pass lab (scene pass, fullscreen post pass reading it, an outline drawn into the
// post pass) that the error table below breaks one field at a time.
const char* const kBaseSpec = R"({
  "schema": 1,
  "id": "01-phong",
  "title": "Phong shading",
  "resolution": [256, 128],
  "passes": [
    {"name": "shade", "program": {"vertex": "phong.vert", "fragment": "phong.frag"},
     "target": {"name": "color", "format": "rgba16f"}, "uniforms": {"u_shininess": 32.0}},
    {"name": "post", "program": {"vertex": "fullscreen.vert", "fragment": "post.frag"}, "draw": "fullscreen",
     "inputs": [{"sampler": "u_scene", "pass": "color"},
                {"sampler": "u_ramp", "texture": "textures/ramp.png", "filter": "nearest", "wrap": "clamp"}],
     "target": {"scale": 0.5}},
    {"name": "outline", "program": {"vertex": "phong.vert", "fragment": "outline.frag"},
     "draw_into": "post", "state": {"polygon_mode": "line", "line_width": 2, "cull": "front"}}
  ],
  "scenes": [
    {"name": "sphere", "file": "scenes/sphere.gltf",
     "camera": {"position": [0, 0, 3], "target": [0, 0, 0], "up": [0, 1, 0], "fov_y_deg": 45,
                "near": 0.1, "far": 100},
     "lights": [{"type": "point", "position": [2, 2, 2]}, {"type": "directional", "direction": [0, -1, 0]}],
     "time": 0.5}
  ],
  "grading": {"points": 10, "psnr_min_db": 30, "ssim_min": 0.95}
})";

const char* const kMinimalSpec = R"({
  "schema": 1,
  "id": "01-phong",
  "passes": [{"name": "shade", "program": {"vertex": "phong.vert", "fragment": "phong.frag"}}],
  "scenes": [{"name": "sphere", "file": "scenes/sphere.gltf"}]
})";

std::string sanitized(std::string s) {
    for (char& c : s) {
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    }
    return s;
}

void writeFile(const fs::path& p, const std::string& text) {
    fs::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << text;
}

std::string allErrors(const LabSpecResult& r) {
    std::string s;
    for (const std::string& e : r.errors) s += "\n  " + e;
    return s.empty() ? " (none)" : s;
}

// Whether some message reads "<origin>: <path>: ..." and contains `problem` after the path.
::testing::AssertionResult hasError(const LabSpecResult& r, const std::string& path,
                                    const std::string& problem) {
    const std::string prefix = std::string(kOrigin) + ": " + (path.empty() ? "" : path + ": ");
    for (const std::string& e : r.errors) {
        if (e.rfind(prefix, 0) == 0 && e.find(problem, prefix.size()) != std::string::npos) {
            return ::testing::AssertionSuccess();
        }
    }
    return ::testing::AssertionFailure() << "no error starting with \"" << prefix << "\" and containing \""
                                         << problem << "\"; errors were:" << allErrors(r);
}

// A labs root in the temp directory with one lab folder, 01-phong, holding the files the specs
// above refer to, plus a few files that specs must not be able to reach.
class LabSpecFixture : public ::testing::Test {
  protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        root_ = fs::temp_directory_path() /
                ("shaderlab_labspec_" + std::to_string(::getpid()) + "_" +
                 sanitized(std::string(info->test_suite_name()) + "_" + info->name()));
        fs::remove_all(root_);
        labs_ = root_ / "labs";
        lab_ = labs_ / "01-phong";
        for (const char* f : {"phong.vert", "phong.frag", "fullscreen.vert", "post.frag", "outline.frag"}) {
            writeFile(lab_ / f, "// shader\n");
        }
        writeFile(lab_ / "textures" / "ramp.png", "not really a png");
        writeFile(lab_ / "local.gltf", "{}");
        writeFile(labs_ / "scenes" / "sphere.gltf", "{}");
        writeFile(labs_ / "scenes" / "cube.glb", "glb");
        writeFile(labs_ / "scenes" / "readme.txt", "scenes");
        writeFile(root_ / "outside.frag", "// outside every lab\n");
        writeFile(labs_ / "outside.gltf", "{}");
    }
    void TearDown() override { fs::remove_all(root_); }

    LabSpecResult parseText(const std::string& text) const {
        return shaderlab::parseLabSpecText(text, kOrigin, lab_.string());
    }

    fs::path root_, labs_, lab_;
};

// =============================================================================================
// Valid specs

using LabSpecParse = LabSpecFixture;

TEST_F(LabSpecParse, FullFixtureGivesTypedValues) {
    fs::copy_file(fs::path(SHADERLAB_TEST_DATA) / "labspec" / "full.json", lab_ / "lab.json");
    const LabSpecResult r = shaderlab::parseLabSpec(lab_.string());
    ASSERT_TRUE(r.ok) << allErrors(r);
    const shaderlab::LabSpec& s = r.spec;

    EXPECT_EQ(s.schema, 1);
    EXPECT_EQ(s.id, "01-phong");
    EXPECT_EQ(s.title, "Phong shading");
    EXPECT_EQ(fs::path(s.lab_dir), lab_);
    EXPECT_TRUE(fs::path(s.lab_dir).is_absolute());
    EXPECT_EQ(fs::path(s.labs_root), labs_);
    EXPECT_EQ(s.width, 320);
    EXPECT_EQ(s.height, 240);
    EXPECT_EQ(s.student_files, (std::vector<std::string>{"phong.vert", "phong.frag", "post.frag"}));
    ASSERT_EQ(s.passes.size(), 3u);

    const shaderlab::PassSpec& shade = s.passes[0];
    EXPECT_EQ(shade.name, "shade");
    EXPECT_EQ(shade.program.vertex, "phong.vert");
    EXPECT_EQ(shade.program.fragment, "phong.frag");
    EXPECT_EQ(shade.draw, shaderlab::DrawKind::Scene);
    EXPECT_TRUE(shade.inputs.empty());
    EXPECT_EQ(shade.target.name, "color");
    EXPECT_EQ(shade.target.format, shaderlab::TargetFormat::RGBA16F);
    EXPECT_EQ(shade.target.width, 128);
    EXPECT_EQ(shade.target.height, 64);
    EXPECT_EQ(shade.target.filter, shaderlab::TextureFilter::Nearest);
    EXPECT_EQ(shade.target.wrap, shaderlab::TextureWrap::Repeat);
    ASSERT_TRUE(shade.state.clear_color.has_value());
    EXPECT_EQ(*shade.state.clear_color, glm::vec4(0.1f, 0.2f, 0.3f, 1.0f));
    EXPECT_TRUE(shade.state.clear_depth);
    EXPECT_TRUE(shade.state.depth_test);
    EXPECT_FALSE(shade.state.depth_write);
    EXPECT_EQ(shade.state.depth_func, shaderlab::DepthFunc::LessEqual);
    EXPECT_EQ(shade.state.cull, shaderlab::CullMode::None);
    EXPECT_EQ(shade.state.polygon_mode, shaderlab::PolygonMode::Fill);
    EXPECT_FLOAT_EQ(shade.state.line_width, 1.5f);
    EXPECT_EQ(shade.state.blend, shaderlab::BlendMode::Alpha);
    EXPECT_TRUE(shade.graded);
    EXPECT_TRUE(shade.draw_into.empty());

    const shaderlab::UniformMap& u = shade.uniforms;
    ASSERT_EQ(u.size(), 8u);
    EXPECT_EQ(std::get<float>(u.at("u_shininess")), 32.0f);
    EXPECT_EQ(std::get<int>(u.at("u_levels")), 4);
    EXPECT_EQ(std::get<bool>(u.at("u_flag")), true);
    EXPECT_EQ(std::get<glm::vec2>(u.at("u_offset")), glm::vec2(0.5f, -0.5f));
    EXPECT_EQ(std::get<glm::vec3>(u.at("u_tint")), glm::vec3(1.0f, 0.5f, 0.2f));
    EXPECT_EQ(std::get<glm::vec4>(u.at("u_rgba")), glm::vec4(0.1f, 0.2f, 0.3f, 0.4f));
    const glm::mat3 basis = std::get<glm::mat3>(u.at("u_basis"));
    EXPECT_EQ(basis[0], glm::vec3(1, 2, 3));  // column-major: the first three numbers are column 0
    EXPECT_EQ(basis[2], glm::vec3(7, 8, 9));
    const glm::mat4 xform = std::get<glm::mat4>(u.at("u_xform"));
    EXPECT_EQ(xform[3], glm::vec4(7, 8, 9, 1));  // the translation column
    EXPECT_EQ(xform[0], glm::vec4(1, 0, 0, 0));

    const shaderlab::PassSpec& post = s.passes[1];
    EXPECT_EQ(post.draw, shaderlab::DrawKind::Fullscreen);
    EXPECT_EQ(post.target.name, "post");  // defaults to the pass name
    EXPECT_EQ(post.target.format, shaderlab::TargetFormat::RGBA8);
    EXPECT_EQ(post.target.width, 0);
    EXPECT_FLOAT_EQ(post.target.scale, 0.5f);
    EXPECT_EQ(post.target.filter, shaderlab::TextureFilter::Linear);
    EXPECT_EQ(post.target.wrap, shaderlab::TextureWrap::ClampToEdge);
    EXPECT_FALSE(post.state.clear_color.has_value());  // "clear_color": null
    EXPECT_FALSE(post.state.depth_test);
    EXPECT_EQ(post.state.blend, shaderlab::BlendMode::Additive);
    EXPECT_FALSE(post.graded);
    ASSERT_EQ(post.inputs.size(), 2u);
    EXPECT_EQ(post.inputs[0].sampler, "u_scene");
    EXPECT_EQ(post.inputs[0].from_pass, "color");
    EXPECT_TRUE(post.inputs[0].texture_file.empty());
    EXPECT_FALSE(post.inputs[0].filter.has_value());
    EXPECT_FALSE(post.inputs[0].wrap.has_value());
    EXPECT_EQ(post.inputs[1].sampler, "u_ramp");
    EXPECT_TRUE(post.inputs[1].from_pass.empty());
    EXPECT_EQ(post.inputs[1].texture_file, "textures/ramp.png");
    EXPECT_EQ(post.inputs[1].filter, shaderlab::TextureFilter::Nearest);
    EXPECT_EQ(post.inputs[1].wrap, shaderlab::TextureWrap::MirroredRepeat);

    const shaderlab::PassSpec& outline = s.passes[2];
    EXPECT_EQ(outline.draw_into, "post");
    EXPECT_EQ(outline.target.name, "post");  // a copy of the target it draws into
    EXPECT_EQ(outline.target.format, shaderlab::TargetFormat::RGBA8);
    EXPECT_FLOAT_EQ(outline.target.scale, 0.5f);
    EXPECT_FALSE(outline.state.clear_color.has_value());  // drawing into a pass keeps its image
    EXPECT_FALSE(outline.state.clear_depth);
    EXPECT_EQ(outline.state.polygon_mode, shaderlab::PolygonMode::Line);
    EXPECT_FLOAT_EQ(outline.state.line_width, 2.0f);
    EXPECT_EQ(outline.state.cull, shaderlab::CullMode::Front);
    EXPECT_EQ(outline.state.depth_func, shaderlab::DepthFunc::Always);
    EXPECT_TRUE(outline.graded);  // the last pass

    ASSERT_EQ(s.scenes.size(), 2u);
    const shaderlab::SceneSpec& sphere = s.scenes[0];
    EXPECT_EQ(sphere.name, "sphere");
    EXPECT_EQ(sphere.file, "scenes/sphere.gltf");
    EXPECT_EQ(sphere.camera.position, glm::vec3(0, 0, 3));
    EXPECT_EQ(sphere.camera.target, glm::vec3(0, 0, 0));
    EXPECT_EQ(sphere.camera.up, glm::vec3(0, 1, 0));
    EXPECT_EQ(sphere.camera.fov_y_deg, 45.0f);
    EXPECT_EQ(sphere.camera.z_near, 0.1f);
    EXPECT_EQ(sphere.camera.z_far, 100.0f);
    ASSERT_TRUE(sphere.lights.has_value());
    ASSERT_EQ(sphere.lights->size(), 2u);
    EXPECT_EQ((*sphere.lights)[0].type, "point");
    EXPECT_EQ((*sphere.lights)[0].position, glm::vec3(2, 2, 2));
    EXPECT_EQ((*sphere.lights)[0].color, glm::vec3(1.0f, 0.9f, 0.8f));
    EXPECT_FLOAT_EQ((*sphere.lights)[0].intensity, 2.5f);
    EXPECT_EQ((*sphere.lights)[1].type, "directional");
    EXPECT_EQ((*sphere.lights)[1].direction, glm::vec3(0, -1, 0));
    EXPECT_EQ((*sphere.lights)[1].color, glm::vec3(1.0f));
    EXPECT_FLOAT_EQ((*sphere.lights)[1].intensity, 1.0f);
    EXPECT_EQ(std::get<float>(sphere.uniforms.at("u_shininess")), 8.0f);
    EXPECT_FLOAT_EQ(sphere.time, 0.5f);

    const shaderlab::SceneSpec& cube = s.scenes[1];
    EXPECT_EQ(cube.file, "scenes/cube.glb");
    EXPECT_EQ(cube.camera.fov_y_deg, 60.0f);
    EXPECT_FALSE(cube.camera.position.has_value());
    ASSERT_TRUE(cube.lights.has_value());  // [] replaces the file's lights with none
    EXPECT_TRUE(cube.lights->empty());
    EXPECT_FLOAT_EQ(cube.time, 0.0f);

    EXPECT_FLOAT_EQ(s.grading.points, 20.0f);
    EXPECT_FLOAT_EQ(s.grading.psnr_min_db, 28.0f);
    EXPECT_FLOAT_EQ(s.grading.ssim_min, 0.9f);
    EXPECT_FLOAT_EQ(s.grading.flip_mean_max, 0.1f);
    EXPECT_FLOAT_EQ(s.grading.mismatch_max, 0.02f);
    EXPECT_FLOAT_EQ(s.grading.pixel_tolerance, 0.04f);
}

TEST_F(LabSpecParse, MinimalSpecGetsTheDocumentedDefaults) {
    const LabSpecResult r = parseText(kMinimalSpec);
    ASSERT_TRUE(r.ok) << allErrors(r);
    const shaderlab::LabSpec& s = r.spec;
    EXPECT_EQ(s.title, "01-phong");  // defaults to the id
    EXPECT_EQ(s.width, 256);
    EXPECT_EQ(s.height, 256);
    EXPECT_EQ(s.student_files, (std::vector<std::string>{"phong.vert", "phong.frag"}));

    ASSERT_EQ(s.passes.size(), 1u);
    const shaderlab::PassSpec& p = s.passes[0];
    EXPECT_EQ(p.draw, shaderlab::DrawKind::Scene);
    EXPECT_EQ(p.target.name, "shade");
    EXPECT_EQ(p.target.format, shaderlab::TargetFormat::RGBA32F);
    EXPECT_EQ(p.target.width, 0);
    EXPECT_EQ(p.target.height, 0);
    EXPECT_FLOAT_EQ(p.target.scale, 1.0f);
    EXPECT_EQ(p.target.filter, shaderlab::TextureFilter::Linear);
    EXPECT_EQ(p.target.wrap, shaderlab::TextureWrap::ClampToEdge);
    ASSERT_TRUE(p.state.clear_color.has_value());
    EXPECT_EQ(*p.state.clear_color, glm::vec4(0, 0, 0, 1));
    EXPECT_TRUE(p.state.clear_depth);
    EXPECT_TRUE(p.state.depth_test);
    EXPECT_TRUE(p.state.depth_write);
    EXPECT_EQ(p.state.depth_func, shaderlab::DepthFunc::Less);
    EXPECT_EQ(p.state.cull, shaderlab::CullMode::Back);
    EXPECT_EQ(p.state.polygon_mode, shaderlab::PolygonMode::Fill);
    EXPECT_FLOAT_EQ(p.state.line_width, 1.0f);
    EXPECT_EQ(p.state.blend, shaderlab::BlendMode::None);
    EXPECT_TRUE(p.uniforms.empty());
    EXPECT_TRUE(p.inputs.empty());
    EXPECT_TRUE(p.graded);  // the only, hence last, pass

    ASSERT_EQ(s.scenes.size(), 1u);
    const shaderlab::SceneSpec& sc = s.scenes[0];
    EXPECT_FALSE(sc.camera.position || sc.camera.target || sc.camera.up || sc.camera.fov_y_deg ||
                 sc.camera.z_near || sc.camera.z_far);
    EXPECT_FALSE(sc.lights.has_value());  // keep the file's lights
    EXPECT_TRUE(sc.uniforms.empty());
    EXPECT_FLOAT_EQ(sc.time, 0.0f);

    EXPECT_FLOAT_EQ(s.grading.points, 10.0f);
    EXPECT_FLOAT_EQ(s.grading.psnr_min_db, 30.0f);
    EXPECT_FLOAT_EQ(s.grading.ssim_min, 0.95f);
    EXPECT_FLOAT_EQ(s.grading.flip_mean_max, 0.05f);
    EXPECT_FLOAT_EQ(s.grading.mismatch_max, 0.01f);
    EXPECT_FLOAT_EQ(s.grading.pixel_tolerance, 0.05f);
}

TEST_F(LabSpecParse, DefaultStudentFilesAreTheProgramFilesInOrderWithoutRepeats) {
    json spec = json::parse(kBaseSpec);
    const LabSpecResult r = parseText(spec.dump());
    ASSERT_TRUE(r.ok) << allErrors(r);
    EXPECT_EQ(r.spec.student_files, (std::vector<std::string>{"phong.vert", "phong.frag", "fullscreen.vert",
                                                              "post.frag", "outline.frag"}));
}

TEST_F(LabSpecParse, FullscreenOnlyLabMayListScenesWithoutFiles) {
    const LabSpecResult r = parseText(R"({
      "schema": 1, "id": "01-phong",
      "passes": [{"name": "march", "draw": "fullscreen",
                  "program": {"vertex": "fullscreen.vert", "fragment": "post.frag"}}],
      "scenes": [{"name": "early", "time": 0.25, "uniforms": {"u_seed": {"int": 7}}},
                 {"name": "late", "time": 2.0}]
    })");
    ASSERT_TRUE(r.ok) << allErrors(r);
    ASSERT_EQ(r.spec.scenes.size(), 2u);
    EXPECT_TRUE(r.spec.scenes[0].file.empty());
    EXPECT_FLOAT_EQ(r.spec.scenes[0].time, 0.25f);
    EXPECT_EQ(std::get<int>(r.spec.scenes[0].uniforms.at("u_seed")), 7);
    EXPECT_FLOAT_EQ(r.spec.scenes[1].time, 2.0f);
}

TEST_F(LabSpecParse, ExplicitClearOnADrawIntoPassIsKept) {
    json spec = json::parse(kBaseSpec);
    spec["passes"][2]["state"]["clear_depth"] = true;
    const LabSpecResult r = parseText(spec.dump());
    ASSERT_TRUE(r.ok) << allErrors(r);
    EXPECT_TRUE(r.spec.passes[2].state.clear_depth);
    EXPECT_FALSE(r.spec.passes[2].state.clear_color.has_value());
}

TEST_F(LabSpecParse, DrawIntoChainEndsAtTheTargetOwner) {
    // "extra" draws into "outline", which draws into "post": all three write post's target.
    json spec = json::parse(kBaseSpec);
    spec["passes"][3] = json::parse(R"({"name": "extra", "draw_into": "outline",
        "program": {"vertex": "phong.vert", "fragment": "outline.frag"}})");
    const LabSpecResult r = parseText(spec.dump());
    ASSERT_TRUE(r.ok) << allErrors(r);
    ASSERT_EQ(r.spec.passes.size(), 4u);
    EXPECT_EQ(r.spec.passes[3].draw_into, "outline");  // as written; the renderer follows the chain
    EXPECT_EQ(r.spec.passes[3].target.name, "post");
    EXPECT_FLOAT_EQ(r.spec.passes[3].target.scale, 0.5f);
    EXPECT_FALSE(r.spec.passes[3].state.clear_color.has_value());
    EXPECT_TRUE(r.spec.passes[3].graded);
    EXPECT_FALSE(r.spec.passes[2].graded);
}

TEST_F(LabSpecParse, FourLightsAreAllowed) {
    json spec = json::parse(kBaseSpec);
    spec["scenes"][0]["lights"][2] = {{"type", "point"}, {"position", {0, 1, 0}}};
    spec["scenes"][0]["lights"][3] = {{"type", "directional"}, {"direction", {1, 0, 0}}};
    const LabSpecResult r = parseText(spec.dump());
    ASSERT_TRUE(r.ok) << allErrors(r);
    EXPECT_EQ(r.spec.scenes[0].lights->size(), 4u);
}

TEST_F(LabSpecParse, LabFolderWithTrailingSlashIsNormalised) {
    const LabSpecResult r = shaderlab::parseLabSpecText(kMinimalSpec, kOrigin, lab_.string() + "/");
    ASSERT_TRUE(r.ok) << allErrors(r);
    EXPECT_EQ(fs::path(r.spec.lab_dir), lab_);
    EXPECT_EQ(fs::path(r.spec.labs_root), labs_);
}

// =============================================================================================
// One broken field at a time: each case edits the base spec with JSON pointers and expects a
// message with the given path and problem, and (count) exactly that many messages in all, so
// that one mistake does not cascade into a pile of follow-up errors.

struct Edit {
    const char* pointer;
    const char* value;  // JSON text; nullptr removes the member or element
};

struct BrokenCase {
    const char* name;
    std::vector<Edit> edits;
    const char* path;
    const char* problem;
    std::size_t count = 1;
};

void PrintTo(const BrokenCase& c, std::ostream* os) { *os << c.name; }

json applyEdits(json doc, const std::vector<Edit>& edits) {
    for (const Edit& e : edits) {
        const json::json_pointer ptr(e.pointer);
        if (e.value) {
            doc[ptr] = json::parse(e.value);
            continue;
        }
        json& parent = doc.at(ptr.parent_pointer());
        if (parent.is_array())
            parent.erase(std::stoul(ptr.back()));
        else
            parent.erase(ptr.back());
    }
    return doc;
}

const char* const kDelete = nullptr;

const std::vector<BrokenCase> kBrokenCases = {
    // top level
    {"SchemaMissing", {{"/schema", kDelete}}, "schema", "required field is missing"},
    {"SchemaUnsupported",
     {{"/schema", "2"}},
     "schema",
     "unsupported version 2; this framework reads version 1"},
    {"SchemaNotInteger", {{"/schema", "\"1\""}}, "schema", "expected an integer, got \"1\""},
    {"IdMissing", {{"/id", kDelete}}, "id", "required field is missing"},
    {"IdNotFolderName",
     {{"/id", "\"02-toon\""}},
     "id",
     "\"02-toon\" does not match the lab folder's name \"01-phong\""},
    {"IdBadCharacters", {{"/id", "\"01 phong\""}}, "id", "is not a valid name"},
    {"TitleNotString", {{"/title", "3"}}, "title", "expected a string, got 3"},
    {"TitleEmpty", {{"/title", "\"\""}}, "title", "must not be empty"},
    {"UnknownTopLevelKey", {{"/pases", "[]"}}, "pases", "unknown key (did you mean \"passes\"?)"},
    {"RootNotObject", {{"", "[]"}}, "", "expected an object, got an empty array"},
    {"ResolutionZero", {{"/resolution/0", "0"}}, "resolution[0]", "must be in [1, 4096], got 0"},
    {"ResolutionTooLarge", {{"/resolution/1", "5000"}}, "resolution[1]", "must be in [1, 4096], got 5000"},
    {"ResolutionFraction", {{"/resolution/0", "256.5"}}, "resolution[0]", "expected an integer, got 256.5"},
    {"ResolutionOneNumber",
     {{"/resolution", "[256]"}},
     "resolution",
     "expected an array of 2 integers [width, height], got an array of 1 element"},
    {"StudentFilesMissingFile",
     {{"/student_files", R"(["phong.frag", "nope.frag"])"}},
     "student_files[1]",
     "nope.frag: file not found"},
    {"StudentFilesEmpty", {{"/student_files", "[]"}}, "student_files", "must list at least one file"},
    {"StudentFilesDuplicate",
     {{"/student_files", R"(["phong.frag", "./phong.frag"])"}},
     "student_files[1]",
     "is already listed as student_files[0]"},
    {"StudentFilesNotArray",
     {{"/student_files", "\"phong.frag\""}},
     "student_files",
     "expected an array of strings, got \"phong.frag\""},
    {"StudentFilesEscape",
     {{"/student_files", R"(["../../outside.frag"])"}},
     "student_files[0]",
     "must not contain \"..\""},

    // passes
    {"PassesMissing", {{"/passes", kDelete}}, "passes", "required field is missing"},
    {"PassesEmpty", {{"/passes", "[]"}}, "passes", "must list at least one pass"},
    {"PassesNotArray", {{"/passes", "{}"}}, "passes", "expected an array of objects, got an empty object"},
    {"PassNotObject", {{"/passes/0", "\"shade\""}}, "passes[0]", "expected an object, got \"shade\"", 2},
    {"PassNameMissing", {{"/passes/0/name", kDelete}}, "passes[0].name", "required field is missing"},
    {"PassNameInvalid",
     {{"/passes/0/name", "\"shade pass\""}},
     "passes[0].name",
     "\"shade pass\" is not a valid name: use only letters, digits, '_' and '-'"},
    {"PassNameDuplicate",
     {{"/passes/2/name", "\"post\""}},
     "passes[2].name",
     "duplicate pass name \"post\", already used by passes[1]"},
    {"PassUnknownKey",
     {{"/passes/0/uniform", "{}"}},
     "passes[0].uniform",
     "unknown key (did you mean \"uniforms\"?)"},
    {"ProgramMissing", {{"/passes/0/program", kDelete}}, "passes[0].program", "required field is missing"},
    {"ProgramVertexMissing",
     {{"/passes/0/program/vertex", kDelete}},
     "passes[0].program.vertex",
     "required field is missing"},
    {"ProgramUnknownKey",
     {{"/passes/0/program/geometry", "\"x.geom\""}},
     "passes[0].program.geometry",
     "unknown key; allowed here: vertex, fragment"},
    {"ProgramFileMissing",
     {{"/passes/0/program/fragment", "\"nope.frag\""}},
     "passes[0].program.fragment",
     "nope.frag: file not found"},
    {"ProgramFileEscapes",
     {{"/passes/0/program/fragment", "\"../../outside.frag\""}},
     "passes[0].program.fragment",
     "must not contain \"..\""},
    {"ProgramFileAbsolute",
     {{"/passes/0/program/fragment", "\"/etc/hostname\""}},
     "passes[0].program.fragment",
     "is an absolute path"},
    {"ProgramFileIsFolder",
     {{"/passes/0/program/fragment", "\"textures\""}},
     "passes[0].program.fragment",
     "not a regular file"},
    {"DrawUnknown",
     {{"/passes/0/draw", "\"triangles\""}},
     "passes[0].draw",
     "expected one of \"scene\", \"fullscreen\", got \"triangles\""},
    {"GradedNotBool", {{"/passes/0/graded", "1"}}, "passes[0].graded", "expected true or false, got 1"},
    {"LastPassNotGraded",
     {{"/passes/2/graded", "false"}},
     "passes[2].graded",
     "the last pass is always graded"},

    // inputs
    {"InputUnknownTarget",
     {{"/passes/1/inputs/0/pass", "\"colour\""}},
     "passes[1].inputs[0].pass",
     "no pass has a target named \"colour\" (did you mean \"color\"?)"},
    {"InputOwnTarget",
     {{"/passes/1/inputs/0/pass", "\"post\""}},
     "passes[1].inputs[0].pass",
     "\"post\" is this pass's own target"},
    {"InputLaterPass",
     {{"/passes/0/inputs", R"([{"sampler": "u_prev", "pass": "post"}])"}},
     "passes[0].inputs[0].pass",
     "is the target of passes[1] (\"post\"), which runs after this pass"},
    {"InputPassNameInsteadOfTarget",
     {{"/passes/1/inputs/0/pass", "\"shade\""}},
     "passes[1].inputs[0].pass",
     "pass \"shade\" names its target \"color\""},
    {"InputDrawIntoPass",
     {{"/passes/3", R"({"name": "final", "draw": "fullscreen",
                        "program": {"vertex": "fullscreen.vert", "fragment": "post.frag"},
                        "inputs": [{"sampler": "u_x", "pass": "outline"}]})"}},
     "passes[3].inputs[0].pass",
     "pass \"outline\" has no target of its own (it draws into the target \"post\"); inputs name targets"},
    {"InputFeedbackLoop",
     {{"/passes/2/inputs", R"([{"sampler": "u_self", "pass": "post"}])"}},
     "passes[2].inputs[0].pass",
     "which this pass draws into; a pass cannot sample the image it renders to"},
    {"InputPassAndTexture",
     {{"/passes/1/inputs/0/texture", "\"textures/ramp.png\""}},
     "passes[1].inputs[0]",
     "give either \"pass\" or \"texture\", not both"},
    {"InputNeitherPassNorTexture",
     {{"/passes/1/inputs/0/pass", kDelete}},
     "passes[1].inputs[0]",
     "needs \"pass\" (the target of an earlier pass) or \"texture\""},
    {"InputTextureMissing",
     {{"/passes/1/inputs/1/texture", "\"textures/nope.png\""}},
     "passes[1].inputs[1].texture",
     "nope.png: file not found"},
    {"InputTextureOutsideLab",
     {{"/passes/1/inputs/1/texture", "\"../scenes/sphere.gltf\""}},
     "passes[1].inputs[1].texture",
     "must not contain \"..\""},
    {"InputsNotArray", {{"/passes/1/inputs", "{}"}}, "passes[1].inputs", "expected an array of objects"},
    {"SamplerMissing",
     {{"/passes/1/inputs/0/sampler", kDelete}},
     "passes[1].inputs[0].sampler",
     "required field is missing"},
    {"SamplerReservedPrefix",
     {{"/passes/1/inputs/0/sampler", "\"gl_Scene\""}},
     "passes[1].inputs[0].sampler",
     "names starting with \"gl_\" are reserved by GLSL"},
    {"SamplerNotIdentifier",
     {{"/passes/1/inputs/0/sampler", "\"2scene\""}},
     "passes[1].inputs[0].sampler",
     "\"2scene\" is not a valid GLSL identifier"},
    {"SamplerIsAFrameworkUniform",
     {{"/passes/1/inputs/0/sampler", "\"u_resolution\""}},
     "passes[1].inputs[0].sampler",
     "\"u_resolution\" is set by the framework (docs/student-contract.md); choose another name"},
    {"SamplerDuplicate",
     {{"/passes/1/inputs/1/sampler", "\"u_scene\""}},
     "passes[1].inputs[1].sampler",
     "sampler \"u_scene\" is already bound by inputs[0]"},
    {"SamplerAlsoAUniform",
     {{"/passes/1/uniforms", R"({"u_scene": 1})"}},
     "passes[1].inputs[0].sampler",
     "is also set in this pass's uniforms"},
    {"InputFilterUnknown",
     {{"/passes/1/inputs/1/filter", "\"bilinear\""}},
     "passes[1].inputs[1].filter",
     "expected one of \"nearest\", \"linear\", got \"bilinear\""},
    {"InputWrapUnknown",
     {{"/passes/1/inputs/1/wrap", "\"clamp_to_edge\""}},
     "passes[1].inputs[1].wrap",
     "expected one of \"clamp\", \"repeat\", \"mirror\", got \"clamp_to_edge\""},

    // targets and draw_into
    {"TargetFormatUnknown",
     {{"/passes/0/target/format", "\"rgb8\""}},
     "passes[0].target.format",
     "expected one of \"rgba8\", \"rgba16f\", \"rgba32f\", got \"rgb8\""},
    {"TargetSizeZero",
     {{"/passes/0/target/size", "[0, 64]"}},
     "passes[0].target.size[0]",
     "must be in [1, 4096], got 0"},
    {"TargetSizeTooLarge",
     {{"/passes/0/target/size", "[64, 8192]"}},
     "passes[0].target.size[1]",
     "must be in [1, 4096], got 8192"},
    {"TargetSizeAndScale",
     {{"/passes/1/target/size", "[64, 64]"}},
     "passes[1].target.scale",
     "cannot be combined with \"size\""},
    {"TargetScaleZero",
     {{"/passes/1/target/scale", "0"}},
     "passes[1].target.scale",
     "must be in (0, 4], got 0"},
    {"TargetScaleTooLarge",
     {{"/passes/1/target/scale", "4.5"}},
     "passes[1].target.scale",
     "must be in (0, 4], got 4.5"},
    {"TargetScaleBelowOnePixel",
     {{"/passes/1/target/scale", "0.001"}},
     "passes[1].target.scale",
     "0.256x0.128 pixels; each side must be between 1 and 4096"},
    {"TargetScaleAboveLimit",
     {{"/resolution", "[4096, 4096]"}, {"/passes/1/target/scale", "2"}},
     "passes[1].target.scale",
     "8192x8192 pixels"},
    {"TargetNameDuplicate",
     {{"/passes/1/target/name", "\"color\""}},
     "passes[1].target.name",
     "target name \"color\" is already the target of passes[0]"},
    {"TargetNamedAfterOtherPass",
     {{"/passes/0/target/name", "\"outline\""}, {"/passes/1/inputs/0/pass", "\"outline\""}},
     "passes[0].target.name",
     "target name \"outline\" is the name of another pass, passes[2]"},
    {"TargetNameInvalid",
     {{"/passes/0/target/name", "\"my color\""}},
     "passes[0].target.name",
     "is not a valid name",
     2},
    {"TargetAndDrawInto",
     {{"/passes/2/target", R"({"name": "extra"})"}},
     "passes[2].draw_into",
     "cannot be combined with \"target\""},
    {"DrawIntoUnknown",
     {{"/passes/2/draw_into", "\"pots\""}},
     "passes[2].draw_into",
     "no pass is named \"pots\" (did you mean \"post\"?)"},
    {"DrawIntoSelf",
     {{"/passes/2/draw_into", "\"outline\""}},
     "passes[2].draw_into",
     "a pass cannot draw into itself"},
    {"DrawIntoLaterPass",
     {{"/passes/0/target", kDelete},
      {"/passes/0/draw_into", "\"post\""},
      {"/passes/1/inputs/0", R"({"sampler": "u_scene", "texture": "textures/ramp.png"})"}},
     "passes[0].draw_into",
     "passes[1] (\"post\") runs after this pass"},
    {"InputFeedbackThroughADrawIntoChain",
     {{"/passes/3", R"({"name": "extra", "program": {"vertex": "phong.vert", "fragment": "outline.frag"},
                        "draw_into": "outline", "inputs": [{"sampler": "u_s", "pass": "post"}]})"}},
     "passes[3].inputs[0].pass",
     "reads target \"post\", which this pass draws into"},

    // render state
    {"StateCullUnknown",
     {{"/passes/2/state/cull", "\"sideways\""}},
     "passes[2].state.cull",
     "expected one of \"back\", \"front\", \"none\", got \"sideways\""},
    {"StateClearColorThreeNumbers",
     {{"/passes/0/state", R"({"clear_color": [0, 0, 0]})"}},
     "passes[0].state.clear_color",
     "expected an array of 4 numbers, got an array of 3 elements"},
    {"StateClearColorString",
     {{"/passes/0/state", R"({"clear_color": "black"})"}},
     "passes[0].state.clear_color",
     "expected an array of 4 numbers (RGBA) or null, got \"black\""},
    {"StateDepthFuncUnknown",
     {{"/passes/0/state", R"({"depth_func": "greater"})"}},
     "passes[0].state.depth_func",
     "expected one of \"less\", \"lequal\", \"always\", got \"greater\""},
    {"StateDepthTestNotBool",
     {{"/passes/0/state", R"({"depth_test": "yes"})"}},
     "passes[0].state.depth_test",
     "expected true or false, got \"yes\""},
    {"StateLineWidthZero",
     {{"/passes/2/state/line_width", "0"}},
     "passes[2].state.line_width",
     "must be in (0, 16], got 0"},
    {"StateBlendUnknown",
     {{"/passes/0/state", R"({"blend": "multiply"})"}},
     "passes[0].state.blend",
     "expected one of \"none\", \"alpha\", \"additive\", got \"multiply\""},
    {"StatePolygonModeUnknown",
     {{"/passes/2/state/polygon_mode", "\"wire\""}},
     "passes[2].state.polygon_mode",
     "expected one of \"fill\", \"line\", got \"wire\""},
    {"StateUnknownKey",
     {{"/passes/2/state/clearcolor", "[0, 0, 0, 1]"}},
     "passes[2].state.clearcolor",
     "unknown key (did you mean \"clear_color\"?)"},
    {"StateNotObject",
     {{"/passes/2/state", "\"default\""}},
     "passes[2].state",
     "expected an object, got \"default\""},

    // uniforms
    {"UniformReservedPrefix",
     {{"/passes/0/uniforms/gl_Color", "1"}},
     "passes[0].uniforms.gl_Color",
     "names starting with \"gl_\" are reserved by GLSL"},
    {"UniformNotIdentifier",
     {{"/passes/0/uniforms/u bad", "1"}},
     "passes[0].uniforms[\"u bad\"]",
     "is not a valid GLSL identifier"},
    {"UniformIsAFrameworkUniform",
     {{"/passes/0/uniforms/u_light_count", "{\"int\": 2}"}},
     "passes[0].uniforms.u_light_count",
     "is set by the framework"},
    {"SceneUniformIsTime",
     {{"/scenes/0/uniforms", R"({"u_time": 2})"}},
     "scenes[0].uniforms.u_time",
     "choose another name (a scene's \"time\" sets u_time)"},
    {"UniformArrayLength",
     {{"/passes/0/uniforms/u_x", "[1, 2, 3, 4, 5]"}},
     "passes[0].uniforms.u_x",
     "expected 2, 3 or 4 numbers (a vector) or 9 or 16 numbers (a column-major matrix), got an array of 5 "
     "elements"},
    {"UniformArrayElement",
     {{"/passes/0/uniforms/u_x", R"([1, "a"])"}},
     "passes[0].uniforms.u_x[1]",
     "expected a number, got \"a\""},
    {"UniformIntNotInteger",
     {{"/passes/0/uniforms/u_x", R"({"int": 2.5})"}},
     "passes[0].uniforms.u_x.int",
     "expected an integer, got 2.5"},
    {"UniformIntTooLarge",
     {{"/passes/0/uniforms/u_x", R"({"int": 3000000000})"}},
     "passes[0].uniforms.u_x.int",
     "does not fit a 32-bit integer"},
    {"UniformBoolNotBool",
     {{"/passes/0/uniforms/u_x", R"({"bool": 1})"}},
     "passes[0].uniforms.u_x.bool",
     "expected true or false, got 1"},
    {"UniformIntAndBool",
     {{"/passes/0/uniforms/u_x", R"({"int": 1, "bool": true})"}},
     "passes[0].uniforms.u_x",
     "give either \"int\" or \"bool\", not both"},
    {"UniformUnknownWrapper",
     {{"/passes/0/uniforms/u_x", R"({"float": 1})"}},
     "passes[0].uniforms.u_x.float",
     "unknown key; allowed here: int, bool"},
    {"UniformEmptyObject",
     {{"/passes/0/uniforms/u_x", "{}"}},
     "passes[0].uniforms.u_x",
     "expected {\"int\": <integer>} or {\"bool\": true|false}, got an empty object"},
    {"UniformString",
     {{"/passes/0/uniforms/u_x", "\"red\""}},
     "passes[0].uniforms.u_x",
     "expected a number, an array of 2, 3, 4, 9 or 16 numbers, {\"int\": n} or {\"bool\": b}, got \"red\""},
    {"UniformBareBool",
     {{"/passes/0/uniforms/u_x", "true"}},
     "passes[0].uniforms.u_x",
     "or {\"bool\": b}, got true"},
    {"UniformTooLargeForFloat",
     {{"/passes/0/uniforms/u_x", "1e39"}},
     "passes[0].uniforms.u_x",
     "is too large for a 32-bit float"},
    {"UniformsNotObject",
     {{"/passes/0/uniforms", "[1]"}},
     "passes[0].uniforms",
     "expected an object of uniform name: value, got an array of 1 element"},

    // scenes
    {"ScenesMissing", {{"/scenes", kDelete}}, "scenes", "required field is missing"},
    {"ScenesEmpty", {{"/scenes", "[]"}}, "scenes", "must list at least one scene"},
    {"SceneNameMissing", {{"/scenes/0/name", kDelete}}, "scenes[0].name", "required field is missing"},
    {"SceneNameDuplicate",
     {{"/scenes/1", R"({"name": "sphere", "file": "scenes/cube.glb"})"}},
     "scenes[1].name",
     "duplicate scene name \"sphere\", already used by scenes[0]"},
    {"SceneUnknownKey",
     {{"/scenes/0/lighting", "[]"}},
     "scenes[0].lighting",
     "unknown key (did you mean \"lights\"?)"},
    {"SceneFileNeededBySceneDraw",
     {{"/scenes/0/file", kDelete}},
     "scenes[0].file",
     "required field is missing: passes[0] (\"shade\") draws the scene"},
    {"SceneFileNotFound",
     {{"/scenes/0/file", "\"scenes/nope.gltf\""}},
     "scenes[0].file",
     "nope.gltf: file not found"},
    {"SceneFileIsRelativeToLabsRootNotLab",
     {{"/scenes/0/file", "\"local.gltf\""}},
     "scenes[0].file",
     "local.gltf: file not found"},
    {"SceneFileNotGltf",
     {{"/scenes/0/file", "\"scenes/readme.txt\""}},
     "scenes[0].file",
     "\"scenes/readme.txt\" is not a glTF file"},
    {"SceneFileEscapes",
     {{"/scenes/0/file", "\"../labs/outside.gltf\""}},
     "scenes[0].file",
     "must not contain \"..\""},
    {"SceneTimeNotNumber",
     {{"/scenes/0/time", "\"0.5\""}},
     "scenes[0].time",
     "expected a number, got \"0.5\""},
    {"SceneUniformIsASampler",
     {{"/scenes/0/uniforms", R"({"u_ramp": 1})"}},
     "scenes[0].uniforms.u_ramp",
     "is a sampler of passes[1] (\"post\")"},
    {"SceneUniformBadValue",
     {{"/scenes/0/uniforms", R"({"u_k": [1, 2, 3, 4, 5, 6]})"}},
     "scenes[0].uniforms.u_k",
     "expected 2, 3 or 4 numbers"},
    {"CameraFovTooWide",
     {{"/scenes/0/camera/fov_y_deg", "180"}},
     "scenes[0].camera.fov_y_deg",
     "must be in (0, 180), got 180"},
    {"CameraNearZero",
     {{"/scenes/0/camera/near", "0"}},
     "scenes[0].camera.near",
     "must be greater than 0, got 0"},
    {"CameraFarBeforeNear",
     {{"/scenes/0/camera/far", "0.05"}},
     "scenes[0].camera.far",
     "must be greater than near (0.1), got 0.05"},
    {"CameraUpZero",
     {{"/scenes/0/camera/up", "[0, 0, 0]"}},
     "scenes[0].camera.up",
     "must not be the zero vector"},
    {"CameraTargetAtPosition",
     {{"/scenes/0/camera/target", "[0, 0, 3]"}},
     "scenes[0].camera.target",
     "must differ from position"},
    {"CameraUpAlongViewDirection",
     {{"/scenes/0/camera/up", "[0, 0, 2]"}},
     "scenes[0].camera.up",
     "is parallel to the view direction"},
    {"CameraPositionTwoNumbers",
     {{"/scenes/0/camera/position", "[0, 0]"}},
     "scenes[0].camera.position",
     "expected an array of 3 numbers, got an array of 2 elements"},
    {"CameraUnknownKey",
     {{"/scenes/0/camera/fov", "45"}},
     "scenes[0].camera.fov",
     "unknown key (did you mean \"fov_y_deg\"?)"},
    {"LightTypeUnknown",
     {{"/scenes/0/lights/0/type", "\"spot\""}},
     "scenes[0].lights[0].type",
     "expected one of \"point\", \"directional\", got \"spot\""},
    {"LightTypeMissing",
     {{"/scenes/0/lights/0/type", kDelete}},
     "scenes[0].lights[0].type",
     "required field is missing"},
    {"PointLightWithoutPosition",
     {{"/scenes/0/lights/0/position", kDelete}},
     "scenes[0].lights[0].position",
     "required for a point light"},
    {"PointLightWithDirection",
     {{"/scenes/0/lights/0/direction", "[0, -1, 0]"}},
     "scenes[0].lights[0].direction",
     "only applies to directional lights"},
    {"DirectionalLightWithoutDirection",
     {{"/scenes/0/lights/1/direction", kDelete}},
     "scenes[0].lights[1].direction",
     "required for a directional light"},
    {"DirectionalLightZeroDirection",
     {{"/scenes/0/lights/1/direction", "[0, 0, 0]"}},
     "scenes[0].lights[1].direction",
     "must not be the zero vector"},
    {"DirectionalLightWithPosition",
     {{"/scenes/0/lights/1/position", "[1, 1, 1]"}},
     "scenes[0].lights[1].position",
     "only applies to point lights"},
    {"LightNegativeIntensity",
     {{"/scenes/0/lights/0/intensity", "-1"}},
     "scenes[0].lights[0].intensity",
     "must be at least 0, got -1"},
    {"LightNegativeColor",
     {{"/scenes/0/lights/0/color", "[1, -0.5, 1]"}},
     "scenes[0].lights[0].color[1]",
     "must be at least 0, got -0.5"},
    {"MoreThanFourLights",
     {{"/scenes/0/lights/2", R"({"type": "point", "position": [0, 1, 0]})"},
      {"/scenes/0/lights/3", R"({"type": "point", "position": [0, 2, 0]})"},
      {"/scenes/0/lights/4", R"({"type": "point", "position": [0, 3, 0]})"}},
     "scenes[0].lights",
     "has 5 lights; shaders receive at most 4 (SL_MAX_LIGHTS)"},
    {"LightsNotArray",
     {{"/scenes/0/lights", "{}"}},
     "scenes[0].lights",
     "expected an array of objects, got an empty object"},

    // grading
    {"GradingPointsZero", {{"/grading/points", "0"}}, "grading.points", "must be greater than 0, got 0"},
    {"GradingPsnrNegative",
     {{"/grading/psnr_min_db", "-1"}},
     "grading.psnr_min_db",
     "must be in [0, 100], got -1"},
    {"GradingSsimAboveOne", {{"/grading/ssim_min", "1.5"}}, "grading.ssim_min", "must be in [0, 1], got 1.5"},
    {"GradingFlipAboveOne",
     {{"/grading/flip_mean_max", "1.2"}},
     "grading.flip_mean_max",
     "must be in [0, 1], got 1.2"},
    {"GradingMismatchNegative",
     {{"/grading/mismatch_max", "-0.1"}},
     "grading.mismatch_max",
     "must be in [0, 1], got -0.1"},
    {"GradingToleranceAboveOne",
     {{"/grading/pixel_tolerance", "2"}},
     "grading.pixel_tolerance",
     "must be in [0, 1], got 2"},
    {"GradingThresholdNotNumber",
     {{"/grading/ssim_min", "\"high\""}},
     "grading.ssim_min",
     "expected a number, got \"high\""},
    {"GradingUnknownKey",
     {{"/grading/psnr_min", "30"}},
     "grading.psnr_min",
     "unknown key (did you mean \"psnr_min_db\"?)"},
    {"GradingNotObject", {{"/grading", "10"}}, "grading", "expected an object, got 10"},
};

class LabSpecBroken : public LabSpecFixture, public ::testing::WithParamInterface<BrokenCase> {};

TEST_P(LabSpecBroken, IsRefusedWithPathAndProblem) {
    const BrokenCase& c = GetParam();
    const LabSpecResult r = parseText(applyEdits(json::parse(kBaseSpec), c.edits).dump(2));
    EXPECT_FALSE(r.ok);
    EXPECT_TRUE(hasError(r, c.path, c.problem));
    EXPECT_EQ(r.errors.size(), c.count) << allErrors(r);
}

INSTANTIATE_TEST_SUITE_P(LabSpec, LabSpecBroken, ::testing::ValuesIn(kBrokenCases),
                         [](const ::testing::TestParamInfo<BrokenCase>& p) {
                             return std::string(p.param.name);
                         });

// The table only means something if the unedited base spec is valid.
using LabSpecBase = LabSpecFixture;

TEST_F(LabSpecBase, TheBaseSpecOfTheErrorTableIsValid) {
    const LabSpecResult r = parseText(kBaseSpec);
    EXPECT_TRUE(r.ok) << allErrors(r);
    EXPECT_TRUE(r.errors.empty());
}

// =============================================================================================
// Several problems at once, and limits that do not fit the table

using LabSpecErrors = LabSpecFixture;

TEST_F(LabSpecErrors, ReportsEveryProblemNotJustTheFirst) {
    json spec = json::parse(kBaseSpec);
    spec["schema"] = 3;
    spec["passes"][0]["state"] = {{"cull", "sideways"}};
    spec["passes"][1]["inputs"][0]["pass"] = "nowhere";
    spec["scenes"][0]["camera"]["fov_y_deg"] = -5;
    spec["grading"]["ssim_min"] = 2;
    const LabSpecResult r = parseText(spec.dump());
    EXPECT_FALSE(r.ok);
    EXPECT_TRUE(hasError(r, "schema", "unsupported version 3"));
    EXPECT_TRUE(hasError(r, "passes[0].state.cull", "got \"sideways\""));
    EXPECT_TRUE(hasError(r, "passes[1].inputs[0].pass", "no pass has a target named \"nowhere\""));
    EXPECT_TRUE(hasError(r, "scenes[0].camera.fov_y_deg", "must be in (0, 180), got -5"));
    EXPECT_TRUE(hasError(r, "grading.ssim_min", "must be in [0, 1], got 2"));
    EXPECT_EQ(r.errors.size(), 5u) << allErrors(r);
}

TEST_F(LabSpecErrors, MoreInputsThanTextureUnitsAreRefused) {
    json spec = json::parse(kBaseSpec);
    json inputs = json::array();
    for (int i = 0; i < 17; ++i)
        inputs.push_back({{"sampler", "u_t" + std::to_string(i)}, {"texture", "textures/ramp.png"}});
    spec["passes"][1]["inputs"] = inputs;
    const LabSpecResult r = parseText(spec.dump());
    EXPECT_FALSE(r.ok);
    EXPECT_TRUE(hasError(r, "passes[1].inputs", "has 17 inputs; at most 16 can be bound at once"));

    inputs.erase(16);  // 16 is fine
    spec["passes"][1]["inputs"] = inputs;
    const LabSpecResult fine = parseText(spec.dump());
    EXPECT_TRUE(fine.ok) << allErrors(fine);
}

TEST_F(LabSpecErrors, FileLinkedFromOutsideTheLabIsRefused) {
    fs::create_symlink(root_ / "outside.frag", lab_ / "linked.frag");
    json spec = json::parse(kBaseSpec);
    spec["passes"][0]["program"]["fragment"] = "linked.frag";
    const LabSpecResult r = parseText(spec.dump());
    EXPECT_FALSE(r.ok);
    EXPECT_TRUE(hasError(r, "passes[0].program.fragment", "resolves outside"));
}

TEST_F(LabSpecErrors, MissingLabFolderIsReportedOnceForText) {
    const LabSpecResult r =
        shaderlab::parseLabSpecText(kMinimalSpec, kOrigin, (labs_ / "99-nothing").string());
    EXPECT_FALSE(r.ok);
    ASSERT_EQ(r.errors.size(), 2u) << allErrors(r);  // the folder, and the id that does not match it
    EXPECT_TRUE(hasError(r, "", "the lab folder " + (labs_ / "99-nothing").string() + " does not exist"));
    EXPECT_TRUE(hasError(r, "id", "does not match the lab folder's name \"99-nothing\""));
}

// =============================================================================================
// JSON syntax

using LabSpecSyntax = LabSpecFixture;

TEST_F(LabSpecSyntax, ParseErrorNamesLineAndColumn) {
    const LabSpecResult r = parseText("{\n  \"schema\": 1,\n  \"id\": \"01-phong\",\n  \"passes\": [,]\n}\n");
    EXPECT_FALSE(r.ok);
    ASSERT_EQ(r.errors.size(), 1u) << allErrors(r);
    EXPECT_EQ(r.errors[0].rfind(std::string(kOrigin) + ": line 4, column 14: syntax error", 0), 0u)
        << r.errors[0];
    EXPECT_NE(r.errors[0].find("unexpected ','"), std::string::npos) << r.errors[0];
}

TEST_F(LabSpecSyntax, ColumnCountsCharactersNotBytes) {
    // "Ü" is two bytes in UTF-8; the stray x is the 16th character of the line.
    const LabSpecResult r = parseText("{\"title\": \"\xC3\x9C\", x}");
    ASSERT_EQ(r.errors.size(), 1u) << allErrors(r);
    EXPECT_EQ(r.errors[0].rfind(std::string(kOrigin) + ": line 1, column 16: ", 0), 0u) << r.errors[0];
}

TEST_F(LabSpecSyntax, TruncatedFileNamesTheEnd) {
    const LabSpecResult r = parseText("{\n  \"schema\": 1,\n");
    ASSERT_EQ(r.errors.size(), 1u) << allErrors(r);
    EXPECT_EQ(r.errors[0].rfind(std::string(kOrigin) + ": line 3, column 1: ", 0), 0u) << r.errors[0];
    EXPECT_NE(r.errors[0].find("unexpected end of input"), std::string::npos) << r.errors[0];
}

TEST_F(LabSpecSyntax, EmptyTextIsASyntaxError) {
    const LabSpecResult r = parseText("");
    EXPECT_FALSE(r.ok);
    ASSERT_EQ(r.errors.size(), 1u) << allErrors(r);
    EXPECT_EQ(r.errors[0].rfind(std::string(kOrigin) + ": line 1, column 1: ", 0), 0u) << r.errors[0];
}

TEST_F(LabSpecSyntax, CommentsAreNotJson) {
    const LabSpecResult r = parseText("{\n  // a comment\n  \"schema\": 1\n}");
    EXPECT_FALSE(r.ok);
    ASSERT_EQ(r.errors.size(), 1u) << allErrors(r);
    EXPECT_EQ(r.errors[0].rfind(std::string(kOrigin) + ": line 2, column ", 0), 0u) << r.errors[0];
}

TEST_F(LabSpecSyntax, NumberOverflowNamesItsLine) {
    json spec = json::parse(kBaseSpec);
    std::string text = spec.dump(2);
    const std::string needle = "\"time\": 0.5";
    ASSERT_NE(text.find(needle), std::string::npos);
    text.replace(text.find(needle), needle.size(), "\"time\": 1e999");
    std::size_t line = 1;
    for (std::size_t i = 0; i < text.find("1e999"); ++i) line += text[i] == '\n';
    const LabSpecResult r = parseText(text);
    ASSERT_EQ(r.errors.size(), 1u) << allErrors(r);
    EXPECT_NE(r.errors[0].find(": line " + std::to_string(line) + ", column "), std::string::npos)
        << r.errors[0];
    EXPECT_NE(r.errors[0].find("1e999"), std::string::npos) << r.errors[0];
}

TEST_F(LabSpecSyntax, DuplicateKeyIsAnErrorNamingItsPath) {
    // nlohmann keeps only the last "uniforms"; the first block would silently vanish.
    const LabSpecResult r = parseText(R"({
      "schema": 1, "id": "01-phong",
      "passes": [{"name": "shade", "program": {"vertex": "phong.vert", "fragment": "phong.frag"},
                  "uniforms": {"u_a": 1}, "uniforms": {"u_b": 2}}],
      "scenes": [{"name": "sphere", "file": "scenes/sphere.gltf"},
                 {"name": "s2", "name": "s3", "file": "scenes/cube.glb"}]
    })");
    EXPECT_FALSE(r.ok);
    EXPECT_TRUE(hasError(r, "passes[0].uniforms", "duplicate key"));
    EXPECT_TRUE(hasError(r, "scenes[1].name", "duplicate key"));
    EXPECT_EQ(r.errors.size(), 2u) << allErrors(r);
}

// =============================================================================================
// Unknown keys

using LabSpecSuggest = LabSpecFixture;

TEST_F(LabSpecSuggest, UnknownKeySuggestsTheClosestKnownKey) {
    json spec = json::parse(kBaseSpec);
    spec["passes"][0]["uniform"] = spec["passes"][0]["uniforms"];
    spec["passes"][0].erase("uniforms");
    spec["passes"][0]["target"]["fromat"] = "rgba8";
    spec["scenes"][0]["camera"]["postion"] = {0, 0, 3};
    const LabSpecResult r = parseText(spec.dump());
    EXPECT_FALSE(r.ok);
    EXPECT_TRUE(hasError(r, "passes[0].uniform", "unknown key (did you mean \"uniforms\"?)"));
    EXPECT_TRUE(hasError(r, "passes[0].target.fromat", "unknown key (did you mean \"format\"?)"));
    EXPECT_TRUE(hasError(r, "scenes[0].camera.postion", "unknown key (did you mean \"position\"?)"));
    EXPECT_EQ(r.errors.size(), 3u) << allErrors(r);
}

TEST_F(LabSpecSuggest, UnknownKeyWithNothingCloseListsTheAllowedKeys) {
    json spec = json::parse(kBaseSpec);
    spec["grading"]["zebra"] = 1;
    const LabSpecResult r = parseText(spec.dump());
    EXPECT_TRUE(
        hasError(r, "grading.zebra",
                 "unknown key; allowed here: points, psnr_min_db, ssim_min, flip_mean_max, mismatch_max, "
                 "pixel_tolerance"));
}

// =============================================================================================
// Reading lab.json from disk

using LabSpecFile = LabSpecFixture;

TEST_F(LabSpecFile, MissingLabJsonNamesThePath) {
    const LabSpecResult r = shaderlab::parseLabSpec(lab_.string());
    EXPECT_FALSE(r.ok);
    ASSERT_EQ(r.errors.size(), 1u) << allErrors(r);
    EXPECT_NE(r.errors[0].find((lab_ / "lab.json").string()), std::string::npos) << r.errors[0];
    EXPECT_NE(r.errors[0].find("file not found"), std::string::npos) << r.errors[0];
    EXPECT_EQ(fs::path(r.spec.lab_dir), lab_);
}

TEST_F(LabSpecFile, MissingLabFolderNamesIt) {
    const std::string missing = (labs_ / "42-nothing").string();
    const LabSpecResult r = shaderlab::parseLabSpec(missing);
    EXPECT_FALSE(r.ok);
    ASSERT_EQ(r.errors.size(), 1u) << allErrors(r);
    EXPECT_NE(r.errors[0].find("the lab folder " + missing + " does not exist"), std::string::npos)
        << r.errors[0];
    EXPECT_EQ(fs::path(r.spec.lab_dir), labs_ / "42-nothing");
    EXPECT_EQ(fs::path(r.spec.labs_root), labs_);
}

TEST_F(LabSpecFile, FileOverOneMebibyteIsRefused) {
    std::string text = kMinimalSpec;
    text.insert(text.size() - 1, std::string((1u << 20) + 1 - text.size(), ' '));  // still valid JSON
    ASSERT_EQ(text.size(), (1u << 20) + 1);
    writeFile(lab_ / "lab.json", text);
    const LabSpecResult r = shaderlab::parseLabSpec(lab_.string());
    EXPECT_FALSE(r.ok);
    ASSERT_EQ(r.errors.size(), 1u) << allErrors(r);
    EXPECT_NE(r.errors[0].find("limit"), std::string::npos) << r.errors[0];

    const LabSpecResult from_text = parseText(text);  // the text entry point has the same cap
    EXPECT_FALSE(from_text.ok);
    EXPECT_TRUE(hasError(from_text, "", "more than the limit of 1048576"));

    text.erase(0, 1);
    text.front() = '{';  // exactly 1 MiB: accepted
    writeFile(lab_ / "lab.json", text);
    const LabSpecResult at_limit = shaderlab::parseLabSpec(lab_.string());
    EXPECT_TRUE(at_limit.ok) << allErrors(at_limit);
}

TEST_F(LabSpecFile, ErrorsNameTheFileTheyCameFrom) {
    writeFile(lab_ / "lab.json", R"({"schema": 1, "id": "01-phong", "passes": []})");
    const LabSpecResult r = shaderlab::parseLabSpec(lab_.string());
    EXPECT_FALSE(r.ok);
    ASSERT_FALSE(r.errors.empty());
    const std::string origin = (lab_ / "lab.json").string();
    for (const std::string& e : r.errors) EXPECT_EQ(e.rfind(origin + ": ", 0), 0u) << e;
    EXPECT_EQ(fs::path(r.spec.lab_dir), lab_);
}

}  // namespace
