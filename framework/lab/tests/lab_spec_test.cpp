// Tests of the lab.json parser, schema 2 (framework/lab/src/lab_spec.cpp), against its contract,
// docs/lab-format.md: a valid spec becomes the expected typed values, defaults included (those
// that depend on other fields too); every kind of mistake, one at a time, is refused with a
// message "<origin>: <json path>: <problem>"; several mistakes give several messages; syntax
// errors name a line and column; the limits on size, nesting and strings hold without a crash;
// the complete and the smallest example of docs/lab-format.md parse; the compiled-in JSON Schema
// is docs/lab.schema.json. Each test builds its own labs root under the temp directory; nothing
// here renders.
#include "shaderlab/lab/lab_spec.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "shaderlab/lab/json_schema_check.h"

namespace fs = std::filesystem;
using nlohmann::json;
using shaderlab::LabSpecResult;

namespace {

const char* const kOrigin = "labs/01-phong/lab.json";

// A valid lab that the error table below breaks one mistake at a time: a shadow pass into a
// sampled depth, a fullscreen pass into a cube target, a scene pass into a two-attachment target
// reading both, a repeated blur that reads its own half-size target, and a last pass from the same
// template; two goals; a scene with lights and one graded at two times.
const char* const kBaseSpec = R"({
  "schema": 2,
  "id": "01-phong",
  "title": "The base of the error table",
  "resolution": [256, 128],
  "goals": [
    {"id": "shading", "title": "Shade into the G-buffer", "points": 6, "passes": ["shade"]},
    {"id": "post", "title": "Blur it", "points": 4, "passes": ["final"]}
  ],
  "targets": {
    "gbuf": {"format": "rgba16f", "attachments": ["albedo", "normal"]},
    "shadow": {"size": [64, 64], "depth": "texture"},
    "half": {"scale": 0.5, "depth": "none"},
    "env": {"type": "cube", "size": [32, 32], "depth": "none"}
  },
  "templates": {
    "post": {"program": {"vertex": "shared/fullscreen.vert", "fragment": "post.frag"}, "draw": "fullscreen"}
  },
  "passes": [
    {"name": "shadow", "program": {"vertex": "phong.vert", "fragment": "depth.frag"}, "target": "shadow",
     "camera": {"light": 0}},
    {"name": "sky", "extends": "post", "program": {"fragment": "sky.frag"}, "target": "env"},
    {"name": "shade", "program": {"vertex": "phong.vert", "fragment": "phong.frag"}, "target": "gbuf",
     "inputs": {"u_shadow": "shadow.depth", "u_env": "env", "u_ramp": {"texture": "ramp.png"}},
     "uniforms": {"u_shininess": 32, "u_light_matrix": "@shadow.view_projection"},
     "graded": true},
    {"name": "blur", "extends": "post", "target": "half",
     "inputs": {"u_image": "gbuf.albedo", "u_prev": "half"}, "repeat": 4},
    {"name": "final", "extends": "post", "inputs": {"u_image": "half", "u_normal": "gbuf.normal"}}
  ],
  "scenes": [
    {"name": "sphere", "file": "scenes/sphere.gltf",
     "camera": {"position": [0, 0, 3], "target": [0, 0, 0], "up": [0, 1, 0], "near": 0.1, "far": 100},
     "lights": [{"type": "point", "position": [2, 2, 2]}, {"type": "directional", "direction": [0, -1, 0]}]},
    {"name": "teapot", "file": "scenes/teapot.gltf", "times": [0, 1], "repeats": {"blur": 2}}
  ],
  "grading": {"psnr_min_db": 30}
})";

// The smallest valid file of docs/lab-format.md (the test below also reads it from there).
const char* const kMinimalSpec = R"({
  "schema": 2,
  "id": "01-phong",
  "passes": [{"name": "shade", "program": {"vertex": "phong.vert", "fragment": "phong.frag"}}],
  "scenes": [{"name": "sphere", "file": "scenes/sphere.gltf"}]
})";

std::string sanitized(std::string s) {
    for (char& c : s)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    return s;
}

void writeFile(const fs::path& p, const std::string& text) {
    fs::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << text;
}

std::string readText(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

std::string allErrors(const LabSpecResult& r) {
    std::string s;
    for (const std::string& e : r.errors) s += "\n  " + e;
    return s.empty() ? " (none)" : s;
}

// Whether some message reads "<origin>: <path>: ..." and contains `problem` after the path.
::testing::AssertionResult hasError(const LabSpecResult& r, const std::string& path,
                                    const std::string& problem, const std::string& origin = kOrigin) {
    const std::string prefix = origin + ": " + (path.empty() ? "" : path + ": ");
    for (const std::string& e : r.errors)
        if (e.rfind(prefix, 0) == 0 && e.find(problem, prefix.size()) != std::string::npos)
            return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "no error starting with \"" << prefix << "\" and containing \""
                                         << problem << "\"; errors were:" << allErrors(r);
}

const shaderlab::PassInput* inputOf(const shaderlab::PassSpec& p, const std::string& sampler) {
    for (const shaderlab::PassInput& in : p.inputs)
        if (in.sampler == sampler) return &in;
    return nullptr;
}

const shaderlab::UniformSetting* uniformOf(const shaderlab::UniformList& list, const std::string& name) {
    for (const shaderlab::UniformSetting& u : list)
        if (u.name == name) return &u;
    return nullptr;
}

using Clears = std::vector<std::optional<glm::vec4>>;
const glm::vec4 kBlack(0.0f, 0.0f, 0.0f, 1.0f);

// A labs root in the temp directory with the lab folder 01-phong holding every file the specs
// here name, the course's shared folder, the scenes, and a file outside the labs root.
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
        for (const char* f : {"phong.vert", "phong.frag", "depth.frag", "sky.frag", "post.frag", "final.frag",
                              "blur.frag", "scene.vert", "gbuffer.frag", "outline.frag", "combine.frag",
                              "advect.frag", "particles.vert", "particles.frag"})
            writeFile(lab_ / f, "// shader\n");
        for (const char* f : {"ramp.png", "volume.png"}) writeFile(lab_ / f, "not really a png");
        for (const char* face : {"px", "nx", "py", "ny", "pz", "nz"}) {
            writeFile(lab_ / "sky" / (std::string(face) + ".png"), "face");
            if (std::string(face) != "ny") writeFile(lab_ / "partial" / (std::string(face) + ".png"), "face");
        }
        writeFile(labs_ / "shared" / "fullscreen.vert", "// shared\n");
        for (const char* f : {"sphere.gltf", "teapot.gltf", "ground_plane.gltf", "cube.glb"})
            writeFile(labs_ / "scenes" / f, "{}");
        writeFile(root_ / "outside.frag", "// outside every lab\n");
    }
    void TearDown() override { fs::remove_all(root_); }

    LabSpecResult parseText(const std::string& text) const {
        return shaderlab::parseLabSpecText(text, kOrigin, lab_.string());
    }
    LabSpecResult parseJson(const json& doc) const { return parseText(doc.dump(2)); }

    fs::path root_, labs_, lab_;
};

// =============================================================================================
// Valid specs

using LabSpecParse = LabSpecFixture;

TEST_F(LabSpecParse, TheBaseSpecOfTheErrorTableIsValid) {
    const LabSpecResult r = parseText(kBaseSpec);
    EXPECT_TRUE(r.ok) << allErrors(r);
    EXPECT_TRUE(r.errors.empty());
}

