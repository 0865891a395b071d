// The general features of lab.json (docs/lab-format.md), each rendered on llvmpipe and checked
// pixel by pixel: textures bound by declared sampler type, target formats, attachments, sizes
// and cube faces, render state defaults, repeats with ping-pong and feedback, draws without a
// mesh, per-pass cameras, uniforms typed by declaration, #include; plus regressions of the bugs
// found while prototyping the course (uniforms and texture units leaking between passes, a
// fullscreen background hiding a later scene draw, camera overrides clipping the scene away,
// undeclared fragment outputs). Each test writes a small lab into a temporary labs root.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "gl_test_support.h"
#include "grader/metrics/image.h"
#include "shaderlab/lab/lab_spec.h"
#include "shaderlab/render/renderer.h"

namespace fs = std::filesystem;

namespace {

using shaderlab::RenderStatus;

const char* const kFullscreenVert = R"(#version 330 core
layout(location = 0) in vec3 a_position;
layout(location = 2) in vec2 a_texcoord;
out vec2 v_uv;
void main() { v_uv = a_texcoord; gl_Position = vec4(a_position, 1.0); }
)";

const char* const kSceneVert = R"(#version 330 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
uniform mat4 u_model_view_projection;
uniform mat3 u_normal_matrix;
out vec3 v_normal;
void main() { v_normal = u_normal_matrix * a_normal; gl_Position = u_model_view_projection * vec4(a_position, 1.0); }
)";

std::string sanitized(std::string s) {
    for (char& c : s)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    return s;
}

class LabFeatures : public ::testing::Test {
  protected:
    void SetUp() override {
        std::string err;
        if (!shaderlab::testing::sharedContext(shaderlab::Backend::OSMesa, &err)) FAIL() << err;
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        root_ = fs::temp_directory_path() /
                ("shaderlab_features_" + std::to_string(::getpid()) + "_" + sanitized(info->name()));
        fs::remove_all(root_);
        lab_ = root_ / "labs" / "70-test";
        fs::create_directories(lab_);
        fs::create_directories(root_ / "labs" / "scenes");
        for (const char* f : {"sphere.gltf", "sphere.bin"})
            fs::copy_file(fs::path(SHADERLAB_SOURCE_DIR) / "labs" / "scenes" / f,
                          root_ / "labs" / "scenes" / f);
        write("fullscreen.vert", kFullscreenVert);
        write("scene.vert", kSceneVert);
    }
    void TearDown() override { fs::remove_all(root_); }

    void write(const std::string& rel, const std::string& text) const {
        fs::create_directories((lab_ / rel).parent_path());
        std::ofstream(lab_ / rel, std::ios::binary) << text;
    }
    void png(const std::string& rel, const grader::Image& img) const {
        fs::create_directories((lab_ / rel).parent_path());
        std::string err;
        ASSERT_TRUE(grader::writePng(img, (lab_ / rel).string(), &err)) << err;
    }

    // Parses lab.json (wrapped in the schema and id) and renders it with the lab folder's shaders.
    shaderlab::LabRender render(const std::string& body, bool all_passes = false) {
        write("lab.json", "{\"schema\": 2, \"id\": \"70-test\", " + body + "}");
        const shaderlab::LabSpecResult parsed = shaderlab::parseLabSpec(lab_.string());
        std::string errors;
        for (const std::string& e : parsed.errors) errors += "\n" + e;
        EXPECT_TRUE(parsed.ok) << errors;
        spec_ = parsed.spec;
        shaderlab::RenderOptions options;
        options.keep_all_passes = all_passes;
        if (!parsed.ok) return {};
        return shaderlab::renderLab(spec_, lab_.string(), options);
    }

    // The image of `pass` (and attachment) in the first scene.
    static const grader::Image& image(const shaderlab::LabRender& r, const std::string& pass,
                                      const std::string& attachment = "") {
        // A blank stand-in keeps a missing image a failure rather than a crash.
        static const grader::Image kMissing(64, 64, 4, 0.0f);
        if (!r.scenes.empty())
            for (const shaderlab::PassImage& p : r.scenes[0].passes)
                if (p.pass == pass && (attachment.empty() || p.attachment == attachment)) return p.color;
        ADD_FAILURE() << "no image of pass " << pass << " " << attachment;
        return kMissing;
    }

    static std::string diagnostics(const shaderlab::LabRender& r) {
        std::string s = r.message;
        for (const shaderlab::Diagnostic& d : r.diagnostics)
            s += "\n" + d.file + ": " + d.severity + ": " + d.message;
        return s;
    }

    fs::path root_, lab_;
    shaderlab::LabSpec spec_;
};

// A fullscreen lab: one scene without a file, resolution w x h.
std::string fullscreenLab(const std::string& passes, int w = 8, int h = 8, const std::string& extra = "") {
    return "\"resolution\": [" + std::to_string(w) + ", " + std::to_string(h) + "], \"passes\": [" + passes +
           "], \"scenes\": [{\"name\": \"s\"}]" + extra;
}

std::string fragment(const std::string& declarations, const std::string& body) {
    return "#version 330 core\nin vec2 v_uv;\n" + declarations + "\nout vec4 o_color;\nvoid main() {\n" +
           body + "\n}\n";
}

// ---------------------------------------------------------------------------------------------
// Textures by declared type

