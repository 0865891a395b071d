// Tests of the lab.json parser, schema 2 (framework/lab/src/lab_spec*.cpp), on valid specs,
// against its contract, docs/lab-format.md: a valid spec becomes the expected typed values,
// defaults included (those that depend on other fields too). Mistakes are in
// lab_spec_broken_test.cpp and lab_spec_errors_test.cpp, the loader's limits in
// lab_spec_load_test.cpp, the docs and the schema in lab_spec_docs_test.cpp. Each test builds its
// own labs root under the temp directory (lab_spec_fixture.h); nothing here renders.
#include "shaderlab/lab/lab_spec.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "lab_spec_fixture.h"

namespace {

using namespace lab_spec_test;

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

// tests/data/labspec/full.json, every feature of the format in one lab, read from disk as a lab
// is; the FullFixture tests check one part each of what it becomes.
LabSpecResult parseFullFixture(const fs::path& lab) {
    fs::copy_file(fs::path(SHADERLAB_TEST_DATA) / "labspec" / "full.json", lab / "lab.json");
    return shaderlab::parseLabSpec(lab.string());
}

// =============================================================================================
// Valid specs

using LabSpecParse = LabSpecFixture;

TEST_F(LabSpecParse, TheBaseSpecOfTheErrorTableIsValid) {
    const LabSpecResult r = parseText(kBaseSpec);
    EXPECT_TRUE(r.ok) << allErrors(r);
    EXPECT_TRUE(r.errors.empty());
}

TEST_F(LabSpecParse, FullFixtureGivesTypedValues) {
    const LabSpecResult r = parseFullFixture(lab_);
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
}

TEST_F(LabSpecParse, FullFixtureGivesTypedTargets) {
    const LabSpecResult r = parseFullFixture(lab_);
    ASSERT_TRUE(r.ok) << allErrors(r);
    const shaderlab::LabSpec& s = r.spec;
    using namespace shaderlab;

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
}

TEST_F(LabSpecParse, FullFixtureGivesTypedPassesAndStates) {
    const LabSpecResult r = parseFullFixture(lab_);
    ASSERT_TRUE(r.ok) << allErrors(r);
    const shaderlab::LabSpec& s = r.spec;
    using namespace shaderlab;

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

    const PassSpec& gbuffer = s.passes[2];
    EXPECT_EQ(gbuffer.target, "gbuffer");
    ASSERT_EQ(gbuffer.state.clear_colors.size(), 2u);  // one per attachment
    EXPECT_EQ(gbuffer.state.clear_colors[0], glm::vec4(0.1f, 0.2f, 0.3f, 1.0f));
    EXPECT_FALSE(gbuffer.state.clear_colors[1].has_value());  // "normal": null keeps what is there
    EXPECT_TRUE(gbuffer.state.clear_depth);
    EXPECT_TRUE(gbuffer.state.depth_test);
    EXPECT_TRUE(gbuffer.state.depth_write);
    EXPECT_EQ(gbuffer.state.depth_func, DepthFunc::LessEqual);

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

    const PassSpec& combine = s.passes[4];
    EXPECT_EQ(combine.target, "lit");
    EXPECT_EQ(combine.draw, DrawKind::Fullscreen);
    EXPECT_FALSE(combine.state.depth_test);
    EXPECT_FALSE(combine.state.depth_write);
    EXPECT_EQ(combine.state.clear_colors, (Clears{kBlack}));

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

    const PassSpec& blur_h = s.passes[7];
    EXPECT_EQ(blur_h.program.vertex, "shared/fullscreen.vert");
    EXPECT_EQ(blur_h.program.fragment, "blur.frag");
    EXPECT_EQ(blur_h.draw, DrawKind::Fullscreen);

    const PassSpec& last = s.passes[9];
    EXPECT_EQ(last.program.vertex, "shared/fullscreen.vert");  // the template's
    EXPECT_EQ(last.program.fragment, "final.frag");            // the pass's
    EXPECT_EQ(last.target, "final");
    EXPECT_FALSE(last.state.depth_test);  // fullscreen, although its target has a depth buffer
    EXPECT_FALSE(last.state.depth_write);
    EXPECT_TRUE(last.state.clear_depth);
    EXPECT_EQ(s.findPass("final"), &last);
    EXPECT_EQ(s.findPass("nothing"), nullptr);
}

TEST_F(LabSpecParse, FullFixtureGivesTypedInputs) {
    const LabSpecResult r = parseFullFixture(lab_);
    ASSERT_TRUE(r.ok) << allErrors(r);
    const shaderlab::LabSpec& s = r.spec;
    using namespace shaderlab;

    ASSERT_EQ(s.passes.size(), 10u);
    const PassSpec& sky = s.passes[1];
    ASSERT_EQ(sky.inputs.size(), 1u);
    const PassInput& faces = sky.inputs[0];
    EXPECT_EQ(faces.sampler, "u_faces");
    EXPECT_EQ(faces.source, InputSource::Cube);
    EXPECT_EQ(faces.cube_files, (std::vector<std::string>{"sky/px.png", "sky/nx.png", "sky/py.png",
                                                          "sky/ny.png", "sky/pz.png", "sky/nz.png"}));
    EXPECT_TRUE(faces.srgb);
    EXPECT_EQ(faces.path, "passes[1].inputs.u_faces");

    const PassSpec& combine = s.passes[4];
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

    const PassSpec& advect = s.passes[5];
    const PassInput* prev = inputOf(advect, "u_prev");  // its own target, inside a repeat group
    ASSERT_NE(prev, nullptr);
    EXPECT_EQ(prev->target, "sim");
}

TEST_F(LabSpecParse, FullFixtureGivesTypedUniforms) {
    const LabSpecResult r = parseFullFixture(lab_);
    ASSERT_TRUE(r.ok) << allErrors(r);
    const shaderlab::LabSpec& s = r.spec;
    using namespace shaderlab;

    ASSERT_EQ(s.passes.size(), 10u);
    const PassSpec& sky = s.passes[1];
    ASSERT_EQ(sky.uniforms.size(), 1u);  // from the template
    EXPECT_EQ(sky.uniforms[0].name, "u_gain");
    EXPECT_EQ(sky.uniforms[0].value, json(1));
    EXPECT_EQ(sky.uniforms[0].path, "passes[1].uniforms.u_gain");

    const PassSpec& gbuffer = s.passes[2];
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

    const PassSpec& combine = s.passes[4];
    ASSERT_EQ(combine.uniforms.size(), 2u);
    EXPECT_EQ(uniformOf(combine.uniforms, "u_steps")->value, json(4));

    const PassSpec& blur_h = s.passes[7];
    EXPECT_EQ(uniformOf(blur_h.uniforms, "u_direction")->value, json::parse("[1, 0]"));

    const PassSpec& last = s.passes[9];
    ASSERT_EQ(last.uniforms.size(), 2u);  // merged entry by entry
    EXPECT_EQ(uniformOf(last.uniforms, "u_gain")->value, json(1));
    EXPECT_EQ(uniformOf(last.uniforms, "u_exposure")->value, json(2));
}

TEST_F(LabSpecParse, FullFixtureGivesTypedRepeatGroups) {
    const LabSpecResult r = parseFullFixture(lab_);
    ASSERT_TRUE(r.ok) << allErrors(r);
    const shaderlab::LabSpec& s = r.spec;
    using namespace shaderlab;

    ASSERT_EQ(s.passes.size(), 10u);
    const PassSpec& shadow = s.passes[0];
    EXPECT_EQ(shadow.loop, -1);

    const PassSpec& advect = s.passes[5];
    EXPECT_EQ(advect.target, "sim");
    EXPECT_EQ(advect.loop, 0);

    const PassSpec& project = s.passes[6];
    EXPECT_EQ(project.loop, 0);

    const PassSpec& blur_h = s.passes[7];
    EXPECT_EQ(blur_h.loop, -1);
    EXPECT_EQ(s.passes[8].loop, 1);

    ASSERT_EQ(s.loops.size(), 2u);
    EXPECT_EQ(s.loops[0].first, 5u);
    EXPECT_EQ(s.loops[0].last, 6u);
    EXPECT_EQ(s.loops[0].count, 10);
    EXPECT_EQ(s.loops[0].declared_by, "project");
    EXPECT_EQ(s.loops[1].first, 8u);
    EXPECT_EQ(s.loops[1].last, 8u);
    EXPECT_EQ(s.loops[1].count, 2);
    EXPECT_EQ(s.loops[1].declared_by, "blur_v");
}

TEST_F(LabSpecParse, FullFixtureGivesTypedScenes) {
    const LabSpecResult r = parseFullFixture(lab_);
    ASSERT_TRUE(r.ok) << allErrors(r);
    const shaderlab::LabSpec& s = r.spec;
    using namespace shaderlab;

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
}

TEST_F(LabSpecParse, FullFixtureGivesTypedGradingAndGoals) {
    const LabSpecResult r = parseFullFixture(lab_);
    ASSERT_TRUE(r.ok) << allErrors(r);
    const shaderlab::LabSpec& s = r.spec;
    using namespace shaderlab;

    ASSERT_EQ(s.passes.size(), 10u);
    const PassSpec& shadow = s.passes[0];
    EXPECT_TRUE(shadow.graded.empty());

    const PassSpec& gbuffer = s.passes[2];
    EXPECT_EQ(gbuffer.graded, (std::vector<std::string>{"normal"}));
    EXPECT_EQ(gbuffer.compare, CompareMode::Hdr);            // graded, a float target, not the last pass
    EXPECT_FLOAT_EQ(gbuffer.thresholds.psnr_min_db, 28.0f);  // the lab's

    const PassSpec& outline = s.passes[3];
    EXPECT_TRUE(outline.graded.empty());
    EXPECT_EQ(outline.compare, CompareMode::Display);  // not graded

    const PassSpec& combine = s.passes[4];
    EXPECT_EQ(combine.graded, (std::vector<std::string>{"color"}));  // true: every attachment
    EXPECT_EQ(combine.compare, CompareMode::Display);
    EXPECT_FLOAT_EQ(combine.thresholds.psnr_min_db, 25.0f);  // the pass's own
    EXPECT_FLOAT_EQ(combine.thresholds.ssim_min, 0.9f);      // the lab's
    EXPECT_FLOAT_EQ(combine.thresholds.flip_mean_max, 0.1f);
    EXPECT_FLOAT_EQ(combine.thresholds.mismatch_max, 0.02f);
    EXPECT_FLOAT_EQ(combine.thresholds.pixel_tolerance, 0.04f);

    const PassSpec& blur_h = s.passes[7];
    EXPECT_FLOAT_EQ(blur_h.thresholds.ssim_min, 0.8f);      // the template's
    EXPECT_FLOAT_EQ(blur_h.thresholds.psnr_min_db, 28.0f);  // the lab's

    const PassSpec& last = s.passes[9];
    EXPECT_EQ(last.graded, (std::vector<std::string>{"color"}));  // the last pass
    EXPECT_EQ(last.compare, CompareMode::Display);                // a float target, but the last pass

    std::vector<std::string> scene_names;
    for (const SceneSpec& sc : s.scenes) scene_names.push_back(sc.name);

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

}  // namespace