TEST_F(LabSpecParse, FullFixtureGivesTypedValues) {
    fs::copy_file(fs::path(SHADERLAB_TEST_DATA) / "labspec" / "full.json", lab_ / "lab.json");
    const LabSpecResult r = shaderlab::parseLabSpec(lab_.string());
    ASSERT_TRUE(r.ok) << allErrors(r);
    const shaderlab::LabSpec& s = r.spec;
    using namespace shaderlab;

    EXPECT_EQ(s.schema, 2);
    EXPECT_EQ(s.id, "01-phong");
    EXPECT_EQ(s.title, "Every feature");
    EXPECT_EQ(fs::path(s.lab_dir), lab_);
    EXPECT_TRUE(fs::path(s.lab_dir).is_absolute());
    EXPECT_EQ(fs::path(s.labs_root), labs_);
    EXPECT_EQ(s.width, 320);
    EXPECT_EQ(s.height, 240);
    // Program files in pass order, each once, shared/ ones left out.
    EXPECT_EQ(s.student_files,
              (std::vector<std::string>{"scene.vert", "depth.frag", "sky.frag", "gbuffer.frag",
                                        "outline.frag", "combine.frag", "advect.frag", "particles.vert",
                                        "particles.frag", "blur.frag", "final.frag"}));

    // Targets: five top-level ones and the two that passes own (lit, sim) plus final's default one.
    ASSERT_EQ(s.targets.size(), 8u);
    const TargetSpec* shadow_t = s.findTarget("shadow");
    ASSERT_NE(shadow_t, nullptr);
    EXPECT_EQ(shadow_t->width, 128);
    EXPECT_EQ(shadow_t->height, 128);
    EXPECT_EQ(shadow_t->depth, DepthMode::Texture);
    EXPECT_EQ(shadow_t->attachments, (std::vector<std::string>{"color"}));
    EXPECT_EQ(shadow_t->format, TargetFormat::RGBA32F);
    EXPECT_EQ(shadow_t->path, "targets.shadow");
    const TargetSpec* env = s.findTarget("env");
    ASSERT_NE(env, nullptr);
    EXPECT_EQ(env->type, TargetType::Cube);
    EXPECT_EQ(env->width, 32);
    EXPECT_EQ(env->height, 32);
    EXPECT_EQ(env->depth, DepthMode::None);
    EXPECT_EQ(env->format, TargetFormat::RGBA16F);
    EXPECT_EQ(env->filter, TextureFilter::Mipmap);
    const TargetSpec* gbuffer_t = s.findTarget("gbuffer");
    ASSERT_NE(gbuffer_t, nullptr);
    EXPECT_EQ(gbuffer_t->attachments, (std::vector<std::string>{"albedo", "normal"}));
    EXPECT_EQ(gbuffer_t->width, 320);  // no size, no scale: the lab resolution
    EXPECT_EQ(gbuffer_t->height, 240);
    EXPECT_EQ(gbuffer_t->depth, DepthMode::Buffer);
    EXPECT_EQ(gbuffer_t->filter, TextureFilter::Nearest);
    EXPECT_EQ(gbuffer_t->wrap, TextureWrap::Repeat);
    const TargetSpec* half_a = s.findTarget("half_a");
    ASSERT_NE(half_a, nullptr);
    EXPECT_FLOAT_EQ(half_a->scale, 0.25f);
    EXPECT_EQ(half_a->width, 80);  // scale times the resolution
    EXPECT_EQ(half_a->height, 60);
    EXPECT_EQ(half_a->type, TargetType::Texture2D);
    EXPECT_EQ(half_a->filter, TextureFilter::Linear);
    EXPECT_EQ(half_a->wrap, TextureWrap::ClampToEdge);
    const TargetSpec* half_b = s.findTarget("half_b");
    ASSERT_NE(half_b, nullptr);
    EXPECT_EQ(half_b->width, 160);
    EXPECT_EQ(half_b->height, 120);
    EXPECT_EQ(half_b->format, TargetFormat::SRGB8);
    EXPECT_EQ(half_b->wrap, TextureWrap::MirroredRepeat);
    const TargetSpec* lit = s.findTarget("lit");  // owned by combine, named by the object
    ASSERT_NE(lit, nullptr);
    EXPECT_EQ(lit->format, TargetFormat::RGBA8);
    EXPECT_EQ(lit->width, 160);
    EXPECT_EQ(lit->height, 120);
    EXPECT_EQ(lit->depth, DepthMode::None);
    EXPECT_EQ(lit->path, "passes[4].target");
    const TargetSpec* sim = s.findTarget("sim");
    ASSERT_NE(sim, nullptr);
    EXPECT_EQ(sim->width, 64);
    EXPECT_EQ(sim->height, 32);
    EXPECT_FLOAT_EQ(sim->scale, 1.0f);
    const TargetSpec* final_t = s.findTarget("final");  // a pass without "target" owns a default one
    ASSERT_NE(final_t, nullptr);
    EXPECT_EQ(final_t->width, 320);
    EXPECT_EQ(final_t->height, 240);
    EXPECT_EQ(final_t->format, TargetFormat::RGBA32F);
    EXPECT_EQ(final_t->depth, DepthMode::Buffer);
    EXPECT_EQ(s.findTarget("nothing"), nullptr);

    ASSERT_EQ(s.passes.size(), 10u);
    std::vector<std::string> names;
    for (const PassSpec& p : s.passes) names.push_back(p.name);
    EXPECT_EQ(names, (std::vector<std::string>{"shadow", "sky", "gbuffer", "outline", "combine", "advect",
                                               "project", "blur_h", "blur_v", "final"}));

    const PassSpec& shadow = s.passes[0];
    EXPECT_EQ(shadow.path, "passes[0]");
    EXPECT_EQ(shadow.program.vertex, "scene.vert");
    EXPECT_EQ(shadow.program.fragment, "depth.frag");
    EXPECT_EQ(shadow.draw, DrawKind::Scene);
    EXPECT_EQ(shadow.target, "shadow");
    EXPECT_EQ(shadow.camera.light, 0);
    EXPECT_EQ(shadow.camera.z_near, 0.5f);
    EXPECT_EQ(shadow.camera.z_far, 20.0f);
    EXPECT_FALSE(shadow.camera.position.has_value());
    EXPECT_TRUE(shadow.camera.any());
    EXPECT_EQ(shadow.state.cull, CullMode::Front);
    EXPECT_EQ(shadow.state.clear_colors, (Clears{kBlack}));  // the first pass drawing into shadow
    EXPECT_TRUE(shadow.state.clear_depth);
    EXPECT_TRUE(shadow.state.depth_test);
    EXPECT_TRUE(shadow.state.depth_write);
    EXPECT_TRUE(shadow.graded.empty());
    EXPECT_EQ(shadow.loop, -1);

    const PassSpec& sky = s.passes[1];  // extends "post": the template's vertex, the pass's fragment
    EXPECT_EQ(sky.program.vertex, "shared/fullscreen.vert");
    EXPECT_EQ(sky.program.fragment, "sky.frag");
    EXPECT_EQ(sky.draw, DrawKind::Fullscreen);
    EXPECT_EQ(sky.target, "env");
    EXPECT_FALSE(sky.state.depth_test);  // fullscreen, and the target has no depth
    EXPECT_FALSE(sky.state.depth_write);
    EXPECT_FALSE(sky.state.clear_depth);
    EXPECT_EQ(sky.state.clear_colors, (Clears{kBlack}));
    EXPECT_EQ(sky.state.blend, BlendMode::None);
    ASSERT_EQ(sky.uniforms.size(), 1u);  // from the template
    EXPECT_EQ(sky.uniforms[0].name, "u_gain");
    EXPECT_EQ(sky.uniforms[0].value, json(1));
    EXPECT_EQ(sky.uniforms[0].path, "passes[1].uniforms.u_gain");
    ASSERT_EQ(sky.inputs.size(), 1u);
    const PassInput& faces = sky.inputs[0];
    EXPECT_EQ(faces.sampler, "u_faces");
    EXPECT_EQ(faces.source, InputSource::Cube);
    EXPECT_EQ(faces.cube_files, (std::vector<std::string>{"sky/px.png", "sky/nx.png", "sky/py.png",
                                                          "sky/ny.png", "sky/pz.png", "sky/nz.png"}));
    EXPECT_TRUE(faces.srgb);
    EXPECT_EQ(faces.path, "passes[1].inputs.u_faces");

    const PassSpec& gbuffer = s.passes[2];
    EXPECT_EQ(gbuffer.target, "gbuffer");
    ASSERT_EQ(gbuffer.state.clear_colors.size(), 2u);  // one per attachment
    EXPECT_EQ(gbuffer.state.clear_colors[0], glm::vec4(0.1f, 0.2f, 0.3f, 1.0f));
    EXPECT_FALSE(gbuffer.state.clear_colors[1].has_value());  // "normal": null keeps what is there
    EXPECT_TRUE(gbuffer.state.clear_depth);
    EXPECT_TRUE(gbuffer.state.depth_test);
    EXPECT_TRUE(gbuffer.state.depth_write);
    EXPECT_EQ(gbuffer.state.depth_func, DepthFunc::LessEqual);
    EXPECT_EQ(gbuffer.graded, (std::vector<std::string>{"normal"}));
    EXPECT_EQ(gbuffer.compare, CompareMode::Hdr);            // graded, a float target, not the last pass
    EXPECT_FLOAT_EQ(gbuffer.thresholds.psnr_min_db, 28.0f);  // the lab's
    ASSERT_EQ(gbuffer.uniforms.size(), 9u);
    const UniformSetting* shininess = uniformOf(gbuffer.uniforms, "u_shininess");
    ASSERT_NE(shininess, nullptr);
    EXPECT_EQ(shininess->value, json(32.5));
    EXPECT_EQ(shininess->path, "passes[2].uniforms.u_shininess");
    const UniformSetting* levels = uniformOf(gbuffer.uniforms, "u_levels");
    ASSERT_NE(levels, nullptr);
    EXPECT_TRUE(levels->value.is_number_integer());  // stays JSON: the shader's type decides
    EXPECT_EQ(uniformOf(gbuffer.uniforms, "u_rim")->value, json(true));
    EXPECT_EQ(uniformOf(gbuffer.uniforms, "u_tint")->value, json::parse("[1, 0.5, 0.2]"));
    EXPECT_EQ(uniformOf(gbuffer.uniforms, "u_xform")->value,
              json::parse("[[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [2, 0, 0, 1]]"));
    EXPECT_EQ(uniformOf(gbuffer.uniforms, "u_material")->value,
              json::parse(R"({"color": [1, 0, 0], "shininess": 32})"));
    EXPECT_EQ(uniformOf(gbuffer.uniforms, "u_lights")->value,
              json::parse(R"([{"color": [1, 1, 1]}, {"color": [0, 0, 1]}])"));
    EXPECT_EQ(uniformOf(gbuffer.uniforms, "u_light_matrix")->value, json("@shadow.view_projection"));
    EXPECT_EQ(uniformOf(gbuffer.uniforms, "u_light_eye")->value, json("@shadow.camera_position"));

    const PassSpec& outline = s.passes[3];  // the second pass drawing into gbuffer
    EXPECT_EQ(outline.target, "gbuffer");
    EXPECT_EQ(outline.state.clear_colors, (Clears{std::nullopt, std::nullopt}));
    EXPECT_FALSE(outline.state.clear_depth);
    EXPECT_TRUE(outline.state.depth_test);  // a scene draw into a target with depth
    EXPECT_TRUE(outline.state.depth_write);
    EXPECT_EQ(outline.state.polygon_mode, PolygonMode::Line);
    EXPECT_FLOAT_EQ(outline.state.line_width, 2.0f);
    EXPECT_EQ(outline.state.blend, BlendMode::Alpha);
    EXPECT_EQ(outline.state.cull, CullMode::None);
    EXPECT_TRUE(outline.graded.empty());
    EXPECT_EQ(outline.compare, CompareMode::Display);  // not graded

    const PassSpec& combine = s.passes[4];
    EXPECT_EQ(combine.target, "lit");
    EXPECT_EQ(combine.draw, DrawKind::Fullscreen);
    EXPECT_FALSE(combine.state.depth_test);
    EXPECT_FALSE(combine.state.depth_write);
    EXPECT_EQ(combine.state.clear_colors, (Clears{kBlack}));
    EXPECT_EQ(combine.graded, (std::vector<std::string>{"color"}));  // true: every attachment
    EXPECT_EQ(combine.compare, CompareMode::Display);
    EXPECT_FLOAT_EQ(combine.thresholds.psnr_min_db, 25.0f);  // the pass's own
    EXPECT_FLOAT_EQ(combine.thresholds.ssim_min, 0.9f);      // the lab's
    EXPECT_FLOAT_EQ(combine.thresholds.flip_mean_max, 0.1f);
    EXPECT_FLOAT_EQ(combine.thresholds.mismatch_max, 0.02f);
    EXPECT_FLOAT_EQ(combine.thresholds.pixel_tolerance, 0.04f);
    EXPECT_EQ(combine.inputs.size(), 10u);
    const PassInput* albedo = inputOf(combine, "u_albedo");
    ASSERT_NE(albedo, nullptr);
    EXPECT_EQ(albedo->source, InputSource::Target);
    EXPECT_EQ(albedo->target, "gbuffer");
    EXPECT_EQ(albedo->attachment, "albedo");
    EXPECT_FALSE(albedo->filter.has_value());  // the target's, when the renderer binds it
    EXPECT_FALSE(albedo->wrap.has_value());
    EXPECT_FALSE(albedo->srgb);
    EXPECT_EQ(albedo->path, "passes[4].inputs.u_albedo");
    const PassInput* normal = inputOf(combine, "u_normal");
    ASSERT_NE(normal, nullptr);
    EXPECT_EQ(normal->source, InputSource::Target);
    EXPECT_EQ(normal->target, "gbuffer");
    EXPECT_EQ(normal->attachment, "normal");
    EXPECT_EQ(normal->filter, TextureFilter::Linear);
    EXPECT_EQ(normal->wrap, TextureWrap::ClampToEdge);
    const PassInput* shadow_in = inputOf(combine, "u_shadow");
    ASSERT_NE(shadow_in, nullptr);
    EXPECT_EQ(shadow_in->target, "shadow");
    EXPECT_EQ(shadow_in->attachment, "depth");
    const PassInput* env_in = inputOf(combine, "u_env");
    ASSERT_NE(env_in, nullptr);
    EXPECT_EQ(env_in->target, "env");
    EXPECT_EQ(env_in->attachment, "");  // the first attachment
    const PassInput* ramp = inputOf(combine, "u_ramp");
    ASSERT_NE(ramp, nullptr);
    EXPECT_EQ(ramp->source, InputSource::File);
    EXPECT_EQ(ramp->file, "ramp.png");
    EXPECT_EQ(ramp->filter, TextureFilter::Nearest);
    EXPECT_EQ(ramp->wrap, TextureWrap::MirroredRepeat);
    EXPECT_TRUE(ramp->srgb);
    const PassInput* volume = inputOf(combine, "u_volume");
    ASSERT_NE(volume, nullptr);
    EXPECT_EQ(volume->source, InputSource::File);
    EXPECT_EQ(volume->layers, 4);
    EXPECT_EQ(inputOf(combine, "u_ramp")->layers, 0);
    const PassInput* noise = inputOf(combine, "u_noise");
    ASSERT_NE(noise, nullptr);
    EXPECT_EQ(noise->source, InputSource::Generated);
    EXPECT_EQ(noise->generated.pattern, "noise");
    EXPECT_EQ(noise->generated.width, 16);
    EXPECT_EQ(noise->generated.height, 8);
    EXPECT_EQ(noise->generated.depth, 4);
    EXPECT_EQ(noise->generated.seed, 7u);
    EXPECT_TRUE(noise->generated.colors.empty());
    const PassInput* checker = inputOf(combine, "u_checker");
    ASSERT_NE(checker, nullptr);
    EXPECT_EQ(checker->generated.pattern, "checker");
    EXPECT_EQ(checker->generated.depth, 1);
    EXPECT_EQ(checker->generated.cells, 4);
    EXPECT_EQ(checker->generated.colors,
              (std::vector<glm::vec4>{glm::vec4(0, 0, 0, 1), glm::vec4(1, 0, 1, 1)}));
    const PassInput* stops = inputOf(combine, "u_stops");  // a gradient without colours: black to white
    ASSERT_NE(stops, nullptr);
    EXPECT_EQ(stops->generated.width, 64);
    EXPECT_EQ(stops->generated.height, 1);
    EXPECT_EQ(stops->generated.colors, (std::vector<glm::vec4>{glm::vec4(0, 0, 0, 1), glm::vec4(1)}));
    const PassInput* sky_in = inputOf(combine, "u_sky");
    ASSERT_NE(sky_in, nullptr);
    EXPECT_EQ(sky_in->source, InputSource::Cube);
    EXPECT_EQ(sky_in->cube_files, faces.cube_files);
    ASSERT_EQ(combine.uniforms.size(), 2u);
    EXPECT_EQ(uniformOf(combine.uniforms, "u_steps")->value, json(4));

    const PassSpec& advect = s.passes[5];
    EXPECT_EQ(advect.target, "sim");
    EXPECT_EQ(advect.loop, 0);
    const PassInput* prev = inputOf(advect, "u_prev");  // its own target, inside a repeat group
    ASSERT_NE(prev, nullptr);
    EXPECT_EQ(prev->target, "sim");

    const PassSpec& project = s.passes[6];
    EXPECT_EQ(project.draw, DrawKind::Procedural);
    EXPECT_EQ(project.primitive, Primitive::Points);
    EXPECT_EQ(project.vertex_count, 1000);
    EXPECT_EQ(project.target, "sim");
    EXPECT_FLOAT_EQ(project.state.point_size, 3.0f);
    EXPECT_EQ(project.state.blend, BlendMode::Additive);
    EXPECT_EQ(project.state.clear_colors, (Clears{std::nullopt}));  // the second pass drawing into sim
    EXPECT_FALSE(project.state.depth_test);                         // the target has no depth
    EXPECT_FALSE(project.state.depth_write);
    EXPECT_EQ(project.loop, 0);

    const PassSpec& blur_h = s.passes[7];
    EXPECT_EQ(blur_h.program.vertex, "shared/fullscreen.vert");
    EXPECT_EQ(blur_h.program.fragment, "blur.frag");
    EXPECT_EQ(blur_h.draw, DrawKind::Fullscreen);
    EXPECT_FLOAT_EQ(blur_h.thresholds.ssim_min, 0.8f);      // the template's
    EXPECT_FLOAT_EQ(blur_h.thresholds.psnr_min_db, 28.0f);  // the lab's
    EXPECT_EQ(uniformOf(blur_h.uniforms, "u_direction")->value, json::parse("[1, 0]"));
    EXPECT_EQ(blur_h.loop, -1);
    EXPECT_EQ(s.passes[8].loop, 1);

    const PassSpec& last = s.passes[9];
    EXPECT_EQ(last.program.vertex, "shared/fullscreen.vert");  // the template's
    EXPECT_EQ(last.program.fragment, "final.frag");            // the pass's
    EXPECT_EQ(last.target, "final");
    EXPECT_EQ(last.graded, (std::vector<std::string>{"color"}));  // the last pass
    EXPECT_EQ(last.compare, CompareMode::Display);                // a float target, but the last pass
    EXPECT_FALSE(last.state.depth_test);  // fullscreen, although its target has a depth buffer
    EXPECT_FALSE(last.state.depth_write);
    EXPECT_TRUE(last.state.clear_depth);
    ASSERT_EQ(last.uniforms.size(), 2u);  // merged entry by entry
    EXPECT_EQ(uniformOf(last.uniforms, "u_gain")->value, json(1));
    EXPECT_EQ(uniformOf(last.uniforms, "u_exposure")->value, json(2));
    EXPECT_EQ(s.findPass("final"), &last);
    EXPECT_EQ(s.findPass("nothing"), nullptr);

    ASSERT_EQ(s.loops.size(), 2u);
    EXPECT_EQ(s.loops[0].first, 5u);
    EXPECT_EQ(s.loops[0].last, 6u);
    EXPECT_EQ(s.loops[0].count, 10);
    EXPECT_EQ(s.loops[0].declared_by, "project");
    EXPECT_EQ(s.loops[1].first, 8u);
    EXPECT_EQ(s.loops[1].last, 8u);
    EXPECT_EQ(s.loops[1].count, 2);
    EXPECT_EQ(s.loops[1].declared_by, "blur_v");

    // "times" expands a scene into name_t0, name_t1, ...
    ASSERT_EQ(s.scenes.size(), 5u);
    std::vector<std::string> scene_names;
    for (const SceneSpec& sc : s.scenes) scene_names.push_back(sc.name);
    EXPECT_EQ(scene_names,
              (std::vector<std::string>{"teapot_t0", "teapot_t1", "teapot_t2", "plane", "ortho"}));
    const SceneSpec& t1 = s.scenes[1];
    EXPECT_EQ(t1.base_name, "teapot");
    EXPECT_EQ(t1.file, "scenes/teapot.gltf");
    EXPECT_FLOAT_EQ(t1.time, 0.5f);
    EXPECT_EQ(t1.path, "scenes[0].times[1]");
    EXPECT_EQ(t1.repeats, (std::map<std::string, int>{{"blur_v", 3}, {"project", 20}}));
    EXPECT_FLOAT_EQ(s.scenes[2].time, 1.0f);
    EXPECT_EQ(s.scenes[2].repeats, t1.repeats);
    const SceneSpec& plane = s.scenes[3];
    EXPECT_EQ(plane.base_name, "plane");
    EXPECT_EQ(plane.path, "scenes[1]");
    EXPECT_FLOAT_EQ(plane.time, 0.25f);
    EXPECT_EQ(plane.camera.position, glm::vec3(0, 0.4f, 6));
    EXPECT_EQ(plane.camera.target, glm::vec3(0, 0, 0));
    EXPECT_EQ(plane.camera.up, glm::vec3(0, 1, 0));
    EXPECT_EQ(plane.camera.fov_y_deg, 50.0f);
    EXPECT_EQ(plane.camera.z_near, 0.1f);
    EXPECT_EQ(plane.camera.z_far, 50.0f);
    EXPECT_FALSE(plane.camera.projection.has_value());
    ASSERT_TRUE(plane.lights.has_value());
    ASSERT_EQ(plane.lights->size(), 2u);
    EXPECT_EQ((*plane.lights)[0].type, "directional");
    EXPECT_EQ((*plane.lights)[0].direction, glm::vec3(0.3f, -1, -0.5f));
    EXPECT_EQ((*plane.lights)[0].color, glm::vec3(1, 0.9f, 0.8f));
    EXPECT_FLOAT_EQ((*plane.lights)[0].intensity, 2.0f);
    EXPECT_EQ((*plane.lights)[1].type, "point");
    EXPECT_EQ((*plane.lights)[1].position, glm::vec3(1, 2, 3));
    EXPECT_EQ((*plane.lights)[1].color, glm::vec3(1));  // default colour and intensity
    EXPECT_FLOAT_EQ((*plane.lights)[1].intensity, 1.0f);
    ASSERT_EQ(plane.uniforms.size(), 1u);
    EXPECT_EQ(plane.uniforms[0].path, "scenes[1].uniforms.u_steps");
    const SceneSpec& ortho = s.scenes[4];
    EXPECT_EQ(ortho.camera.projection, Projection::Orthographic);
    EXPECT_EQ(ortho.camera.height, 4.0f);
    ASSERT_TRUE(ortho.lights.has_value());  // [] replaces the file's lights with none
    EXPECT_TRUE(ortho.lights->empty());
    EXPECT_TRUE(ortho.repeats.empty());

    // Goals: a base scene name means all of its times; a time name one of them.
    ASSERT_EQ(s.goals.size(), 4u);
    EXPECT_EQ(s.goals[0].id, "gbuffer");
    EXPECT_EQ(s.goals[0].title, "Write the G-buffer");
    EXPECT_FLOAT_EQ(s.goals[0].points, 3.0f);
    EXPECT_EQ(s.goals[0].scenes, scene_names);  // every scene
    EXPECT_EQ(s.goals[0].passes, (std::vector<std::string>{"gbuffer"}));
    EXPECT_FALSE(s.goals[0].implicit);
    EXPECT_EQ(s.goals[1].scenes, (std::vector<std::string>{"teapot_t0", "teapot_t1", "teapot_t2", "plane"}));
    EXPECT_EQ(s.goals[1].passes, (std::vector<std::string>{"combine", "final"}));
    EXPECT_EQ(s.goals[3].scenes, (std::vector<std::string>{"teapot_t2"}));
    EXPECT_FLOAT_EQ(s.grading.points, 11.0f);  // the sum of the goals' points
    EXPECT_FLOAT_EQ(s.grading.thresholds.psnr_min_db, 28.0f);
    EXPECT_FLOAT_EQ(s.grading.thresholds.ssim_min, 0.9f);
    EXPECT_FLOAT_EQ(s.grading.thresholds.flip_mean_max, 0.1f);
    EXPECT_FLOAT_EQ(s.grading.thresholds.mismatch_max, 0.02f);
    EXPECT_FLOAT_EQ(s.grading.thresholds.pixel_tolerance, 0.04f);
}