TEST_F(LabFeatures, OneRampFeedsASampler1DAndASampler2D) {
    grader::Image ramp(4, 1, 3);
    for (int x = 0; x < 4; ++x)
        for (int c = 0; c < 3; ++c) ramp.at(x, 0, c) = 0.2f * static_cast<float>(x + 1);
    png("ramp.png", ramp);
    write("one.frag", fragment("uniform sampler1D u_ramp;", "o_color = texture(u_ramp, v_uv.x);"));
    write("two.frag", fragment("uniform sampler2D u_ramp;", "o_color = texture(u_ramp, vec2(v_uv.x, 0.5));"));
    const auto r = render(fullscreenLab(R"(
        {"name": "one", "program": {"vertex": "fullscreen.vert", "fragment": "one.frag"}, "draw": "fullscreen",
         "inputs": {"u_ramp": {"texture": "ramp.png", "filter": "nearest"}}, "graded": true},
        {"name": "two", "program": {"vertex": "fullscreen.vert", "fragment": "two.frag"}, "draw": "fullscreen",
         "inputs": {"u_ramp": {"texture": "ramp.png", "filter": "nearest"}}})"));
    ASSERT_EQ(r.status, RenderStatus::Ok) << diagnostics(r);
    for (const char* pass : {"one", "two"}) {
        const grader::Image& img = image(r, pass);
        ASSERT_EQ(img.width, 8);
        EXPECT_NEAR(img.at(0, 4, 0), 0.2f, 1e-3f) << pass;
        EXPECT_NEAR(img.at(3, 4, 0), 0.4f, 1e-3f) << pass;
        EXPECT_NEAR(img.at(7, 4, 0), 0.8f, 1e-3f) << pass;
    }
}

TEST_F(LabFeatures, NonRampImageForASampler1DIsAnErrorNamingTheKey) {
    png("square.png", grader::Image(4, 4, 3, 0.5f));
    write("one.frag", fragment("uniform sampler1D u_ramp;", "o_color = texture(u_ramp, v_uv.x);"));
    const auto r = render(
        fullscreenLab(R"({"name": "one", "program": {"vertex": "fullscreen.vert", "fragment": "one.frag"},
        "draw": "fullscreen", "inputs": {"u_ramp": {"texture": "square.png"}}})"));
    EXPECT_EQ(r.status, RenderStatus::LinkError);
    EXPECT_NE(r.message.find("passes[0].inputs.u_ramp"), std::string::npos) << r.message;
    EXPECT_NE(r.message.find("Nx1"), std::string::npos) << r.message;
}

TEST_F(LabFeatures, LayeredImageFeedsASampler3D) {
    grader::Image slices(2, 4, 3);  // top half slice 0 (0.25), bottom half slice 1 (0.75)
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 2; ++x)
            for (int c = 0; c < 3; ++c) slices.at(x, y, c) = y < 2 ? 0.25f : 0.75f;
    png("volume.png", slices);
    write("vol.frag", fragment("uniform sampler3D u_volume;",
                               "o_color = texture(u_volume, vec3(0.5, 0.5, v_uv.x < 0.5 ? 0.25 : 0.75));"));
    const auto r = render(
        fullscreenLab(R"({"name": "vol", "program": {"vertex": "fullscreen.vert", "fragment": "vol.frag"},
        "draw": "fullscreen", "inputs": {"u_volume": {"texture": "volume.png", "layers": 2, "filter": "nearest"}}})"));
    ASSERT_EQ(r.status, RenderStatus::Ok) << diagnostics(r);
    EXPECT_NEAR(image(r, "vol").at(1, 4, 0), 0.25f, 1e-3f);
    EXPECT_NEAR(image(r, "vol").at(6, 4, 0), 0.75f, 1e-3f);
}

TEST_F(LabFeatures, SixFacesFeedASamplerCube) {
    const char* faces[6] = {"px", "nx", "py", "ny", "pz", "nz"};
    for (int f = 0; f < 6; ++f)
        png(std::string("sky_") + faces[f] + ".png", grader::Image(2, 2, 3, 0.1f * (f + 1)));
    // Pixel column i looks along the axis of face i.
    write("cube.frag", fragment("uniform samplerCube u_sky;", R"(
        int i = int(v_uv.x * 6.0);
        vec3 axes[6] = vec3[6](vec3(1, 0, 0), vec3(-1, 0, 0), vec3(0, 1, 0), vec3(0, -1, 0), vec3(0, 0, 1), vec3(0, 0, -1));
        o_color = texture(u_sky, axes[i]);)"));
    const auto r = render(
        fullscreenLab(R"({"name": "cube", "program": {"vertex": "fullscreen.vert", "fragment": "cube.frag"},
        "draw": "fullscreen", "inputs": {"u_sky": {"cube": "sky_{face}.png", "filter": "nearest"}}})",
                      6, 2));
    ASSERT_EQ(r.status, RenderStatus::Ok) << diagnostics(r);
    for (int f = 0; f < 6; ++f)
        EXPECT_NEAR(image(r, "cube").at(f, 1, 0), 0.1f * (f + 1), 2.5e-3f) << faces[f];
}

TEST_F(LabFeatures, DepthTargetFeedsSampler2DAndSampler2DShadow) {
    // A quad over the left half at NDC z = 0.5 (window depth 0.75); the right half keeps depth 1.
    write("half.vert", R"(#version 330 core
        void main() {
            vec2 c[4] = vec2[4](vec2(-1, -1), vec2(0, -1), vec2(-1, 1), vec2(0, 1));
            gl_Position = vec4(c[gl_VertexID], 0.5, 1.0);
        })");
    write("white.frag", "#version 330 core\nout vec4 o_color;\nvoid main() { o_color = vec4(1.0); }\n");
    write(
        "read.frag",
        fragment("uniform sampler2D u_depth; uniform sampler2DShadow u_shadow;",
                 "o_color = vec4(texture(u_depth, v_uv).r, texture(u_shadow, vec3(v_uv, 0.8)), 0.0, 1.0);"));
    const auto r = render(fullscreenLab(R"(
        {"name": "depth", "program": {"vertex": "half.vert", "fragment": "white.frag"},
         "draw": {"primitive": "triangle_strip", "count": 4}, "target": {"depth": "texture"}, "state": {"cull": "none"}},
        {"name": "read", "program": {"vertex": "fullscreen.vert", "fragment": "read.frag"}, "draw": "fullscreen",
         "inputs": {"u_depth": {"target": "depth.depth", "filter": "nearest"}, "u_shadow": "depth.depth"}})"));
    ASSERT_EQ(r.status, RenderStatus::Ok) << diagnostics(r);
    const grader::Image& img = image(r, "read");
    EXPECT_NEAR(img.at(1, 4, 0), 0.75f, 1e-4f);  // raw depth
    EXPECT_NEAR(img.at(6, 4, 0), 1.0f, 1e-4f);
    EXPECT_NEAR(img.at(1, 4, 1), 0.0f, 1e-4f);  // 0.8 <= 0.75 fails
    EXPECT_NEAR(img.at(6, 4, 1), 1.0f, 1e-4f);  // 0.8 <= 1 holds
}

TEST_F(LabFeatures, GeneratedTexturesAreDeterministic) {
    write("gen.frag",
          fragment("uniform sampler2D u_checker; uniform sampler2D u_noise;",
                   "o_color = vec4(texture(u_checker, v_uv).r, texture(u_noise, v_uv).rg, 1.0);"));
    const std::string lab =
        fullscreenLab(R"({"name": "gen", "program": {"vertex": "fullscreen.vert", "fragment": "gen.frag"},
        "draw": "fullscreen", "inputs": {
          "u_checker": {"generate": {"pattern": "checker", "size": [8, 8], "cells": 2}, "filter": "nearest"},
          "u_noise": {"generate": {"pattern": "noise", "size": [8, 8], "seed": 7}, "filter": "nearest"}}})");
    const auto a = render(lab);
    const auto b = render(lab);
    ASSERT_EQ(a.status, RenderStatus::Ok) << diagnostics(a);
    const grader::Image& img = image(a, "gen");
    EXPECT_EQ(img.pixels, image(b, "gen").pixels);
    // 2x2 cells of 4x4 texels: black at the bottom left (GL row 0), white beside it.
    EXPECT_NEAR(img.at(0, 7, 0), 0.0f, 1e-6f);
    EXPECT_NEAR(img.at(5, 7, 0), 1.0f, 1e-6f);
    EXPECT_NEAR(img.at(5, 0, 0), 0.0f, 1e-6f);
    float lo = 1.0f, hi = 0.0f;
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
            lo = std::min(lo, img.at(x, y, 1));
            hi = std::max(hi, img.at(x, y, 1));
        }
    EXPECT_GE(lo, 0.0f);
    EXPECT_LT(hi, 1.0f);
    EXPECT_GT(hi - lo, 0.5f);  // noise, not a constant
}

// "srgb": true decodes the file's values to linear when sampling (IEC 61966-2-1).
TEST_F(LabFeatures, SrgbTextureIsDecodedWhenSampled) {
    png("half.png", grader::Image(2, 2, 3, 128.0f / 255.0f));
    write("read.frag",
          fragment("uniform sampler2D u_plain; uniform sampler2D u_srgb;",
                   "o_color = vec4(texture(u_plain, v_uv).r, texture(u_srgb, v_uv).r, 0.0, 1.0);"));
    const auto r = render(
        fullscreenLab(R"({"name": "read", "program": {"vertex": "fullscreen.vert", "fragment": "read.frag"},
        "draw": "fullscreen", "inputs": {"u_plain": {"texture": "half.png"}, "u_srgb": {"texture": "half.png", "srgb": true}}})",
                      2, 2));
    ASSERT_EQ(r.status, RenderStatus::Ok) << diagnostics(r);
    const float encoded = 128.0f / 255.0f;
    const float linear = std::pow((encoded + 0.055f) / 1.055f, 2.4f);  // about 0.216
    EXPECT_NEAR(image(r, "read").at(0, 0, 0), encoded, 1e-4f);
    EXPECT_NEAR(image(r, "read").at(0, 0, 1), linear, 2e-3f);
}

TEST_F(LabFeatures, SamplerTypeTheLabCannotFeedIsALinkError) {
    write("bad.frag",
          fragment("uniform samplerCube u_image;", "o_color = texture(u_image, vec3(v_uv, 1.0));"));
    png("flat.png", grader::Image(2, 2, 3, 0.5f));
    const auto r = render(
        fullscreenLab(R"({"name": "bad", "program": {"vertex": "fullscreen.vert", "fragment": "bad.frag"},
        "draw": "fullscreen", "inputs": {"u_image": {"texture": "flat.png"}}})"));
    EXPECT_EQ(r.status, RenderStatus::LinkError);
    EXPECT_NE(r.message.find("passes[0].inputs.u_image"), std::string::npos) << r.message;
    EXPECT_NE(r.message.find("samplerCube"), std::string::npos) << r.message;
}

// ---------------------------------------------------------------------------------------------
// Targets

TEST_F(LabFeatures, TargetFormatsClampOrKeepValues) {
    write("hdr.frag", fragment("", "o_color = vec4(2.0, -1.0, 0.5, 1.0);"));
    const std::string pass =
        R"({"name": "NAME", "program": {"vertex": "fullscreen.vert", "fragment": "hdr.frag"},
        "draw": "fullscreen", "target": {"format": "FORMAT"}, "graded": true})";
    auto make = [&](const std::string& name, const std::string& format) {
        std::string p = pass;
        p.replace(p.find("NAME"), 4, name);
        p.replace(p.find("FORMAT"), 6, format);
        return p;
    };
    const auto r = render(fullscreenLab(make("a", "rgba8") + "," + make("b", "rgba16f") + "," +
                                        make("c", "rgba32f") + "," + make("d", "srgb8")));
    ASSERT_EQ(r.status, RenderStatus::Ok) << diagnostics(r);
    EXPECT_NEAR(image(r, "a").at(2, 2, 0), 1.0f, 1e-6f);
    EXPECT_NEAR(image(r, "a").at(2, 2, 1), 0.0f, 1e-6f);
    EXPECT_NEAR(image(r, "b").at(2, 2, 0), 2.0f, 1e-3f);
    EXPECT_NEAR(image(r, "b").at(2, 2, 1), -1.0f, 1e-3f);
    EXPECT_FLOAT_EQ(image(r, "c").at(2, 2, 0), 2.0f);
    // srgb8 stores the sRGB encoding of linear 0.5 (IEC 61966-2-1): 1.055 * 0.5^(1/2.4) - 0.055.
    EXPECT_NEAR(image(r, "d").at(2, 2, 2), 1.055f * std::pow(0.5f, 1.0f / 2.4f) - 0.055f, 3.0f / 255.0f);
}

TEST_F(LabFeatures, AttachmentsAreWrittenByTheirOutputsAndReadByName) {
    write("mrt.frag",
          "#version 330 core\nout vec4 o_albedo;\nout vec4 o_normal;\n"
          "void main() { o_albedo = vec4(1, 0, 0, 1); o_normal = vec4(0, 1, 0, 1); }\n");
    write("read.frag", fragment("uniform sampler2D u_n;", "o_color = texture(u_n, v_uv);"));
    const auto r =
        render(fullscreenLab(R"(
        {"name": "gbuffer", "program": {"vertex": "fullscreen.vert", "fragment": "mrt.frag"}, "draw": "fullscreen",
         "target": "g", "graded": true},
        {"name": "read", "program": {"vertex": "fullscreen.vert", "fragment": "read.frag"}, "draw": "fullscreen",
         "inputs": {"u_n": "g.normal"}})",
                             8, 8, R"(, "targets": {"g": {"attachments": ["albedo", "normal"]}})"));
    ASSERT_EQ(r.status, RenderStatus::Ok) << diagnostics(r);
    EXPECT_FLOAT_EQ(image(r, "gbuffer", "albedo").at(3, 3, 0), 1.0f);
    EXPECT_FLOAT_EQ(image(r, "gbuffer", "normal").at(3, 3, 1), 1.0f);
    EXPECT_FLOAT_EQ(image(r, "gbuffer", "normal").at(3, 3, 0), 0.0f);
    EXPECT_FLOAT_EQ(image(r, "read").at(3, 3, 1), 1.0f);
    EXPECT_EQ(r.diagnostics.size(), 0u) << diagnostics(r);
}