TEST_F(LabSpecParse, MinimalSpecGetsTheDocumentedDefaults) {
    const LabSpecResult r = parseText(kMinimalSpec);
    ASSERT_TRUE(r.ok) << allErrors(r);
    const shaderlab::LabSpec& s = r.spec;
    using namespace shaderlab;
    EXPECT_EQ(s.schema, 2);
    EXPECT_EQ(s.title, "01-phong");  // the id
    EXPECT_EQ(s.width, 256);
    EXPECT_EQ(s.height, 256);
    EXPECT_EQ(s.student_files, (std::vector<std::string>{"phong.vert", "phong.frag"}));

    ASSERT_EQ(s.targets.size(), 1u);  // the pass's own, with every default
    const TargetSpec& t = s.targets[0];
    EXPECT_EQ(t.name, "shade");
    EXPECT_EQ(t.format, TargetFormat::RGBA32F);
    EXPECT_EQ(t.type, TargetType::Texture2D);
    EXPECT_EQ(t.width, 256);
    EXPECT_EQ(t.height, 256);
    EXPECT_FLOAT_EQ(t.scale, 1.0f);
    EXPECT_EQ(t.attachments, (std::vector<std::string>{"color"}));
    EXPECT_EQ(t.depth, DepthMode::Buffer);
    EXPECT_EQ(t.filter, TextureFilter::Linear);
    EXPECT_EQ(t.wrap, TextureWrap::ClampToEdge);

    ASSERT_EQ(s.passes.size(), 1u);
    const PassSpec& p = s.passes[0];
    EXPECT_EQ(p.draw, DrawKind::Scene);
    EXPECT_EQ(p.target, "shade");
    EXPECT_TRUE(p.inputs.empty());
    EXPECT_TRUE(p.uniforms.empty());
    EXPECT_FALSE(p.camera.any());
    EXPECT_EQ(p.state.clear_colors, (Clears{kBlack}));
    EXPECT_TRUE(p.state.clear_depth);
    EXPECT_TRUE(p.state.depth_test);
    EXPECT_TRUE(p.state.depth_write);
    EXPECT_EQ(p.state.depth_func, DepthFunc::Less);
    EXPECT_EQ(p.state.cull, CullMode::Back);
    EXPECT_EQ(p.state.polygon_mode, PolygonMode::Fill);
    EXPECT_FLOAT_EQ(p.state.line_width, 1.0f);
    EXPECT_FLOAT_EQ(p.state.point_size, 1.0f);
    EXPECT_EQ(p.state.blend, BlendMode::None);
    EXPECT_EQ(p.graded, (std::vector<std::string>{"color"}));  // the only, hence last, pass
    EXPECT_EQ(p.compare, CompareMode::Display);
    EXPECT_FLOAT_EQ(p.thresholds.psnr_min_db, 30.0f);
    EXPECT_EQ(p.loop, -1);
    EXPECT_TRUE(s.loops.empty());

    ASSERT_EQ(s.scenes.size(), 1u);
    const SceneSpec& sc = s.scenes[0];
    EXPECT_EQ(sc.name, "sphere");
    EXPECT_EQ(sc.base_name, "sphere");
    EXPECT_FALSE(sc.camera.any());
    EXPECT_FALSE(sc.lights.has_value());  // keep the file's lights
    EXPECT_TRUE(sc.uniforms.empty());
    EXPECT_FLOAT_EQ(sc.time, 0.0f);
    EXPECT_TRUE(sc.repeats.empty());

    // Without goals, each scene is a goal of its own sharing grading.points.
    ASSERT_EQ(s.goals.size(), 1u);
    EXPECT_EQ(s.goals[0].id, "sphere");
    EXPECT_EQ(s.goals[0].title, "scene sphere");
    EXPECT_FLOAT_EQ(s.goals[0].points, 10.0f);
    EXPECT_EQ(s.goals[0].scenes, (std::vector<std::string>{"sphere"}));
    EXPECT_EQ(s.goals[0].passes, (std::vector<std::string>{"shade"}));
    EXPECT_TRUE(s.goals[0].implicit);

    EXPECT_FLOAT_EQ(s.grading.points, 10.0f);
    EXPECT_FLOAT_EQ(s.grading.thresholds.psnr_min_db, 30.0f);
    EXPECT_FLOAT_EQ(s.grading.thresholds.ssim_min, 0.95f);
    EXPECT_FLOAT_EQ(s.grading.thresholds.flip_mean_max, 0.05f);
    EXPECT_FLOAT_EQ(s.grading.thresholds.mismatch_max, 0.01f);
    EXPECT_FLOAT_EQ(s.grading.thresholds.pixel_tolerance, 0.05f);
}

// Thresholds apply lab, then pass, then scene; a scene changes only what it names.
TEST_F(LabSpecParse, SceneThresholdsOverrideThePassesForThatScene) {
    const LabSpecResult r = parseText(R"({
      "schema": 2, "id": "01-phong",
      "passes": [{"name": "shade", "program": {"vertex": "phong.vert", "fragment": "phong.frag"},
                  "thresholds": {"psnr_min_db": 25}}],
      "scenes": [{"name": "strict", "file": "scenes/sphere.gltf"},
                 {"name": "loose", "file": "scenes/sphere.gltf", "thresholds": {"mismatch_max": 0.08}}],
      "grading": {"ssim_min": 0.9}
    })");
    ASSERT_TRUE(r.ok) << allErrors(r);
    const shaderlab::GradingThresholds strict =
        r.spec.scenes[0].thresholds.applyTo(r.spec.passes[0].thresholds);
    const shaderlab::GradingThresholds loose =
        r.spec.scenes[1].thresholds.applyTo(r.spec.passes[0].thresholds);
    EXPECT_FLOAT_EQ(strict.psnr_min_db, 25.0f);
    EXPECT_FLOAT_EQ(strict.ssim_min, 0.9f);
    EXPECT_FLOAT_EQ(strict.mismatch_max, 0.01f);
    EXPECT_FLOAT_EQ(loose.psnr_min_db, 25.0f);
    EXPECT_FLOAT_EQ(loose.mismatch_max, 0.08f);
}

TEST_F(LabSpecParse, ImplicitGoalsShareThePointsOverEveryExpandedScene) {
    json spec = json::parse(kMinimalSpec);
    spec["scenes"] = json::parse(R"([{"name": "spin", "file": "scenes/teapot.gltf", "times": [0, 1, 2]},
                                     {"name": "still", "file": "scenes/sphere.gltf"}])");
    spec["grading"] = {{"points", 20}};
    const LabSpecResult r = parseJson(spec);
    ASSERT_TRUE(r.ok) << allErrors(r);
    ASSERT_EQ(r.spec.goals.size(), 4u);
    std::vector<std::string> ids;
    for (const shaderlab::GoalSpec& g : r.spec.goals) {
        ids.push_back(g.id);
        EXPECT_FLOAT_EQ(g.points, 5.0f);
        EXPECT_TRUE(g.implicit);
        EXPECT_EQ(g.scenes, std::vector<std::string>{g.id});
    }
    EXPECT_EQ(ids, (std::vector<std::string>{"spin_t0", "spin_t1", "spin_t2", "still"}));
    EXPECT_EQ(r.spec.goals[3].title, "scene still");
    EXPECT_FLOAT_EQ(r.spec.grading.points, 20.0f);
}

TEST_F(LabSpecParse, GradedEarlierPassesAreInTheImplicitGoals) {
    json spec = json::parse(kMinimalSpec);
    spec["passes"][0]["graded"] = true;
    spec["passes"][1] = json::parse(R"({"name": "post", "draw": "fullscreen",
        "program": {"vertex": "shared/fullscreen.vert", "fragment": "post.frag"}, "inputs": {"u_scene": "shade"}})");
    const LabSpecResult r = parseJson(spec);
    ASSERT_TRUE(r.ok) << allErrors(r);
    ASSERT_EQ(r.spec.goals.size(), 1u);
    EXPECT_EQ(r.spec.goals[0].passes, (std::vector<std::string>{"shade", "post"}));
    EXPECT_EQ(r.spec.passes[0].compare, shaderlab::CompareMode::Hdr);  // graded rgba32f, not last
    EXPECT_EQ(r.spec.passes[1].compare, shaderlab::CompareMode::Display);
    // Default student files: the shared vertex shader is not one.
    EXPECT_EQ(r.spec.student_files, (std::vector<std::string>{"phong.vert", "phong.frag", "post.frag"}));
}

TEST_F(LabSpecParse, ExplicitStateOverridesTheDefaultsOfPassKindAndDrawOrder) {
    json spec = json::parse(kBaseSpec);
    // A second writer of gbuf that clears anyway; a fullscreen pass that tests depth.
    spec["passes"][5] = spec["passes"][4];
    spec["passes"][4] = json::parse(R"({"name": "again", "program": {"vertex": "phong.vert",
        "fragment": "phong.frag"}, "target": "gbuf", "state": {"clear_color": [1, 0, 0, 1], "clear_depth": true,
        "depth_write": false}})");
    spec["passes"][5]["state"] = {{"depth_test", true}, {"clear_color", {{"color", {0, 1, 0, 1}}}}};
    const LabSpecResult r = parseJson(spec);
    ASSERT_TRUE(r.ok) << allErrors(r);
    const shaderlab::PassSpec& again = r.spec.passes[4];
    EXPECT_EQ(again.state.clear_colors, (Clears{glm::vec4(1, 0, 0, 1), glm::vec4(1, 0, 0, 1)}));
    EXPECT_TRUE(again.state.clear_depth);
    EXPECT_TRUE(again.state.depth_test);
    EXPECT_FALSE(again.state.depth_write);
    const shaderlab::PassSpec& last = r.spec.passes[5];
    EXPECT_TRUE(last.state.depth_test);
    EXPECT_FALSE(last.state.depth_write);
    EXPECT_EQ(last.state.clear_colors, (Clears{glm::vec4(0, 1, 0, 1)}));
}

TEST_F(LabSpecParse, AFirstWriterClearsOnlyOnce) {
    // sky and a later pass into the same cube target; blur runs 4 times but is one writer.
    json spec = json::parse(kBaseSpec);
    spec["passes"][5] = spec["passes"][4];
    spec["passes"][4] = json::parse(R"({"name": "sky2", "extends": "post", "target": "env"})");
    const LabSpecResult r = parseJson(spec);
    ASSERT_TRUE(r.ok) << allErrors(r);
    EXPECT_EQ(r.spec.passes[1].state.clear_colors, (Clears{kBlack}));
    EXPECT_EQ(r.spec.passes[4].state.clear_colors, (Clears{std::nullopt}));
    EXPECT_EQ(r.spec.passes[3].state.clear_colors, (Clears{kBlack}));
}

TEST_F(LabSpecParse, SelfReadInsideARepeatIsAllowedAndOutsideIsNot) {
    json spec = json::parse(kBaseSpec);
    spec["passes"][4]["inputs"]["u_self"] = "final";
    EXPECT_TRUE(hasError(parseJson(spec), "passes[4].inputs.u_self", "which this pass draws into"));
    spec["passes"][4]["repeat"] = 3;
    const LabSpecResult r = parseJson(spec);
    ASSERT_TRUE(r.ok) << allErrors(r);
    EXPECT_EQ(r.spec.passes[4].loop, 1);
}

TEST_F(LabSpecParse, InsideARepeatGroupAPassMayReadWhatTheGroupDrawsLater) {
    json spec = json::parse(kBaseSpec);
    spec["passes"][2]["inputs"]["u_blurred"] = "half";  // blur (passes[3]) draws it after shade
    EXPECT_TRUE(hasError(parseJson(spec), "passes[2].inputs.u_blurred", "a cycle"));
    spec["passes"][3]["repeat"] = {{"count", 4}, {"from", "shade"}};
    const LabSpecResult r = parseJson(spec);
    ASSERT_TRUE(r.ok) << allErrors(r);
    ASSERT_EQ(r.spec.loops.size(), 1u);
    EXPECT_EQ(r.spec.loops[0].first, 2u);
    EXPECT_EQ(r.spec.loops[0].last, 3u);
    EXPECT_EQ(r.spec.loops[0].declared_by, "blur");
    EXPECT_EQ(r.spec.passes[2].loop, 0);
    EXPECT_EQ(r.spec.passes[1].loop, -1);
}

TEST_F(LabSpecParse, RepeatFromItselfIsAGroupOfOne) {
    json spec = json::parse(kBaseSpec);
    spec["passes"][3]["repeat"] = {{"count", 7}, {"from", "blur"}};
    const LabSpecResult r = parseJson(spec);
    ASSERT_TRUE(r.ok) << allErrors(r);
    ASSERT_EQ(r.spec.loops.size(), 1u);
    EXPECT_EQ(r.spec.loops[0].first, 3u);
    EXPECT_EQ(r.spec.loops[0].last, 3u);
    EXPECT_EQ(r.spec.loops[0].count, 7);
}

TEST_F(LabSpecParse, AGoalMayNameOneTimeOfAScene) {
    json spec = json::parse(kBaseSpec);
    spec["goals"][1]["scenes"] = {"teapot_t1", "sphere"};
    spec["goals"][2] = json::parse(R"({"id": "first", "title": "The first frame", "points": 1,
                                       "scenes": ["teapot_t0"], "passes": ["final"]})");
    const LabSpecResult r = parseJson(spec);
    ASSERT_TRUE(r.ok) << allErrors(r);
    EXPECT_EQ(r.spec.goals[1].scenes, (std::vector<std::string>{"teapot_t1", "sphere"}));
    EXPECT_EQ(r.spec.goals[2].scenes, (std::vector<std::string>{"teapot_t0"}));
    EXPECT_FLOAT_EQ(r.spec.grading.points, 11.0f);
}

TEST_F(LabSpecParse, FullscreenOnlyLabMayListScenesWithoutFiles) {
    const LabSpecResult r = parseText(R"({
      "schema": 2, "id": "01-phong",
      "passes": [{"name": "march", "draw": "fullscreen",
                  "program": {"vertex": "shared/fullscreen.vert", "fragment": "post.frag"}},
                 {"name": "dots", "draw": {"primitive": "triangle_strip", "count": 4},
                  "program": {"vertex": "particles.vert", "fragment": "particles.frag"}, "target": "march"}],
      "scenes": [{"name": "early", "time": 0.25, "uniforms": {"u_seed": 7}}, {"name": "late", "time": 2}]
    })");
    ASSERT_TRUE(r.ok) << allErrors(r);
    ASSERT_EQ(r.spec.scenes.size(), 2u);
    EXPECT_TRUE(r.spec.scenes[0].file.empty());
    EXPECT_FLOAT_EQ(r.spec.scenes[0].time, 0.25f);
    EXPECT_EQ(r.spec.passes[1].primitive, shaderlab::Primitive::TriangleStrip);
    EXPECT_EQ(r.spec.passes[1].vertex_count, 4);
    EXPECT_TRUE(r.spec.passes[1].state.depth_test);  // a draw without a mesh is not fullscreen
    EXPECT_FALSE(r.spec.passes[1].state.clear_depth);
    EXPECT_EQ(r.spec.student_files,
              (std::vector<std::string>{"post.frag", "particles.vert", "particles.frag"}));
}

TEST_F(LabSpecParse, ACubeTargetMayBeDrawnWithoutAMesh) {
    json spec = json::parse(kBaseSpec);
    spec["passes"][1]["draw"] = {{"primitive", "triangles"}, {"count", 3}};
    const LabSpecResult r = parseJson(spec);
    EXPECT_TRUE(r.ok) << allErrors(r);
}

TEST_F(LabSpecParse, SixteenInputsFourLightsAndTheLimitsOfRangesAreAllowed) {
    json spec = json::parse(kBaseSpec);
    json inputs = json::object();
    for (int i = 0; i < 16; ++i) inputs["u_t" + std::to_string(i)] = {{"texture", "ramp.png"}};
    spec["passes"][4]["inputs"] = inputs;
    spec["scenes"][0]["lights"] = json::array();
    for (int i = 0; i < 4; ++i)
        spec["scenes"][0]["lights"].push_back({{"type", "point"}, {"position", {i, 1, 0}}});
    spec["targets"]["half"] = {{"size", {4096, 4096}}, {"depth", "none"}};
    spec["passes"][3]["repeat"] = 10000;
    spec["scenes"][1].erase("repeats");
    spec["scenes"][1]["times"] = {0};
    spec["grading"]["ssim_min"] = 1;
    spec["grading"]["mismatch_max"] = 0;
    const LabSpecResult r = parseJson(spec);
    EXPECT_TRUE(r.ok) << allErrors(r);
}

TEST_F(LabSpecParse, LabFolderWithTrailingSlashIsNormalised) {
    const LabSpecResult r = shaderlab::parseLabSpecText(kMinimalSpec, kOrigin, lab_.string() + "/");
    ASSERT_TRUE(r.ok) << allErrors(r);
    EXPECT_EQ(fs::path(r.spec.lab_dir), lab_);
    EXPECT_EQ(fs::path(r.spec.labs_root), labs_);
}

TEST_F(LabSpecParse, LabFilePathsResolveSharedAgainstTheLabsRoot) {
    const LabSpecResult r = parseText(kMinimalSpec);
    ASSERT_TRUE(r.ok) << allErrors(r);
    EXPECT_EQ(fs::path(shaderlab::labFilePath(r.spec, "phong.frag")), lab_ / "phong.frag");
    EXPECT_EQ(fs::path(shaderlab::labFilePath(r.spec, "shared/fullscreen.vert")),
              labs_ / "shared" / "fullscreen.vert");
    EXPECT_EQ(fs::path(shaderlab::sharedFolder(labs_.string())), labs_ / "shared");
}