TEST_F(LabFeatures, ScaledTargetsAreFractionsOfTheLabResolution) {
    write("one.frag", fragment("", "o_color = vec4(1.0);"));
    const auto r = render(fullscreenLab(R"(
        {"name": "half", "program": {"vertex": "fullscreen.vert", "fragment": "one.frag"}, "draw": "fullscreen",
         "target": {"scale": 0.5}, "graded": true},
        {"name": "quarter", "program": {"vertex": "fullscreen.vert", "fragment": "one.frag"}, "draw": "fullscreen",
         "target": {"scale": 0.25}})",
                                        16, 8));
    ASSERT_EQ(r.status, RenderStatus::Ok) << diagnostics(r);
    EXPECT_EQ(image(r, "half").width, 8);
    EXPECT_EQ(image(r, "half").height, 4);
    EXPECT_EQ(image(r, "quarter").width, 4);
    EXPECT_EQ(image(r, "quarter").height, 2);
}

TEST_F(LabFeatures, CubeTargetIsDrawnFaceByFaceAndSampled) {
    write("face.frag", fragment("uniform int u_cube_face;", "o_color = vec4(float(u_cube_face + 1) / 8.0);"));
    write("look.frag",
          fragment("uniform samplerCube u_env;", "o_color = texture(u_env, vec3(0.0, -1.0, 0.0));"));
    const auto r = render(fullscreenLab(R"(
        {"name": "faces", "program": {"vertex": "fullscreen.vert", "fragment": "face.frag"}, "draw": "fullscreen",
         "target": {"type": "cube", "size": [4, 4], "depth": "none"}, "graded": true},
        {"name": "look", "program": {"vertex": "fullscreen.vert", "fragment": "look.frag"}, "draw": "fullscreen",
         "inputs": {"u_env": "faces"}})"));
    ASSERT_EQ(r.status, RenderStatus::Ok) << diagnostics(r);
    const grader::Image& strip = image(r, "faces");
    ASSERT_EQ(strip.width, 24);
    ASSERT_EQ(strip.height, 4);
    for (int f = 0; f < 6; ++f)
        EXPECT_FLOAT_EQ(strip.at(f * 4 + 1, 1, 0), float(f + 1) / 8.0f) << "face " << f;
    EXPECT_FLOAT_EQ(image(r, "look").at(4, 4, 0), 4.0f / 8.0f);  // -y is face 3
}

// ---------------------------------------------------------------------------------------------
// Pass state

// Regression: fullscreen passes wrote depth 0.5 and hid a scene drawn after them.
TEST_F(LabFeatures, FullscreenBackgroundDoesNotHideALaterSceneDraw) {
    write("sky.frag", fragment("", "o_color = vec4(0.0, 0.0, 1.0, 1.0);"));
    write("red.frag", "#version 330 core\nout vec4 o_color;\nvoid main() { o_color = vec4(1, 0, 0, 1); }\n");
    const auto r = render(R"("resolution": [32, 32], "passes": [
        {"name": "sky", "program": {"vertex": "fullscreen.vert", "fragment": "sky.frag"}, "draw": "fullscreen"},
        {"name": "ball", "program": {"vertex": "scene.vert", "fragment": "red.frag"}, "target": "sky",
         "camera": {"position": [0, 0, 3], "target": [0, 0, 0]}}],
        "scenes": [{"name": "s", "file": "scenes/sphere.gltf"}])");
    ASSERT_EQ(r.status, RenderStatus::Ok) << diagnostics(r);
    const shaderlab::PassImage& ball = r.scenes[0].passes.back();
    EXPECT_FLOAT_EQ(ball.color.at(16, 16, 0), 1.0f);  // the sphere in front of the sky
    EXPECT_FLOAT_EQ(ball.color.at(0, 0, 2), 1.0f);    // the sky around it
    // A fullscreen pass drew into the target: every pixel is graded (no depth-based mask).
    EXPECT_EQ(std::count(ball.coverage.begin(), ball.coverage.end(), 1), 32 * 32);
}

TEST_F(LabFeatures, DepthBufferOnlyWhereAPassUsesDepth) {
    // Both targets default to "depth": "buffer". Only the scene pass tests and writes depth, so
    // only its target gets one: with every pass kept, it alone has a depth image.
    write("grey.frag", fragment("", "o_color = vec4(0.5);"));
    write("red.frag", "#version 330 core\nout vec4 o_color;\nvoid main() { o_color = vec4(1, 0, 0, 1); }\n");
    const auto r = render(R"("resolution": [16, 16], "passes": [
        {"name": "ball", "program": {"vertex": "scene.vert", "fragment": "red.frag"},
         "camera": {"position": [0, 0, 3], "target": [0, 0, 0]}},
        {"name": "post", "program": {"vertex": "fullscreen.vert", "fragment": "grey.frag"}, "draw": "fullscreen"}],
        "scenes": [{"name": "s", "file": "scenes/sphere.gltf"}])",
                          /*all_passes=*/true);
    ASSERT_EQ(r.status, RenderStatus::Ok) << diagnostics(r);
    std::vector<std::string> depth_images;
    for (const shaderlab::PassImage& p : r.scenes[0].passes)
        if (p.attachment == "depth") depth_images.push_back(p.pass);
    EXPECT_EQ(depth_images, std::vector<std::string>{"ball"});
    // The scene pass's depth buffer still masks what it covers.
    const shaderlab::PassImage& ball = r.scenes[0].passes.front();
    const auto covered = std::count(ball.coverage.begin(), ball.coverage.end(), 1);
    EXPECT_GT(covered, 0);
    EXPECT_LT(covered, 16 * 16);
}

TEST_F(LabFeatures, PassNoGradedImageDependsOnIsNotRun) {
    // "spin" draws into a target nobody reads and is not graded; its shader loops past the loop
    // guard's limit, so running it fails the lab. Grading skips it; keeping every pass (render
    // --all-passes, the viewer) runs it. "base" feeds the graded pass and always runs.
    write("grey.frag", fragment("", "o_color = vec4(0.5);"));
    write("copy.frag", fragment("uniform sampler2D u_base;", "o_color = texture(u_base, v_uv);"));
    write("spin.frag", fragment("",
                                "float a = 0.0;\nfor (int i = 0; i < 100000000; ++i) a += sin(float(i));\n"
                                "o_color = vec4(a);"));
    const std::string lab = fullscreenLab(R"(
        {"name": "base", "program": {"vertex": "fullscreen.vert", "fragment": "grey.frag"}, "draw": "fullscreen"},
        {"name": "spin", "program": {"vertex": "fullscreen.vert", "fragment": "spin.frag"}, "draw": "fullscreen"},
        {"name": "show", "program": {"vertex": "fullscreen.vert", "fragment": "copy.frag"}, "draw": "fullscreen",
         "inputs": {"u_base": "base"}})");
    const auto graded = render(lab);
    ASSERT_EQ(graded.status, RenderStatus::Ok) << diagnostics(graded);
    EXPECT_NEAR(image(graded, "show").at(3, 3, 0), 0.5f, 1e-6f);
    const auto every_pass = render(lab, /*all_passes=*/true);
    EXPECT_NE(every_pass.status, RenderStatus::Ok)
        << "the spinning pass ran and should have hit the loop guard";
}