// =============================================================================================
// One mistake at a time: each case edits the base spec with JSON pointers and expects a message
// with the given path and problem, and `count` messages in all (one mistake, one message, unless
// the mistake really is in several places).

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
    // ---- schema: types
    {"SchemaVersionOne",
     {{"/schema", "1"}},
     "schema",
     "expected 2 (this framework reads lab.json schema 2), got 1"},
    {"SchemaMissing", {{"/schema", kDelete}}, "schema", "is required"},
    {"RootNotObject", {{"", "[]"}}, "", "expected an object, got an empty array"},
    {"TitleNotString", {{"/title", "3"}}, "title", "expected a string, got 3"},
    {"TitleEmpty", {{"/title", "\"\""}}, "title", "must not be empty"},
    {"NumberAsString", {{"/scenes/0/time", "\"0.5\""}}, "scenes[0].time", "expected a number, got \"0.5\""},
    {"NumberBeyondAFloat", {{"/scenes/0/time", "1e39"}}, "scenes[0].time", "must be in [-3.4e+38, 3.4e+38]"},
    {"BooleanAsNumber",
     {{"/passes/2/state", R"({"depth_test": 1})"}},
     "passes[2].state.depth_test",
     "expected true or false, got 1"},
    {"GradedAsNumber",
     {{"/passes/2/graded", "1"}},
     "passes[2].graded",
     "expected true, false, or the attachments to grade (\"depth\" included), got 1"},
    {"IntegerWithDecimals", {{"/resolution/0", "256.5"}}, "resolution[0]", "expected an integer, got 256.5"},
    {"RepeatWithDecimals", {{"/passes/3/repeat", "2.5"}}, "passes[3].repeat", "got 2.5"},
    {"ResolutionOneNumber",
     {{"/resolution", "[256]"}},
     "resolution",
     "expected [width, height], integers from 1 to 4096, got an array of 1 element"},
    {"CameraPositionTwoNumbers",
     {{"/scenes/0/camera/position", "[0, 3]"}},
     "scenes[0].camera.position",
     "expected 3 numbers, got an array of 2 elements"},
    {"UniformValueNull",
     {{"/passes/2/uniforms/u_shininess", "null"}},
     "passes[2].uniforms.u_shininess",
     "expected a number, true/false, an array (vector, matrix or array), an object (struct), or "
     "\"@pass.view_projection\", got null"},
    {"UniformPassReferenceMalformed",
     {{"/passes/2/uniforms/u_light_matrix", "\"@shadow.viewproj\""}},
     "passes[2].uniforms.u_light_matrix",
     "expected \"@<pass>.view\", \"@<pass>.projection\", \"@<pass>.view_projection\" or "
     "\"@<pass>.camera_position\", got \"@shadow.viewproj\""},
    {"InputNumber",
     {{"/passes/4/inputs/u_image", "3"}},
     "passes[4].inputs.u_image",
     "expected a target name"},
    {"ClearColorString",
     {{"/passes/2/state", R"({"clear_color": "black"})"}},
     "passes[2].state.clear_color",
     "expected [r, g, b, a], null, or an object of attachment name to [r, g, b, a] or null, got \"black\""},

    // ---- schema: allowed values and ranges
    {"EnumAsInTheDocs",
     {{"/passes/0/state", R"({"cull": "sideways"})"}},
     "passes[0].state.cull",
     "expected one of \"back\", \"front\" or \"none\", got \"sideways\""},
    {"EnumDidYouMean",
     {{"/passes/0/state", R"({"cull": "fornt"})"}},
     "passes[0].state.cull",
     "got \"fornt\" (did you mean \"front\"?)"},
    {"TargetFormatDidYouMean",
     {{"/targets/gbuf/format", "\"rgb16f\""}},
     "targets.gbuf.format",
     "expected one of \"rgba8\", \"srgb8\", \"rgba16f\" or \"rgba32f\", got \"rgb16f\" (did you mean "
     "\"rgba16f\"?)"},
    {"DrawPrimitiveDidYouMean",
     {{"/passes/4/draw", R"({"primitive": "triangle", "count": 3})"}},
     "passes[4].draw.primitive",
     "(did you mean \"triangles\"?)"},
    {"DrawUnknown",
     {{"/passes/4/draw", "\"fulscreen\""}},
     "passes[4].draw",
     "got \"fulscreen\" (did you mean \"fullscreen\"?)"},
    {"ScaleZero", {{"/targets/half/scale", "0"}}, "targets.half.scale", "must be in (0, 4], got 0"},
    {"ScaleAboveFour", {{"/targets/half/scale", "4.5"}}, "targets.half.scale", "must be in (0, 4], got 4.5"},
    {"ResolutionTooLarge", {{"/resolution/1", "5000"}}, "resolution[1]", "must be in [1, 4096], got 5000"},
    {"FieldOfViewOf180",
     {{"/scenes/0/camera", R"({"fov_y_deg": 180})"}},
     "scenes[0].camera.fov_y_deg",
     "must be in (0, 180), got 180"},
    {"NearZero", {{"/scenes/0/camera/near", "0"}}, "scenes[0].camera.near", "must be in (0, 3.4e+38], got 0"},
    {"LightIntensityNegative",
     {{"/scenes/0/lights/0/intensity", "-1"}},
     "scenes[0].lights[0].intensity",
     "must be in [0, 3.4e+38], got -1"},
    {"LightColorNegative",
     {{"/scenes/0/lights/0/color", "[1, -0.5, 1]"}},
     "scenes[0].lights[0].color[1]",
     "must be in [0, 3.4e+38], got -0.5"},
    {"CameraLightIndexFour",
     {{"/passes/0/camera/light", "4"}},
     "passes[0].camera.light",
     "must be in [0, 3]"},
    {"SsimAboveOne", {{"/grading/ssim_min", "1.5"}}, "grading.ssim_min", "must be in [0, 1], got 1.5"},
    {"PassThresholdNegative",
     {{"/passes/2/thresholds", R"({"psnr_min_db": -1})"}},
     "passes[2].thresholds.psnr_min_db",
     "must be in [0, 100], got -1"},
    {"GoalPointsZero", {{"/goals/0/points", "0"}}, "goals[0].points", "must be in (0, 1000], got 0"},
    {"RepeatZero", {{"/passes/3/repeat", "0"}}, "passes[3].repeat", "must be in [1, 10000], got 0"},
    {"RepeatBillion",
     {{"/passes/3/repeat", "1000000000"}},
     "passes[3].repeat",
     "must be in [1, 10000], got 1000000000"},
    {"RepeatGroupCountZero",
     {{"/passes/3/repeat", R"({"count": 0, "from": "blur"})"}},
     "passes[3].repeat.count",
     "must be in [1, 10000], got 0"},
    {"RepeatGroupWithoutFrom",
     {{"/passes/3/repeat", R"({"count": 2})"}},
     "passes[3].repeat.from",
     "is required"},
    {"SceneRepeatsZero",
     {{"/scenes/1/repeats/blur", "0"}},
     "scenes[1].repeats.blur",
     "must be in [1, 10000], got 0"},
    {"DrawCountZero",
     {{"/passes/4/draw", R"({"primitive": "points", "count": 0})"}},
     "passes[4].draw.count",
     "must be in [1, 4194304], got 0"},
    {"TooManyLights",
     {{"/scenes/0/lights/2", R"({"type": "point", "position": [0, 1, 0]})"},
      {"/scenes/0/lights/3", R"({"type": "point", "position": [0, 2, 0]})"},
      {"/scenes/0/lights/4", R"({"type": "point", "position": [0, 3, 0]})"}},
     "scenes[0].lights",
     "must have at most 4 elements, got 5"},
    {"TooManyTimes",
     {{"/scenes/1/times", "[0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16]"}},
     "scenes[1].times",
     "must have at most 16 elements, got 17"},
    {"StudentFilesEmpty", {{"/student_files", "[]"}}, "student_files", "must not be empty"},
    {"AttachmentListedTwice",
     {{"/targets/gbuf/attachments", R"(["albedo", "albedo"])"}},
     "targets.gbuf.attachments[1]",
     "\"albedo\" is listed twice"},
    {"AttachmentNamedDepth",
     {{"/targets/gbuf/attachments", R"(["albedo", "depth"])"}},
     "targets.gbuf.attachments[1]",
     "is the name of the depth attachment"},

    // ---- schema: keys
    {"UnknownKeyDidYouMean",
     {{"/passes/2/uniform", "{}"}},
     "passes[2].uniform",
     "unknown key (did you mean \"uniforms\"?)"},
    {"UnknownKeyInATarget",
     {{"/targets/gbuf/fromat", "\"rgba8\""}},
     "targets.gbuf.fromat",
     "unknown key (did you mean \"format\"?)"},
    {"UnknownKeyInAnInputObject",
     {{"/passes/2/inputs/u_ramp/filtr", "\"nearest\""}},
     "passes[2].inputs.u_ramp.filtr",
     "unknown key (did you mean \"filter\"?)"},
    {"UnknownKeyAtTheTop", {{"/pases", "[]"}}, "pases", "unknown key (did you mean \"passes\"?)"},
    {"UnknownKeyListsTheAllowedOnes",
     {{"/grading/zebra", "1"}},
     "grading.zebra",
     "unknown key (allowed here: \"flip_mean_max\", \"mismatch_max\", \"pixel_tolerance\", \"points\", "
     "\"psnr_min_db\", \"ssim_min\")"},
    {"PassesMissing", {{"/passes", kDelete}}, "passes", "is required"},
    {"LightTypeMissing", {{"/scenes/0/lights/0/type", kDelete}}, "scenes[0].lights[0].type", "is required"},
    {"GoalTitleMissing", {{"/goals/0/title", kDelete}}, "goals[0].title", "is required"},
    {"SceneNameMissing", {{"/scenes/0/name", kDelete}}, "scenes[0].name", "is required"},
    {"DrawObjectWithoutCount",
     {{"/passes/4/draw", R"({"primitive": "points"})"}},
     "passes[4].draw.count",
     "is required"},

    // ---- schema: names and paths
    {"NamePattern",
     {{"/passes/3/name", "\"blur pass\""}},
     "passes[3].name",
     "expected a name of 1 to 64 letters, digits, '_' or '-', got \"blur pass\""},
    {"NameTooLong",
     {{"/goals/0/id", "\"g0123456789012345678901234567890123456789012345678901234567890123\""}},
     "goals[0].id",
     "expected a name of 1 to 64 letters"},
    {"TargetKeyPattern",
     {{"/targets/my target", "{}"}},
     "targets[\"my target\"]",
     "a name of 1 to 64 letters, digits, '_' or '-'"},
    {"GlslNameStartsWithADigit",
     {{"/passes/2/uniforms/2x", "1"}},
     "passes[2].uniforms.2x",
     "a GLSL identifier (letters, digits and '_', not starting with a digit or gl_)"},
    {"GlslNameStartsWithGl",
     {{"/passes/2/inputs/gl_Tex", "\"shadow\""}},
     "passes[2].inputs.gl_Tex",
     "a GLSL identifier"},
    {"GlslNameWithASpace",
     {{"/passes/2/inputs/u ramp", "\"shadow\""}},
     "passes[2].inputs[\"u ramp\"]",
     "a GLSL identifier"},
    {"FrameworkUniformRefused",
     {{"/passes/2/uniforms/u_time", "1"}},
     "passes[2].uniforms.u_time",
     "\"u_time\" is set by the framework (docs/student-contract.md); a lab value would replace it"},
    {"FrameworkUniformRefusedInAScene",
     {{"/scenes/0/uniforms", R"({"u_resolution": [1, 1]})"}},
     "scenes[0].uniforms.u_resolution",
     "is set by the framework"},
    {"FrameworkUniformRefusedInATemplate",
     {{"/templates/post/uniforms", R"({"u_iteration": 1})"}},
     "templates.post.uniforms.u_iteration",
     "is set by the framework"},
    {"PathWithDotDot",
     {{"/passes/2/program/fragment", "\"../02-toon/phong.frag\""}},
     "passes[2].program.fragment",
     "expected a relative path with '/' separators and no '..', got \"../02-toon/phong.frag\""},
    {"PathWithDotDotInside",
     {{"/passes/2/inputs/u_ramp/texture", "\"sky/../ramp.png\""}},
     "passes[2].inputs.u_ramp.texture",
     "no '..'"},
    {"SharedPathWithDotDot",
     {{"/passes/2/program/vertex", "\"shared/../01-phong/phong.vert\""}},
     "passes[2].program.vertex",
     "no '..'"},
    {"SceneFileWithDotDot", {{"/scenes/0/file", "\"../outside.gltf\""}}, "scenes[0].file", "no '..'"},
    {"PathAbsolute",
     {{"/passes/2/program/fragment", "\"/etc/hostname\""}},
     "passes[2].program.fragment",
     "a relative path"},
    {"PathWithBackslash",
     {{"/passes/2/program/fragment", "\"sky\\\\px.png\""}},
     "passes[2].program.fragment",
     "a relative path with '/' separators"},
    {"SceneFileNotGltf",
     {{"/scenes/0/file", "\"scenes/sphere.obj\""}},
     "scenes[0].file",
     "expected a .gltf or .glb file, got \"scenes/sphere.obj\""},

    // ---- schema: fields that exclude each other
    {"SizeAndScale",
     {{"/targets/half/size", "[64, 64]"}},
     "targets.half",
     "gives both \"size\" and \"scale\"; give one"},
    {"SizeAndScaleInAPassTarget",
     {{"/passes/4/target", R"({"size": [8, 8], "scale": 2})"}},
     "passes[4].target",
     "gives both \"size\" and \"scale\"; give one"},
    {"TimeAndTimes", {{"/scenes/1/time", "0.5"}}, "scenes[1]", "gives both \"time\" and \"times\"; give one"},

    // ---- read: templates, programs, inputs, lights
    {"TargetUnderTargetsWithAName",
     {{"/targets/half/name", "\"other\""}},
     "targets.half.name",
     "a target under \"targets\" is named by its key; leave \"name\" out"},
    {"TemplateWithAName",
     {{"/templates/post/name", "\"post\""}},
     "templates.post.name",
     "a template cannot have \"name\""},
    {"TemplateWithARepeat",
     {{"/templates/post/repeat", "2"}},
     "templates.post.repeat",
     "a template cannot have \"repeat\""},
    {"TemplateThatExtends",
     {{"/templates/post/extends", "\"post\""}},
     "templates.post.extends",
     "a template cannot have \"extends\""},
    {"ExtendsUnknownTemplate",
     {{"/passes/4/extends", "\"pots\""}},
     "passes[4].extends",
     "no template is called \"pots\" (did you mean \"post\"?)"},
    {"PassNameMissing", {{"/passes/0/name", kDelete}}, "passes[0].name", "is required"},
    {"ProgramMissing", {{"/passes/2/program", kDelete}}, "passes[2].program", "is required"},
    {"ProgramStageMissing",
     {{"/passes/2/program/fragment", kDelete}},
     "passes[2].program.fragment",
     "is required"},
    // Two passes take their fragment shader from the template: both are named.
    {"ProgramMissingAfterTheTemplateIsMerged",
     {{"/templates/post/program/fragment", kDelete}},
     "passes[3].program.fragment",
     "is required (neither the pass nor its template \"post\" gives it)",
     2},
    {"InputWithTwoSources",
     {{"/passes/2/inputs/u_ramp", R"({"texture": "ramp.png", "target": "half"})"}},
     "passes[2].inputs.u_ramp",
     "give only one source of \"target\", \"texture\", \"cube\" and \"generate\""},
    {"InputWithoutASource",
     {{"/passes/2/inputs/u_ramp", R"({"filter": "nearest"})"}},
     "passes[2].inputs.u_ramp",
     "give one source: \"target\", \"texture\", \"cube\" or \"generate\""},
    {"LayersOfATarget",
     {{"/passes/4/inputs/u_image", R"({"target": "half", "layers": 2})"}},
     "passes[4].inputs.u_image.layers",
     "only a \"texture\" file can be cut into layers"},
    {"SrgbOfATarget",
     {{"/passes/4/inputs/u_image", R"({"target": "half", "srgb": true})"}},
     "passes[4].inputs.u_image.srgb",
     "a target's encoding is its format (\"srgb8\")"},
    {"CubePathWithoutFace",
     {{"/passes/2/inputs/u_sky", R"({"cube": "sky/px.png"})"}},
     "passes[2].inputs.u_sky.cube",
     "a single path must contain {face}"},
    {"CubeWithFiveFiles",
     {{"/passes/2/inputs/u_sky", R"({"cube": ["a.png", "b.png", "c.png", "d.png", "e.png"]})"}},
     "passes[2].inputs.u_sky.cube",
     "must have at least 6 elements, got 5"},
    {"CheckerWithThreeColours",
     {{"/passes/2/inputs/u_gen",
       R"({"generate": {"pattern": "checker", "size": [8, 8], "colors": [[0,0,0,1], [1,1,1,1], [1,0,0,1]]}})"}},
     "passes[2].inputs.u_gen.generate.colors",
     "a checker takes exactly two colours"},
    {"GradientWithOneColour",
     {{"/passes/2/inputs/u_gen",
       R"({"generate": {"pattern": "gradient", "size": [8], "colors": [[0,0,0,1]]}})"}},
     "passes[2].inputs.u_gen.generate.colors",
     "a gradient needs at least two colour stops"},
    {"NoiseWithColours",
     {{"/passes/2/inputs/u_gen",
       R"({"generate": {"pattern": "noise", "size": [8], "colors": [[0,0,0,1]]}})"}},
     "passes[2].inputs.u_gen.generate.colors",
     "noise takes no colours"},
    {"GeneratedTooLarge",
     {{"/passes/2/inputs/u_gen", R"({"generate": {"pattern": "noise", "size": [4096, 4096, 2]}})"}},
     "passes[2].inputs.u_gen.generate.size",
     "has 33554432 texels; at most 16777216 are allowed"},
    {"PointLightWithADirection",
     {{"/scenes/0/lights/0/direction", "[0, -1, 0]"}},
     "scenes[0].lights[0].direction",
     "a point light shines in every direction; give only \"position\""},
    {"PointLightWithoutAPosition",
     {{"/scenes/0/lights/0/position", kDelete}},
     "scenes[0].lights[0].position",
     "required for a point light"},
    {"DirectionalLightWithAPosition",
     {{"/scenes/0/lights/1/position", "[1, 1, 1]"}},
     "scenes[0].lights[1].position",
     "a directional light has no position"},
    {"DirectionalLightWithoutADirection",
     {{"/scenes/0/lights/1/direction", kDelete}},
     "scenes[0].lights[1].direction",
     "required for a directional light"},
    {"DirectionalLightOfZeroDirection",
     {{"/scenes/0/lights/1/direction", "[0, 0, 0]"}},
     "scenes[0].lights[1].direction",
     "must not be the zero vector"},
    {"GradingPointsWithGoals",
     {{"/grading/points", "10"}},
     "grading.points",
     "cannot be given with goals: the lab's points are the sum of its goals' points"},

    // ---- validate: the lab folder, names
    {"IdIsNotTheFolder",
     {{"/id", "\"02-toon\""}},
     "id",
     "is \"02-toon\" but the lab folder is \"01-phong\"; they must be the same"},
    {"PassNameTwice",
     {{"/passes/1/name", "\"shadow\""}},
     "passes[1].name",
     "pass \"shadow\" is listed twice"},
    {"SceneNameTwice",
     {{"/scenes/2", R"({"name": "sphere", "file": "scenes/sphere.gltf"})"}},
     "scenes[2].name",
     "scene \"sphere\" is also the name of scenes[0]"},
    {"SceneNameClashesWithAnExpandedTime",
     {{"/scenes/2", R"({"name": "teapot_t1", "file": "scenes/sphere.gltf"})"}},
     "scenes[2].name",
     "scene \"teapot_t1\" is also the name of scenes[1]"},
    {"GoalIdTwice", {{"/goals/1/id", "\"shading\""}}, "goals[1].id", "goal \"shading\" is listed twice"},
    {"OwnTargetClashesWithATopLevelOne",
     {{"/passes/4/target", R"({"name": "half"})"}},
     "passes[4].target",
     "declares target \"half\", which targets.half already declares; to draw into it, write \"target\": "
     "\"half\""},

    // ---- validate: targets
    {"PassTargetUnknown",
     {{"/passes/4/target", "\"halff\""}},
     "passes[4].target",
     "no target is called \"halff\" (did you mean \"half\"?)"},
    {"CubeTargetNotSquare",
     {{"/targets/env/size", "[32, 16]"}},
     "targets.env",
     "a cube target must be square, got 32x16"},
    {"CubeTargetWithSampledDepth",
     {{"/targets/env/depth", "\"texture\""}},
     "targets.env.depth",
     "a cube target's depth cannot be sampled"},
    {"SceneDrawIntoACubeTarget",
     {{"/passes/1/draw", "\"scene\""}},
     "passes[1].draw",
     "a scene draw cannot render into the cube target \"env\""},
    {"ScaleBelowOnePixel",
     {{"/targets/half/scale", "0.001"}},
     "targets.half.scale",
     "gives a 0x0 target; each side must be from 1 to 4096 pixels"},
    {"ScaleAboveTheLimit",
     {{"/resolution", "[4096, 4096]"}, {"/targets/half/scale", "2"}},
     "targets.half.scale",
     "gives a 8192x8192 target"},
    {"DepthTestOnATargetWithoutDepth",
     {{"/passes/3/state", R"({"depth_test": true})"}},
     "passes[3].state.depth_test",
     "target \"half\" has no depth (\"depth\": \"none\")"},
    {"ClearColorOfAnUnknownAttachment",
     {{"/passes/2/state", R"({"clear_color": {"albdo": [0, 0, 0, 1]}})"}},
     "passes[2].state.clear_color.albdo",
     "target \"gbuf\" has no attachment \"albdo\" (did you mean \"albedo\"?)"},

    // ---- validate: inputs and the order of reads and draws
    {"InputTargetUnknown",
     {{"/passes/4/inputs/u_image", "\"hlaf\""}},
     "passes[4].inputs.u_image",
     "no target is called \"hlaf\" (did you mean \"half\"?)"},
    {"InputAttachmentUnknown",
     {{"/passes/4/inputs/u_normal", "\"gbuf.normals\""}},
     "passes[4].inputs.u_normal",
     "target \"gbuf\" has no attachment \"normals\" (did you mean \"normal\"?)"},
    {"InputObjectAttachmentUnknown",
     {{"/passes/4/inputs/u_normal", R"({"target": "gbuf.colour", "filter": "nearest"})"}},
     "passes[4].inputs.u_normal",
     "target \"gbuf\" has no attachment \"colour\""},
    {"DepthReadWithoutADepthTexture",
     {{"/passes/4/inputs/u_normal", "\"gbuf.depth\""}},
     "passes[4].inputs.u_normal",
     "reads the depth of target \"gbuf\", which cannot be sampled: give the target \"depth\": \"texture\""},
    {"DepthReadOfTheTargetDrawnInto",
     {{"/passes/0/inputs", R"({"u_self": "shadow.depth"})"}},
     "passes[0].inputs.u_self",
     "reads the depth of the target this pass draws into"},
    {"ReadsATargetNoPassDraws",
     {{"/targets/spare", "{}"}, {"/passes/4/inputs/u_spare", "\"spare\""}},
     "passes[4].inputs.u_spare",
     "reads target \"spare\", which no pass draws into"},
    {"ReadsATargetDrawnLaterACycle",
     {{"/passes/2/inputs/u_blurred", "\"half\""}},
     "passes[2].inputs.u_blurred",
     "reads target \"half\", which is first drawn by passes[3] (\"blur\") after this pass: a cycle. A pass "
     "reads what earlier passes drew, unless both are in one repeat group"},
    {"ReadsItsOwnTargetOutsideARepeat",
     {{"/passes/4/inputs/u_self", "\"final\""}},
     "passes[4].inputs.u_self",
     "reads target \"final\", which this pass draws into and no earlier pass drew: there is nothing to read "
     "yet, unless the pass is repeated"},
    {"SamplerAlsoAUniform",
     {{"/passes/2/uniforms/u_ramp", "1"}},
     "passes[2].inputs.u_ramp",
     "\"u_ramp\" is both a sampler input and a uniform value of this pass"},
    {"SceneUniformNamesASampler",
     {{"/scenes/0/uniforms", R"({"u_ramp": 1})"}},
     "scenes[0].uniforms.u_ramp",
     "\"u_ramp\" is a sampler input of passes[2]; a sampler gets a texture, not a value"},
    {"UniformReferenceToAnUnknownPass",
     {{"/passes/2/uniforms/u_light_matrix", "\"@shadw.view_projection\""}},
     "passes[2].uniforms.u_light_matrix",
     "no pass is called \"shadw\" (did you mean \"shadow\"?)"},
    {"UniformReferenceInsideAStructToAnUnknownPass",
     {{"/scenes/0/uniforms", R"({"u_lights": [{"matrix": "@nowhere.view"}]})"}},
     "scenes[0].uniforms.u_lights[0].matrix",
     "no pass is called \"nowhere\""},

    // ---- validate: repeats and work
    {"RepeatFromALaterPass",
     {{"/passes/3/repeat", R"({"count": 2, "from": "final"})"}},
     "passes[3].repeat.from",
     "\"final\" comes after this pass; \"from\" names the first pass of the group, which ends at this pass"},
    {"RepeatFromAnUnknownPass",
     {{"/passes/3/repeat", R"({"count": 2, "from": "blurr"})"}},
     "passes[3].repeat.from",
     "no pass is called \"blurr\" (did you mean \"blur\"?)"},
    {"OverlappingRepeatGroups",
     {{"/passes/4/repeat", R"({"count": 2, "from": "shade"})"}},
     "passes[4].repeat",
     "overlaps the repeat group of pass \"blur\"; repeat groups cannot overlap or nest"},
    {"SceneRepeatsAPassWithoutRepeat",
     {{"/scenes/1/repeats", R"({"shade": 2})"}},
     "scenes[1].repeats.shade",
     "pass \"shade\" has no \"repeat\" to change"},
    {"SceneRepeatsAnUnknownPass",
     {{"/scenes/1/repeats", R"({"blurr": 2})"}},
     "scenes[1].repeats.blurr",
     "no pass is called \"blurr\" (did you mean \"blur\"?)"},
    // 10000 runs of a pass into a cube target are 60000 per scene; each of the three (expanded)
    // scenes is over the bound.
    {"TooMuchWorkForOneScene",
     {{"/passes/1/repeat", "10000"}},
     "scenes[0]",
     "runs passes 60007 times for one scene; at most 20000 are allowed (lower \"repeat\")",
     3},
    // 2400 runs of a group of 8 (the cube pass counts six) fit one scene; 17 scenes do not fit a lab.
    {"TooMuchWorkForTheLab",
     {{"/passes/3/repeat", R"({"count": 2400, "from": "sky"})"},
      {"/scenes/1", R"({"name": "teapot", "file": "scenes/teapot.gltf",
                        "times": [0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15]})"}},
     "scenes",
     "together run passes 326434 times; at most 200000 are allowed"},

    // ---- validate: cameras
    {"FarNotBeyondNear",
     {{"/scenes/0/camera/far", "0.1"}},
     "scenes[0].camera.far",
     "must be greater than near (0.1), got 0.1"},
    {"FarNotBeyondNearInAPassCamera",
     {{"/passes/0/camera", R"({"near": 5, "far": 1})"}},
     "passes[0].camera.far",
     "must be greater than near (5), got 1"},
    {"FarNotBeyondNearOnATimesScene",
     {{"/scenes/1/camera", R"({"near": 2, "far": 1})"}},
     "scenes[1].camera.far",
     "must be greater than near (2), got 1"},
    {"UpParallelToTheView",
     {{"/scenes/0/camera/up", "[0, 0, -2]"}},
     "scenes[0].camera.up",
     "must not be parallel to the viewing direction (target - position)"},
    {"UpZero", {{"/scenes/0/camera/up", "[0, 0, 0]"}}, "scenes[0].camera.up", "must not be the zero vector"},
    {"TargetAtThePosition",
     {{"/scenes/0/camera/target", "[0, 0, 3]"}},
     "scenes[0].camera.target",
     "must differ from position"},
    {"LightCameraWithAPosition",
     {{"/passes/0/camera/position", "[0, 1, 0]"}},
     "passes[0].camera",
     "\"light\" places the camera at the light; leave \"position\" and \"target\" out"},
    {"HeightWithoutOrthographic",
     {{"/scenes/0/camera", R"({"height": 2})"}},
     "scenes[0].camera.height",
     "applies to \"projection\": \"orthographic\" only"},
    {"FieldOfViewOfAnOrthographicCamera",
     {{"/scenes/0/camera", R"({"projection": "orthographic", "height": 2, "fov_y_deg": 40})"}},
     "scenes[0].camera.fov_y_deg",
     "an orthographic camera has no field of view; give \"height\""},

    // ---- validate: grading and goals
    {"LastPassNotGraded",
     {{"/passes/4/graded", "false"}},
     "passes[4].graded",
     "the last pass is the lab's result and is always graded; leave \"graded\" out"},
    {"GradedAttachmentUnknown",
     {{"/passes/2/graded", R"(["albedo", "normals"])"}},
     "passes[2].graded",
     "target \"gbuf\" has no attachment \"normals\" (did you mean \"normal\"?)"},
    {"GradedDepthOfATargetWithoutDepth",
     {{"/passes/4/target", R"({"depth": "none"})"}, {"/passes/4/graded", R"(["depth"])"}},
     "passes[4].graded",
     "target \"final\" has no depth to grade"},
    {"GoalSceneUnknown",
     {{"/goals/1/scenes", R"(["sphere", "teapott"])"}},
     "goals[1].scenes[1]",
     "no scene is called \"teapott\" (did you mean \"teapot\"?)"},
    {"GoalPassUnknown",
     {{"/goals/1/passes", R"(["fianl"])"}},
     "goals[1].passes[0]",
     "no pass is called \"fianl\" (did you mean \"final\"?)"},
    {"GoalPassNotGraded",
     {{"/goals/1/passes", R"(["final", "blur"])"}},
     "goals[1].passes[1]",
     "pass \"blur\" is not graded; mark it \"graded\": true to grade a goal on it"},
    {"SceneInNoGoal",
     {{"/goals/0/scenes", R"(["sphere"])"}, {"/goals/1/scenes", R"(["sphere"])"}},
     "scenes[1]",
     "scene \"teapot\" is in no goal's \"scenes\": every graded scene must test some goal"},
    {"GradedPassCheckedByNoGoal",
     {{"/goals/1/passes", R"(["shade"])"}},
     "passes[4].graded",
     "pass \"final\" is graded, but no goal checks it in scene \"sphere\", \"teapot_t0\", \"teapot_t1\"; add "
     "it "
     "to a goal's \"passes\" or stop grading it"},
    {"GradedPassCheckedByNoGoalInOneTime",
     {{"/goals/1/scenes", R"(["sphere", "teapot_t0"])"}},
     "passes[4].graded",
     "no goal checks it in scene \"teapot_t1\""},

    // ---- validate: files
    {"ProgramFileMissing",
     {{"/passes/2/program/fragment", "\"nope.frag\""}},
     "passes[2].program.fragment",
     "/labs/01-phong/nope.frag: file not found"},
    {"ProgramFileIsAFolder",
     {{"/passes/2/program/fragment", "\"sky\""}},
     "passes[2].program.fragment",
     "not a regular file"},
    {"SharedFileMissing",
     {{"/passes/4/program", R"({"fragment": "shared/nope.frag"})"}},
     "passes[4].program.fragment",
     "/labs/shared/nope.frag: file not found"},
    {"LabFileNamedAsShared",
     {{"/passes/2/program/fragment", "\"shared/phong.frag\""}},
     "passes[2].program.fragment",
     "/labs/shared/phong.frag: file not found"},
    // The template's file is used by three passes: each is named.
    {"SharedFileMissingInATemplate",
     {{"/templates/post/program/vertex", "\"shared/nope.vert\""}},
     "passes[1].program.vertex",
     "/labs/shared/nope.vert: file not found",
     3},
    {"TextureFileMissing",
     {{"/passes/2/inputs/u_ramp", R"({"texture": "nope.png"})"}},
     "passes[2].inputs.u_ramp.texture",
     "/labs/01-phong/nope.png: file not found"},
    {"CubeFaceMissing",
     {{"/passes/2/inputs/u_sky", R"({"cube": "partial/{face}.png"})"}},
     "passes[2].inputs.u_sky.cube[3]",
     "/labs/01-phong/partial/ny.png: file not found"},
    {"CubeFaceOfAListMissing",
     {{"/passes/2/inputs/u_sky",
       R"({"cube": ["sky/px.png", "sky/nx.png", "sky/py.png", "sky/ny.png", "sky/pz.png", "sky/no.png"]})"}},
     "passes[2].inputs.u_sky.cube[5]",
     "sky/no.png: file not found"},
    {"SceneFileMissing",
     {{"/scenes/1/file", "\"scenes/torus.gltf\""}},
     "scenes[1].file",
     "/labs/scenes/torus.gltf: file not found"},
    {"SceneFileInTheLabFolder",
     {{"/scenes/0/file", "\"sphere.gltf\""}},
     "scenes[0].file",
     "/labs/sphere.gltf: file not found"},
    {"SceneFileRequired",
     {{"/scenes/0/file", kDelete}},
     "scenes[0].file",
     "is required: a pass draws the scene (\"draw\": \"scene\")"},
    {"StudentFileMissing",
     {{"/student_files", R"(["phong.frag", "nope.frag"])"}},
     "student_files[1]",
     "/labs/01-phong/nope.frag: file not found"},
    {"StudentFileUnderShared",
     {{"/student_files", R"(["phong.frag", "shared/fullscreen.vert"])"}},
     "student_files[1]",
     "a shared file cannot be a student file"},
};

class LabSpecBroken : public LabSpecFixture, public ::testing::WithParamInterface<BrokenCase> {};

TEST_P(LabSpecBroken, IsRefusedWithPathAndProblem) {
    const BrokenCase& c = GetParam();
    const LabSpecResult r = parseJson(applyEdits(json::parse(kBaseSpec), c.edits));
    EXPECT_FALSE(r.ok);
    EXPECT_TRUE(hasError(r, c.path, c.problem));
    EXPECT_EQ(r.errors.size(), c.count) << allErrors(r);
}

INSTANTIATE_TEST_SUITE_P(LabSpec, LabSpecBroken, ::testing::ValuesIn(kBrokenCases),
                         [](const ::testing::TestParamInfo<BrokenCase>& p) {
                             return std::string(p.param.name);
                         });

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

// =============================================================================================
// JSON syntax and the limits of the loader

using LabSpecSyntax = LabSpecFixture;

TEST_F(LabSpecSyntax, ParseErrorNamesLineAndColumn) {
    const LabSpecResult r = parseText("{\n  \"schema\": 2,\n  \"id\": \"01-phong\",\n  \"passes\": [,]\n}\n");
    EXPECT_FALSE(r.ok);
    ASSERT_EQ(r.errors.size(), 1u) << allErrors(r);
    EXPECT_EQ(r.errors[0].rfind(std::string(kOrigin) + ": line 4, column 14: syntax error", 0), 0u)
        << r.errors[0];
    EXPECT_NE(r.errors[0].find("unexpected ','"), std::string::npos) << r.errors[0];
}