// The loop guard's error sits at the loop that ran past its limit, in the file that holds it
// (an included one too), with the caret under its keyword; a finite loop before it is not blamed.
TEST_F(LabFeatures, TheLoopGuardNamesTheLoopThatRanPastItsLimit) {
    const std::string spin =
        "#version 330 core\n"
        "in vec2 v_uv;\n"
        "out vec4 o_color;\n"
        "void main() {\n"
        "    float a = 0.0;\n"
        "    for (int i = 0; i < 4; ++i) a += 0.1;\n"
        "    a += v_uv.x; while (a >= 0.0) a += 1.0;\n"
        "    o_color = vec4(a);\n"
        "}\n";
    write("spin.frag", spin);
    const std::string pass =
        R"({"name": "spin", "program": {"vertex": "fullscreen.vert", "fragment": "spin.frag"}, "draw": "fullscreen"})";
    const auto r = render(fullscreenLab(pass));
    ASSERT_TRUE(r.endless_loop) << diagnostics(r);
    const auto loop =
        std::find_if(r.diagnostics.begin(), r.diagnostics.end(),
                     [](const shaderlab::Diagnostic& d) { return d.message.rfind("endless loop", 0) == 0; });
    ASSERT_NE(loop, r.diagnostics.end()) << diagnostics(r);
    EXPECT_EQ(loop->file, "spin.frag");
    EXPECT_EQ(loop->line, 7);
    EXPECT_EQ(loop->source_line, "    a += v_uv.x; while (a >= 0.0) a += 1.0;");
    EXPECT_EQ(loop->column, static_cast<int>(loop->source_line.find("while")) + 1);
    EXPECT_NE(loop->message.find("the loop at line 7 ran more than"), std::string::npos) << loop->message;

    // In an included file: that file and its own line.
    write("spin_lib.glsl", "float spin(float a) {\n    while (a >= 0.0) a += 1.0;\n    return a;\n}\n");
    write("spin.frag",
          "#version 330 core\n#include \"spin_lib.glsl\"\nin vec2 v_uv;\nout vec4 o_color;\n"
          "void main() { o_color = vec4(spin(v_uv.x)); }\n");
    const auto included = render(fullscreenLab(pass));
    ASSERT_TRUE(included.endless_loop) << diagnostics(included);
    const auto in_lib =
        std::find_if(included.diagnostics.begin(), included.diagnostics.end(),
                     [](const shaderlab::Diagnostic& d) { return d.message.rfind("endless loop", 0) == 0; });
    ASSERT_NE(in_lib, included.diagnostics.end()) << diagnostics(included);
    EXPECT_EQ(in_lib->file, "spin_lib.glsl");
    EXPECT_EQ(in_lib->line, 2);
    EXPECT_EQ(in_lib->source_line, "    while (a >= 0.0) a += 1.0;");
    EXPECT_EQ(in_lib->column, 5);
}

TEST_F(LabFeatures, BlendingCullingAndClearsPerAttachment) {
    write("quarter.frag", fragment("", "o_color = vec4(0.25);"));
    write("facing.frag",
          "#version 330 core\nout vec4 o_color;\n"
          "void main() { o_color = vec4(gl_FrontFacing ? 1.0 : 0.0, 0.0, 0.0, 1.0); }\n");
    write("two.frag", "#version 330 core\nout vec4 o_a;\nout vec4 o_b;\nvoid main() { discard; }\n");
    const auto r = render(R"("resolution": [16, 16], "passes": [
        {"name": "add1", "program": {"vertex": "fullscreen.vert", "fragment": "quarter.frag"}, "draw": "fullscreen",
         "target": {"depth": "none"}, "state": {"clear_color": [0, 0, 0, 0]}},
        {"name": "add2", "program": {"vertex": "fullscreen.vert", "fragment": "quarter.frag"}, "draw": "fullscreen",
         "target": "add1", "state": {"blend": "additive"}, "graded": true},
        {"name": "back", "program": {"vertex": "scene.vert", "fragment": "facing.frag"}, "state": {"cull": "front"},
         "camera": {"position": [0, 0, 3], "target": [0, 0, 0]}, "graded": true},
        {"name": "front", "program": {"vertex": "scene.vert", "fragment": "facing.frag"},
         "camera": {"position": [0, 0, 3], "target": [0, 0, 0]}, "graded": true},
        {"name": "clears", "program": {"vertex": "fullscreen.vert", "fragment": "two.frag"}, "draw": "fullscreen",
         "target": {"attachments": ["a", "b"]}, "state": {"clear_color": {"a": [0.5, 0, 0, 1], "b": [0, 0.75, 0, 1]}}}],
        "scenes": [{"name": "s", "file": "scenes/sphere.gltf"}])");
    ASSERT_EQ(r.status, RenderStatus::Ok) << diagnostics(r);
    EXPECT_NEAR(image(r, "add2").at(3, 3, 0), 0.5f, 1e-6f);
    EXPECT_FLOAT_EQ(image(r, "back").at(8, 8, 0), 0.0f);  // front faces culled: the inside shows
    EXPECT_FLOAT_EQ(image(r, "front").at(8, 8, 0), 1.0f);
    EXPECT_FLOAT_EQ(image(r, "clears", "a").at(3, 3, 0), 0.5f);
    EXPECT_FLOAT_EQ(image(r, "clears", "b").at(3, 3, 1), 0.75f);
}

TEST_F(LabFeatures, WideLinesCoverMoreThanThinOnes) {
    write("white.frag", "#version 330 core\nout vec4 o_color;\nvoid main() { o_color = vec4(1.0); }\n");
    const std::string pass =
        R"({"name": "NAME", "program": {"vertex": "scene.vert", "fragment": "white.frag"},
        "camera": {"position": [0, 0, 3], "target": [0, 0, 0]}, "state": {"polygon_mode": "MODE", "line_width": WIDTH}, "graded": true})";
    auto make = [&](const char* name, const char* mode, const char* width) {
        std::string p = pass;
        p.replace(p.find("NAME"), 4, name);
        p.replace(p.find("MODE"), 4, mode);
        p.replace(p.find("WIDTH"), 5, width);
        return p;
    };
    const auto r = render("\"resolution\": [64, 64], \"passes\": [" + make("fill", "fill", "1") + "," +
                          make("thin", "line", "1") + "," + make("wide", "line", "4") +
                          "], \"scenes\": [{\"name\": \"s\", \"file\": \"scenes/sphere.gltf\"}]");
    ASSERT_EQ(r.status, RenderStatus::Ok) << diagnostics(r);
    auto lit = [](const grader::Image& img) {
        int n = 0;
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x) n += img.at(x, y, 0) > 0.5f;
        return n;
    };
    EXPECT_LT(lit(image(r, "thin")), lit(image(r, "wide")));
    EXPECT_LT(lit(image(r, "thin")), lit(image(r, "fill")));
}