TEST_F(LabSpecSyntax, ColumnsCountCharactersNotBytes) {
    // "Ü" is two bytes in UTF-8, "€" three and "😀" four; the stray x is the 16th character.
    for (const std::string& text : {std::string("x"), std::string("\xC3\x9C"), std::string("\xE2\x82\xAC"),
                                    std::string("\xF0\x9F\x98\x80")}) {
        const LabSpecResult r = parseText("{\"title\": \"" + text + "\", x}");
        ASSERT_EQ(r.errors.size(), 1u) << allErrors(r);
        EXPECT_EQ(r.errors[0].rfind(std::string(kOrigin) + ": line 1, column 16: ", 0), 0u) << r.errors[0];
    }
    const LabSpecResult r = parseText("{\"title\": \"\xC3\x9C\xC3\x9C\xC3\x9C\",\n \"\xE2\x82\xAC\": x}");
    ASSERT_EQ(r.errors.size(), 1u) << allErrors(r);
    EXPECT_EQ(r.errors[0].rfind(std::string(kOrigin) + ": line 2, column 7: ", 0), 0u) << r.errors[0];
}

TEST_F(LabSpecSyntax, TrailingCommaIsASyntaxError) {
    json spec = json::parse(kMinimalSpec);
    std::string text = spec.dump(2);
    text.insert(text.rfind('\n'), ",");  // after the last member: {..., "schema": 2,}
    const LabSpecResult r = parseText(text);
    ASSERT_EQ(r.errors.size(), 1u) << allErrors(r);
    EXPECT_NE(r.errors[0].find("syntax error"), std::string::npos) << r.errors[0];
    EXPECT_NE(r.errors[0].find("unexpected '}'"), std::string::npos) << r.errors[0];
}

TEST_F(LabSpecSyntax, TruncatedFileNamesTheEnd) {
    const LabSpecResult r = parseText("{\n  \"schema\": 2,\n");
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
    const LabSpecResult r = parseText("{\n  // a comment\n  \"schema\": 2\n}");
    EXPECT_FALSE(r.ok);
    ASSERT_EQ(r.errors.size(), 1u) << allErrors(r);
    EXPECT_EQ(r.errors[0].rfind(std::string(kOrigin) + ": line 2, column ", 0), 0u) << r.errors[0];
}

TEST_F(LabSpecSyntax, NumberOverflowNamesItsLine) {
    json spec = json::parse(kBaseSpec);
    spec["scenes"][0]["time"] = 0.5;
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

TEST_F(LabSpecSyntax, DuplicateKeysAreErrorsNamingTheirPath) {
    // A JSON reader keeps only the last of a repeated key; the first would silently vanish.
    const LabSpecResult r = parseText(R"({
      "schema": 2, "id": "01-phong",
      "passes": [{"name": "shade", "program": {"vertex": "phong.vert", "fragment": "phong.frag"},
                  "uniforms": {"u_a": 1, "u_a": 2}, "state": {"cull": "none"}, "state": {"cull": "back"}}],
      "scenes": [{"name": "sphere", "file": "scenes/sphere.gltf"},
                 {"name": "s2", "name": "s3", "file": "scenes/cube.glb"}],
      "targets": {"a b": {}, "a b": {}}
    })");
    EXPECT_FALSE(r.ok);
    EXPECT_TRUE(hasError(r, "passes[0].uniforms.u_a", "duplicate key"));
    EXPECT_TRUE(hasError(r, "passes[0].state", "duplicate key"));
    EXPECT_TRUE(hasError(r, "scenes[1].name", "duplicate key"));
    EXPECT_TRUE(hasError(r, "targets[\"a b\"]", "duplicate key"));
    EXPECT_EQ(r.errors.size(), 4u) << allErrors(r);
}

TEST_F(LabSpecSyntax, NestingIsLimitedTo32Levels) {
    // The root object, passes, the pass and its uniforms are four levels; then k arrays.
    auto nested = [](int k) {
        json spec = json::parse(kMinimalSpec);
        std::string value = std::string(static_cast<std::size_t>(k), '[') + "1" +
                            std::string(static_cast<std::size_t>(k), ']');
        std::string text = spec.dump();
        const std::string needle = "\"name\":\"shade\"";
        text.insert(text.find(needle), "\"uniforms\":{\"u_deep\":" + value + "},");
        return text;
    };
    const LabSpecResult at_limit = parseText(nested(28));
    EXPECT_TRUE(at_limit.ok) << allErrors(at_limit);
    const LabSpecResult deeper = parseText(nested(29));
    EXPECT_FALSE(deeper.ok);
    ASSERT_EQ(deeper.errors.size(), 1u) << allErrors(deeper);
    EXPECT_NE(deeper.errors[0].find("nested deeper than 32 levels"), std::string::npos) << deeper.errors[0];
    EXPECT_NE(deeper.errors[0].find("passes[0].uniforms.u_deep"), std::string::npos) << deeper.errors[0];

    // Far deeper than any stack would survive, unclosed or closed: refused, not a crash.
    const LabSpecResult abyss = parseText(std::string(500000, '['));
    ASSERT_EQ(abyss.errors.size(), 1u) << allErrors(abyss);
    EXPECT_NE(abyss.errors[0].find("nested deeper than 32 levels"), std::string::npos) << abyss.errors[0];
    const LabSpecResult closed = parseText(std::string(200000, '[') + std::string(200000, ']'));
    ASSERT_EQ(closed.errors.size(), 1u) << allErrors(closed);
    EXPECT_NE(closed.errors[0].find("nested deeper than 32 levels"), std::string::npos) << closed.errors[0];
}