// ---------------------------------------------------------------------------------------------
// Repeats

TEST_F(LabFeatures, RepeatedPassReadsItsOwnPreviousResult) {
    write("zero.frag", fragment("", "o_color = vec4(0.0);"));
    write("inc.frag", fragment("uniform sampler2D u_prev; uniform int u_iteration;",
                               "o_color = texture(u_prev, v_uv) + vec4(1.0, 0.0, 0.0, 0.0);\n"
                               "o_color.g = float(u_iteration);"));
    const std::string lab = fullscreenLab(R"(
        {"name": "init", "program": {"vertex": "fullscreen.vert", "fragment": "zero.frag"}, "draw": "fullscreen",
         "target": "acc"},
        {"name": "step", "program": {"vertex": "fullscreen.vert", "fragment": "inc.frag"}, "draw": "fullscreen",
         "target": "acc", "inputs": {"u_prev": "acc"}, "repeat": 10})",
                                          2, 2, R"(, "targets": {"acc": {"depth": "none"}})");
    auto r = render(lab);
    ASSERT_EQ(r.status, RenderStatus::Ok) << diagnostics(r);
    EXPECT_FLOAT_EQ(image(r, "step").at(0, 0, 0), 10.0f);
    EXPECT_FLOAT_EQ(image(r, "step").at(0, 0, 1), 9.0f);  // u_iteration of the last run

    std::string per_scene = lab;
    per_scene.replace(per_scene.find("{\"name\": \"s\"}"), 13, R"({"name": "s", "repeats": {"step": 3}})");
    r = render(per_scene);
    ASSERT_EQ(r.status, RenderStatus::Ok) << diagnostics(r);
    EXPECT_FLOAT_EQ(image(r, "step").at(0, 0, 0), 3.0f);
}

// An effect applied in place: a pass reads the target it draws into, which an earlier pass drew.
TEST_F(LabFeatures, PassReadsTheTargetItDrawsIntoAfterAnEarlierPass) {
    write("quarter.frag", fragment("", "o_color = vec4(0.25);"));
    write("twice.frag", fragment("uniform sampler2D u_in;", "o_color = texture(u_in, v_uv) * 2.0;"));
    const auto r = render(fullscreenLab(R"(
        {"name": "first", "program": {"vertex": "fullscreen.vert", "fragment": "quarter.frag"}, "draw": "fullscreen",
         "target": {"depth": "none"}},
        {"name": "again", "program": {"vertex": "fullscreen.vert", "fragment": "twice.frag"}, "draw": "fullscreen",
         "target": "first", "inputs": {"u_in": "first"}})",
                                        2, 2));
    ASSERT_EQ(r.status, RenderStatus::Ok) << diagnostics(r);
    EXPECT_FLOAT_EQ(image(r, "again").at(0, 0, 0), 0.5f);
}

TEST_F(LabFeatures, RepeatGroupFeedsItsResultBackIntoTheNextIteration) {
    write("plus.frag", fragment("uniform sampler2D u_in;", "o_color = texture(u_in, v_uv) + vec4(1.0);"));
    write("twice.frag", fragment("uniform sampler2D u_in;", "o_color = texture(u_in, v_uv) * 2.0;"));
    const auto r = render(fullscreenLab(R"(
        {"name": "a", "program": {"vertex": "fullscreen.vert", "fragment": "plus.frag"}, "draw": "fullscreen",
         "target": {"depth": "none"}, "inputs": {"u_in": "b"}, "state": {"clear_color": [0, 0, 0, 0]}},
        {"name": "b", "program": {"vertex": "fullscreen.vert", "fragment": "twice.frag"}, "draw": "fullscreen",
         "target": {"depth": "none"}, "inputs": {"u_in": "a"}, "repeat": {"count": 3, "from": "a"}})",
                                        2, 2));
    ASSERT_EQ(r.status, RenderStatus::Ok) << diagnostics(r);
    // b starts at 0: a = 1, b = 2; a = 3, b = 6; a = 7, b = 14.
    EXPECT_FLOAT_EQ(image(r, "b").at(0, 0, 0), 14.0f);
}

TEST_F(LabFeatures, TimesGradeOneSceneAtSeveralFixedTimes) {
    write("time.frag", fragment("uniform float u_time;", "o_color = vec4(u_time);"));
    const auto r = render(R"("resolution": [2, 2], "passes": [{"name": "t", "program":
        {"vertex": "fullscreen.vert", "fragment": "time.frag"}, "draw": "fullscreen"}],
        "scenes": [{"name": "anim", "times": [0.25, 0.5]}])");
    ASSERT_EQ(r.status, RenderStatus::Ok) << diagnostics(r);
    ASSERT_EQ(r.scenes.size(), 2u);
    EXPECT_EQ(r.scenes[0].scene, "anim_t0");
    EXPECT_FLOAT_EQ(r.scenes[0].passes[0].color.at(0, 0, 0), 0.25f);
    EXPECT_FLOAT_EQ(r.scenes[1].passes[0].color.at(0, 0, 0), 0.5f);
}

// ---------------------------------------------------------------------------------------------
// Draws without a mesh, cameras

TEST_F(LabFeatures, PointsDrivenByVertexIdWithProgramPointSize) {
    // Four points at the centres of four pixels of a 16x16 target, each gl_PointSize wide.
    write("points.vert", R"(#version 330 core
        uniform float u_size;
        void main() {
            vec2 pixel = vec2(2.0 + 4.0 * float(gl_VertexID), 8.0);
            gl_Position = vec4((pixel + 0.5) / 16.0 * 2.0 - 1.0, 0.0, 1.0);
            gl_PointSize = u_size;
        })");
    write("white.frag", "#version 330 core\nout vec4 o_color;\nvoid main() { o_color = vec4(1.0); }\n");
    const std::string pass =
        R"({"name": "NAME", "program": {"vertex": "points.vert", "fragment": "white.frag"},
        "draw": {"primitive": "points", "count": 4}, "uniforms": {"u_size": SIZE}, "graded": true})";
    auto make = [&](const char* name, const char* size) {
        std::string p = pass;
        p.replace(p.find("NAME"), 4, name);
        p.replace(p.find("SIZE"), 4, size);
        return p;
    };
    const auto r = render(fullscreenLab(make("one", "1") + "," + make("three", "3"), 16, 16));
    ASSERT_EQ(r.status, RenderStatus::Ok) << diagnostics(r);
    auto lit = [](const grader::Image& img) {
        int n = 0;
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x) n += img.at(x, y, 0) > 0.5f;
        return n;
    };
    EXPECT_EQ(lit(image(r, "one")), 4);
    EXPECT_EQ(lit(image(r, "three")), 4 * 9);
}