TEST_F(LabSpecSyntax, StringsAreLimitedTo4096Bytes) {
    json spec = json::parse(kMinimalSpec);
    spec["$schema"] = std::string(4096, 'a');
    const LabSpecResult at_limit = parseJson(spec);
    EXPECT_TRUE(at_limit.ok) << allErrors(at_limit);

    spec["$schema"] = std::string(4097, 'a');
    const LabSpecResult longer = parseJson(spec);
    EXPECT_FALSE(longer.ok);
    EXPECT_TRUE(hasError(longer, "[\"$schema\"]", "a string of 4097 bytes is longer than the limit of 4096"));
    EXPECT_EQ(longer.errors.size(), 1u) << allErrors(longer);

    spec = json::parse(kMinimalSpec);
    spec["passes"][0]["uniforms"][std::string(100000, 'u')] = 1;  // a key: refused, not a crash
    const LabSpecResult long_key = parseJson(spec);
    EXPECT_FALSE(long_key.ok);
    EXPECT_TRUE(hasError(long_key, "passes[0].uniforms", "a key of 100000 bytes is too long"));
    EXPECT_EQ(long_key.errors.size(), 1u) << allErrors(long_key);
}

// =============================================================================================
// Reading lab.json from disk

using LabSpecFile = LabSpecFixture;

TEST_F(LabSpecFile, MissingLabJsonNamesThePath) {
    const LabSpecResult r = shaderlab::parseLabSpec(lab_.string());
    EXPECT_FALSE(r.ok);
    ASSERT_EQ(r.errors.size(), 1u) << allErrors(r);
    EXPECT_EQ(r.errors[0], (lab_ / "lab.json").string() + ": file not found");
}

TEST_F(LabSpecFile, LabJsonThatIsAFolderIsRefused) {
    fs::create_directories(lab_ / "lab.json");
    const LabSpecResult r = shaderlab::parseLabSpec(lab_.string());
    EXPECT_FALSE(r.ok);
    ASSERT_EQ(r.errors.size(), 1u) << allErrors(r);
    EXPECT_EQ(r.errors[0], (lab_ / "lab.json").string() + ": not a regular file");
}

TEST_F(LabSpecFile, MissingLabFolderNamesIt) {
    const std::string missing = (labs_ / "42-nothing").string();
    const LabSpecResult r = shaderlab::parseLabSpec(missing);
    EXPECT_FALSE(r.ok);
    ASSERT_EQ(r.errors.size(), 1u) << allErrors(r);
    EXPECT_NE(r.errors[0].find("the lab folder " + missing + " does not exist"), std::string::npos)
        << r.errors[0];
}

TEST_F(LabSpecFile, FileOverOneMebibyteIsRefused) {
    std::string text = kMinimalSpec;
    text.insert(text.size() - 1, std::string((1u << 20) + 1 - text.size(), ' '));  // still valid JSON
    ASSERT_EQ(text.size(), (1u << 20) + 1);
    writeFile(lab_ / "lab.json", text);
    const LabSpecResult r = shaderlab::parseLabSpec(lab_.string());
    EXPECT_FALSE(r.ok);
    ASSERT_EQ(r.errors.size(), 1u) << allErrors(r);
    EXPECT_EQ(r.errors[0],
              (lab_ / "lab.json").string() + ": file is 1048577 bytes, more than the limit of 1048576");

    const LabSpecResult from_text = parseText(text);  // the text entry point has the same cap
    EXPECT_FALSE(from_text.ok);
    EXPECT_TRUE(hasError(from_text, "", "is 1048577 bytes, more than the limit of 1048576 (1 MiB)"));

    text.erase(text.size() - 2, 1);  // exactly 1 MiB: accepted
    ASSERT_EQ(text.size(), 1u << 20);
    writeFile(lab_ / "lab.json", text);
    const LabSpecResult at_limit = shaderlab::parseLabSpec(lab_.string());
    EXPECT_TRUE(at_limit.ok) << allErrors(at_limit);
}

TEST_F(LabSpecFile, ErrorsNameTheFileTheyCameFrom) {
    writeFile(lab_ / "lab.json", R"({"schema": 2, "id": "01-phong", "passes": []})");
    const LabSpecResult r = shaderlab::parseLabSpec(lab_.string());
    EXPECT_FALSE(r.ok);
    ASSERT_EQ(r.errors.size(), 2u) << allErrors(r);  // passes is empty; scenes is missing
    const std::string origin = (lab_ / "lab.json").string();
    for (const std::string& e : r.errors) EXPECT_EQ(e.rfind(origin + ": ", 0), 0u) << e;
}

// =============================================================================================
// docs/lab-format.md and docs/lab.schema.json stay true

// The `n`th ```json block after the heading `heading` of docs/lab-format.md.
std::string jsonBlockOfTheDocs(const std::string& heading, int n) {
    const std::string doc = readText(fs::path(SHADERLAB_SOURCE_DIR) / "docs" / "lab-format.md");
    std::size_t at = doc.find("\n" + heading + "\n");
    if (at == std::string::npos) return "";
    for (int i = 0; i <= n; ++i) {
        at = doc.find("```json\n", at);
        if (at == std::string::npos) return "";
        at += 8;
        if (i < n) at = doc.find("```", at) + 3;
    }
    const std::size_t end = doc.find("```", at);
    return end == std::string::npos ? "" : doc.substr(at, end - at);
}

using LabSpecDocs = LabSpecFixture;

TEST_F(LabSpecDocs, TheCompleteExampleParses) {
    const std::string text = jsonBlockOfTheDocs("## A complete example", 0);
    ASSERT_FALSE(text.empty()) << "no ```json block under \"## A complete example\" in docs/lab-format.md";
    const json doc = json::parse(text);
    const fs::path lab = labs_ / doc.at("id").get<std::string>();
    // Every file it names, empty: the parser checks that files exist, not what they hold.
    auto create = [&](const std::string& path) {
        writeFile(path.rfind("shared/", 0) == 0 ? labs_ / path : lab / path, "");
    };
    auto programs = [&](const json& pass) {
        if (!pass.contains("program")) return;
        for (const auto& stage : pass["program"].items()) create(stage.value());
        if (pass.contains("inputs"))
            for (const auto& in : pass["inputs"].items())
                if (in.value().is_object() && in.value().contains("texture")) create(in.value()["texture"]);
    };
    for (const json& pass : doc.at("passes")) programs(pass);
    const json templates = doc.value("templates", json::object());
    for (const auto& t : templates.items()) programs(t.value());
    const json student_files = doc.value("student_files", json::array());
    for (const json& f : student_files) create(f);
    for (const json& scene : doc.at("scenes"))
        if (scene.contains("file")) writeFile(labs_ / scene["file"].get<std::string>(), "{}");
    writeFile(lab / "lab.json", text);

    const LabSpecResult r = shaderlab::parseLabSpec(lab.string());
    ASSERT_TRUE(r.ok) << allErrors(r);
    // What the prose around it says.
    const shaderlab::LabSpec& s = r.spec;
    EXPECT_EQ(s.id, "42-example");
    std::vector<std::string> scenes;
    for (const shaderlab::SceneSpec& sc : s.scenes) scenes.push_back(sc.name);
    EXPECT_EQ(scenes, (std::vector<std::string>{"teapot_t0", "teapot_t1", "grazing"}));  // two times
    const shaderlab::TargetSpec* half = s.findTarget("half_a");
    ASSERT_NE(half, nullptr);
    EXPECT_EQ(half->width, s.width / 2);  // half size
    const shaderlab::TargetSpec* gbuffer = s.findTarget("gbuffer");
    ASSERT_NE(gbuffer, nullptr);
    EXPECT_EQ(gbuffer->attachments.size(), 2u);  // two attachments
    EXPECT_EQ(s.findPass("blur_h")->program.fragment,
              s.findPass("blur_v")->program.fragment);  // one template
    EXPECT_EQ(s.findPass("combine")->draw, shaderlab::DrawKind::Fullscreen);
    EXPECT_EQ(s.goals.size(), 3u);
    EXPECT_FLOAT_EQ(s.grading.points, 10.0f);
    EXPECT_EQ(s.student_files, doc.at("student_files").get<std::vector<std::string>>());
}

TEST_F(LabSpecDocs, TheSmallestExampleParsesWithTheDefaults) {
    const std::string text = jsonBlockOfTheDocs("## A complete example", 1);
    ASSERT_FALSE(text.empty()) << "no second ```json block under \"## A complete example\"";
    EXPECT_EQ(json::parse(text),
              json::parse(kMinimalSpec));  // what MinimalSpecGetsTheDocumentedDefaults reads
    const LabSpecResult r = parseText(text);
    ASSERT_TRUE(r.ok) << allErrors(r);
    EXPECT_EQ(r.spec.passes[0].graded, (std::vector<std::string>{"color"}));
    EXPECT_EQ(r.spec.goals.size(), 1u);
}

TEST_F(LabSpecDocs, TheTemplateExampleIsAPartOfAValidLab) {
    // The bloom fragment under "Templates": its template, and its two complete pass lines after a
    // pass drawing "bright".
    const std::string text = jsonBlockOfTheDocs("### Templates", 0);
    ASSERT_FALSE(text.empty());
    json spec = json::parse(kMinimalSpec);
    json passes =
        json::parse(R"([{"name": "bright", "program": {"vertex": "phong.vert", "fragment": "post.frag"}}])");
    std::string templates = text.substr(0, text.find("\"passes\""));
    while (!templates.empty() &&
           (templates.back() == ',' || std::isspace(static_cast<unsigned char>(templates.back()))))
        templates.pop_back();
    spec["templates"] = json::parse("{" + templates + "}").at("templates");
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);) {
        line.erase(0, line.find_first_not_of(' '));
        while (!line.empty() && (line.back() == ',' || line.back() == ' ')) line.pop_back();
        if (line.rfind("{ \"name\":", 0) == 0) passes.push_back(json::parse(line));
    }
    ASSERT_EQ(passes.size(), 3u) << text;
    spec["passes"] = passes;
    spec["targets"] = {{"blur0_a", json::object()}, {"blur0_b", json::object()}};
    const LabSpecResult r = parseJson(spec);
    ASSERT_TRUE(r.ok) << allErrors(r);
    EXPECT_EQ(r.spec.passes[1].name, "blur0_h");
    EXPECT_EQ(r.spec.passes[2].program.fragment, "blur.frag");
    EXPECT_EQ(r.spec.passes[2].state.blend, shaderlab::BlendMode::None);
    EXPECT_EQ(r.spec.passes[2].draw, shaderlab::DrawKind::Fullscreen);
}

TEST(LabSchema, TheSchemaFileParsesAndIsTheCompiledInCopy) {
    const std::string text = readText(fs::path(SHADERLAB_SOURCE_DIR) / "docs" / "lab.schema.json");
    ASSERT_FALSE(text.empty());
    const json schema = json::parse(text);  // throws, failing the test, if it is not JSON
    EXPECT_EQ(schema.at("$schema"), "http://json-schema.org/draft-07/schema#");
    EXPECT_EQ(schema.at("required"), json::parse(R"(["schema", "id", "passes", "scenes"])"));
    EXPECT_EQ(shaderlab::labSchemaText(), text);
}

TEST(LabSchema, ItAcceptsTheDocsExampleAndRefusesAMistake) {
    const json schema = json::parse(shaderlab::labSchemaText());
    const shaderlab::JsonSchemaChecker checker(schema);
    json doc = json::parse(jsonBlockOfTheDocs("## A complete example", 0));
    EXPECT_TRUE(checker.check(doc).empty());
    doc["passes"][0]["state"]["cull"] = "sideways";
    const std::vector<shaderlab::SchemaProblem> problems = checker.check(doc);
    ASSERT_EQ(problems.size(), 1u);
    EXPECT_EQ(problems[0].path, "passes[0].state.cull");
}

// The uniforms a lab may not set are those docs/student-contract.md lists as the framework's.
TEST(LabSchema, TheRefusedUniformNamesAreTheFrameworksInTheStudentContract) {
    const std::string contract = readText(fs::path(SHADERLAB_SOURCE_DIR) / "docs" / "student-contract.md");
    std::set<std::string> documented;
    const std::regex row(R"(\n\| `(u_[A-Za-z0-9_]+)` \| `)");
    for (auto it = std::sregex_iterator(contract.begin(), contract.end(), row); it != std::sregex_iterator();
         ++it)
        documented.insert((*it)[1]);
    const json schema = json::parse(shaderlab::labSchemaText());
    std::set<std::string> refused;
    for (const json& n : schema.at("definitions").at("lab_uniform_name").at("allOf")[1].at("not").at("enum"))
        refused.insert(n.get<std::string>());
    EXPECT_GE(documented.size(), 10u);
    EXPECT_EQ(refused, documented);
}

}  // namespace