// Regression: a partial override (a new position) kept the automatic near and far planes, which
// clipped the whole scene away.
TEST_F(LabFeatures, MovedCameraRefitsNearAndFar) {
    write("white.frag", "#version 330 core\nout vec4 o_color;\nvoid main() { o_color = vec4(1.0); }\n");
    const auto r = render(R"("resolution": [32, 32], "passes": [{"name": "p", "program":
        {"vertex": "scene.vert", "fragment": "white.frag"}}],
        "scenes": [{"name": "far", "file": "scenes/sphere.gltf", "camera": {"position": [0, 0, 40], "fov_y_deg": 8}}])");
    ASSERT_EQ(r.status, RenderStatus::Ok) << diagnostics(r);
    EXPECT_FLOAT_EQ(r.scenes[0].passes[0].color.at(16, 16, 0), 1.0f);
}

TEST_F(LabFeatures, PassCameraLooksFromALightAndIsReusableAsAMatrix) {
    write("depth.frag",
          "#version 330 core\nout vec4 o_color;\nvoid main() { o_color = vec4(gl_FragCoord.z); }\n");
    // The lit pass projects the sphere's centre with the shadow pass's matrix: the centre of the
    // light's view, (0.5, 0.5) in texture space.
    write("project.frag", fragment("uniform mat4 u_light_matrix;",
                                   "vec4 p = u_light_matrix * vec4(0.0, 0.0, 0.0, 1.0);\n"
                                   "o_color = vec4(p.xy / p.w * 0.5 + 0.5, 0.0, 1.0);"));
    const auto r = render(R"("resolution": [32, 32], "passes": [
        {"name": "shadow", "program": {"vertex": "scene.vert", "fragment": "depth.frag"},
         "camera": {"light": 0}, "target": {"depth": "texture"}, "graded": true},
        {"name": "lit", "program": {"vertex": "fullscreen.vert", "fragment": "project.frag"}, "draw": "fullscreen",
         "uniforms": {"u_light_matrix": "@shadow.view_projection"}}],
        "scenes": [{"name": "s", "file": "scenes/sphere.gltf",
                    "lights": [{"type": "directional", "direction": [1, -1, 0]}]}])");
    ASSERT_EQ(r.status, RenderStatus::Ok) << diagnostics(r);
    const grader::Image& shadow = image(r, "shadow");
    // An orthographic view holding the bounding sphere: the sphere covers the middle, depths in (0, 1).
    EXPECT_GT(shadow.at(16, 16, 0), 0.0f);
    EXPECT_LT(shadow.at(16, 16, 0), 1.0f);
    EXPECT_NEAR(image(r, "lit").at(3, 3, 0), 0.5f, 1e-4f);
    EXPECT_NEAR(image(r, "lit").at(3, 3, 1), 0.5f, 1e-4f);
}

// ---------------------------------------------------------------------------------------------
// Uniforms

TEST_F(LabFeatures, UniformsTakeTheTypeTheProgramDeclares) {
    write("u.frag", fragment(R"(
        struct Light { vec3 color; float k; };
        uniform int u_levels;
        uniform bool u_on;
        uniform ivec2 u_cells;
        uniform float u_weights[3];
        uniform Light u_lights[2];
        uniform mat2 u_m;)",
                             R"(o_color = vec4(float(u_levels) + (u_on ? 0.5 : 0.0),
                       float(u_cells.x * 10 + u_cells.y) + u_weights[2],
                       u_lights[1].color.g * u_lights[1].k,
                       u_m[1][0]);)"));
    const auto r =
        render(fullscreenLab(R"({"name": "u", "program": {"vertex": "fullscreen.vert", "fragment": "u.frag"},
        "draw": "fullscreen", "uniforms": {"u_levels": 3, "u_on": true, "u_cells": [4, 2], "u_weights": [0.1, 0.2, 0.25],
        "u_lights": [{"color": [1, 1, 1], "k": 1}, {"color": [0, 0.5, 0], "k": 3}], "u_m": [[1, 0], [7, 1]]}})",
                             2, 2));
    ASSERT_EQ(r.status, RenderStatus::Ok) << diagnostics(r);
    const grader::Image& img = image(r, "u");
    EXPECT_FLOAT_EQ(img.at(0, 0, 0), 3.5f);
    EXPECT_FLOAT_EQ(img.at(0, 0, 1), 42.25f);
    EXPECT_FLOAT_EQ(img.at(0, 0, 2), 1.5f);
    EXPECT_FLOAT_EQ(img.at(0, 0, 3), 7.0f);
}

// Regression: "u_mode": 1.5 for an int uniform stayed 0 with only a warning.
TEST_F(LabFeatures, ValueThatDoesNotFitTheDeclarationIsAnErrorNamingTheKey) {
    write("u.frag", fragment("uniform int u_mode;", "o_color = vec4(float(u_mode));"));
    const auto r =
        render(fullscreenLab(R"({"name": "u", "program": {"vertex": "fullscreen.vert", "fragment": "u.frag"},
        "draw": "fullscreen", "uniforms": {"u_mode": 1.5}})"));
    EXPECT_EQ(r.status, RenderStatus::LinkError);
    EXPECT_NE(r.message.find("passes[0].uniforms.u_mode"), std::string::npos) << r.message;
    EXPECT_NE(r.message.find("int u_mode"), std::string::npos) << r.message;
}

// Regression: a uniform set by one pass leaked into the next pass sharing the program, and a
// texture bound for one pass was still bound for the next.
TEST_F(LabFeatures, UniformsAndTexturesDoNotLeakBetweenPassesSharingAProgram) {
    write("gain.frag", fragment("uniform float u_gain = 0.25; uniform sampler2D u_tex;",
                                "o_color = vec4(u_gain, texture(u_tex, v_uv).r, 0.0, 1.0);"));
    const auto r = render(fullscreenLab(R"(
        {"name": "first", "program": {"vertex": "fullscreen.vert", "fragment": "gain.frag"}, "draw": "fullscreen",
         "uniforms": {"u_gain": 1.0}, "inputs": {"u_tex": {"generate": {"pattern": "constant", "size": [1, 1]}}},
         "graded": true},
        {"name": "second", "program": {"vertex": "fullscreen.vert", "fragment": "gain.frag"}, "draw": "fullscreen"})"));
    ASSERT_EQ(r.status, RenderStatus::Ok) << diagnostics(r);
    EXPECT_FLOAT_EQ(image(r, "first").at(1, 1, 0), 1.0f);
    EXPECT_FLOAT_EQ(image(r, "first").at(1, 1, 1), 1.0f);
    EXPECT_FLOAT_EQ(image(r, "second").at(1, 1, 0), 0.25f);  // the GLSL initialiser, not 1.0
    EXPECT_FLOAT_EQ(image(r, "second").at(1, 1, 1), 0.0f);   // no texture fed: black
}

TEST_F(LabFeatures, UniformTheShadersNeverMentionGetsAWarningWithASuggestion) {
    write("u.frag", fragment("uniform float u_shinyness;", "o_color = vec4(u_shinyness);"));
    const auto r =
        render(fullscreenLab(R"({"name": "u", "program": {"vertex": "fullscreen.vert", "fragment": "u.frag"},
        "draw": "fullscreen", "uniforms": {"u_shininess": 8}})"));
    ASSERT_EQ(r.status, RenderStatus::Ok) << diagnostics(r);
    bool warned = false;
    for (const shaderlab::Diagnostic& d : r.diagnostics)
        warned = warned || (d.severity == "warning" && d.message.find("u_shininess") != std::string::npos &&
                            d.message.find("u_shinyness") != std::string::npos);
    EXPECT_TRUE(warned) << diagnostics(r);
}

// A scene's uniform goes to every pass: a pass whose program does not use it is not warned
// about, as long as some program of the lab mentions it; one that no program mentions is.
TEST_F(LabFeatures, SceneUniformsWarnOnlyWhenNoShaderMentionsThem) {
    write("gain.frag", fragment("uniform float u_gain;", "o_color = vec4(u_gain);"));
    write("copy.frag", fragment("uniform sampler2D u_in;", "o_color = texture(u_in, v_uv);"));
    const auto r = render(R"("resolution": [2, 2], "passes": [
        {"name": "a", "program": {"vertex": "fullscreen.vert", "fragment": "gain.frag"}, "draw": "fullscreen"},
        {"name": "b", "program": {"vertex": "fullscreen.vert", "fragment": "copy.frag"}, "draw": "fullscreen",
         "inputs": {"u_in": "a"}}],
        "scenes": [{"name": "s", "uniforms": {"u_gain": 0.5, "u_gian": 1}}])");
    ASSERT_EQ(r.status, RenderStatus::Ok) << diagnostics(r);
    int about_gain = 0, about_gian = 0;
    for (const shaderlab::Diagnostic& d : r.diagnostics) {
        about_gain += d.message.find("sets u_gain ") != std::string::npos;
        about_gian += d.message.find("sets u_gian ") != std::string::npos;
    }
    EXPECT_EQ(about_gain, 0) << diagnostics(r);
    EXPECT_EQ(about_gian, 1) << diagnostics(r);
    EXPECT_FLOAT_EQ(image(r, "b").at(0, 0, 0), 0.5f);
}

// ---------------------------------------------------------------------------------------------
// Shader files

TEST_F(LabFeatures, IncludedFilesKeepTheirOwnLineNumbers) {
    write("common.glsl",
          "// helpers\nfloat half_of(float x) { return x * 0.5; }\nfloat broken() { return y; }\n");
    write("main.frag",
          "#version 330 core\n#include \"common.glsl\"\nout vec4 o_color;\nvoid main() { o_color = "
          "vec4(half_of(1.0)); }\n");
    const auto r = render(
        fullscreenLab(R"({"name": "m", "program": {"vertex": "fullscreen.vert", "fragment": "main.frag"},
        "draw": "fullscreen"})"));
    EXPECT_EQ(r.status, RenderStatus::CompileError);
    bool found = false;
    for (const shaderlab::Diagnostic& d : r.diagnostics)
        found = found || (d.file == "common.glsl" && d.line == 3);
    EXPECT_TRUE(found) << diagnostics(r);

    write("common.glsl", "float half_of(float x) { return x * 0.5; }\n");
    fs::create_directories(root_ / "labs" / "shared");
    std::ofstream(root_ / "labs" / "shared" / "quarter.glsl")
        << "float quarter_of(float x) { return x * 0.25; }\n";
    write("main.frag",
          "#version 330 core\n#include \"common.glsl\"\n#include \"shared/quarter.glsl\"\n"
          "#include \"common.glsl\"\nout vec4 o_color;\nvoid main() { o_color = "
          "vec4(half_of(quarter_of(1.0))); }\n");
    const auto ok = render(
        fullscreenLab(R"({"name": "m", "program": {"vertex": "fullscreen.vert", "fragment": "main.frag"},
        "draw": "fullscreen"})"));
    ASSERT_EQ(ok.status, RenderStatus::Ok) << diagnostics(ok);
    EXPECT_FLOAT_EQ(image(ok, "m").at(0, 0, 0), 0.125f);
}

// A file in two programs (here with two vertex stages) is compiled twice; its error is reported
// once, on the line that lacks the ';'.
TEST_F(LabFeatures, FileInTwoProgramsReportsItsErrorOnce) {
    write("other.vert", kFullscreenVert);
    write("bad.frag",
          "#version 330 core\nin vec2 v_uv;\nout vec4 o_color\nvoid main() { o_color = vec4(v_uv, 0.0, 1.0); "
          "}\n");
    const auto r = render(fullscreenLab(
        R"({"name": "a", "program": {"vertex": "fullscreen.vert", "fragment": "bad.frag"}, "draw": "fullscreen"},
        {"name": "b", "program": {"vertex": "other.vert", "fragment": "bad.frag"}, "draw": "fullscreen"})"));
    EXPECT_EQ(r.status, RenderStatus::CompileError);
    int errors = 0;
    for (const shaderlab::Diagnostic& d : r.diagnostics) {
        if (d.severity != "error") continue;
        ++errors;
        EXPECT_EQ(d.file, "bad.frag");
        EXPECT_EQ(d.line, 3);
    }
    EXPECT_EQ(errors, 1) << diagnostics(r);
}

// Regression: outputs that no attachment receives were lost without a word.
TEST_F(LabFeatures, OutputThatReachesNoAttachmentIsDiagnosed) {
    write("two.frag",
          "#version 330 core\nout vec4 o_color;\nlayout(location = 1) out vec4 o_glow;\n"
          "void main() { o_color = vec4(1.0); o_glow = vec4(1.0); }\n");
    const auto r = render(
        fullscreenLab(R"({"name": "m", "program": {"vertex": "fullscreen.vert", "fragment": "two.frag"},
        "draw": "fullscreen"})"));
    ASSERT_EQ(r.status, RenderStatus::Ok) << diagnostics(r);
    bool warned = false;
    for (const shaderlab::Diagnostic& d : r.diagnostics)
        warned = warned || (d.severity == "warning" && d.message.find("o_glow") != std::string::npos);
    EXPECT_TRUE(warned) << diagnostics(r);
}

}  // namespace
