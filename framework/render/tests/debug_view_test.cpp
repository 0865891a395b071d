// The debug view of vertex data (debug_view.h) against answers worked out by hand: the bundled
// sphere's normal at the centre of the picture faces the camera (and still does once the camera
// is turned), its texture coordinates grow along the axes its generator gives them, and the quads
// of tests/data/gltf/tangent_quads.gltf show the tangent, bitangent and handedness their file
// holds; a mesh without TANGENT is grey and named in a note, never given made-up tangents.
#include "shaderlab/render/debug_view.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "gl_test_support.h"
#include "shaderlab/lab/lab_spec.h"
#include "shaderlab/render/renderer.h"
#include "shaderlab/scene/camera.h"
#include "shaderlab/scene/gltf_loader.h"

namespace fs = std::filesystem;
using shaderlab::DebugView;

namespace {

constexpr int kSize = 64;
const fs::path kSource = SHADERLAB_SOURCE_DIR;

glm::vec3 pixel(const shaderlab::SceneRender& s, int x, int y) {
    const grader::Image& img = s.passes.at(0).color;
    return {img.at(x, y, 0), img.at(x, y, 1), img.at(x, y, 2)};
}

bool covered(const shaderlab::SceneRender& s, int x, int y) {
    return s.passes.at(0).coverage.at(static_cast<std::size_t>(y * kSize + x)) != 0;
}

glm::vec3 encoded(const glm::vec3& direction) { return glm::normalize(direction) * 0.5f + 0.5f; }

void expectNear(const glm::vec3& got, const glm::vec3& want, float tolerance, const std::string& what) {
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(got[c], want[c], tolerance)
            << what << ": got (" << got.x << ", " << got.y << ", " << got.z << "), want (" << want.x << ", "
            << want.y << ", " << want.z << ")";
}

// A lab of its own in a scratch folder: the scenes named, copied beside it, 64 x 64 pixels.
class DebugViewRender : public ::testing::Test {
  protected:
    void SetUp() override {
        std::string err;
        if (!shaderlab::testing::sharedContext(shaderlab::Backend::OSMesa, &err)) FAIL() << err;
        root_ = fs::temp_directory_path() / ("shaderlab_debug_view_" + std::to_string(::getpid()) + "_" +
                                             ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(root_);
        lab_ = root_ / "labs" / "70-debug";
        fs::create_directories(lab_);
        fs::create_directories(root_ / "labs" / "scenes");
        for (const char* f : {"sphere.gltf", "sphere.bin", "cube_no_normals.gltf", "cube_no_normals.bin"})
            fs::copy_file(kSource / "labs" / "scenes" / f, root_ / "labs" / "scenes" / f);
        fs::copy_file(fs::path(SHADERLAB_TEST_DATA) / "gltf" / "tangent_quads.gltf",
                      root_ / "labs" / "scenes" / "tangent_quads.gltf");
        // The lab's own program is never compiled by the debug view; it only has to exist.
        std::ofstream(lab_ / "scene.vert") << "#version 330 core\nvoid main() {}\n";
        std::ofstream(lab_ / "scene.frag") << "#version 330 core\nout vec4 o_color;\nvoid main() {}\n";
        std::ofstream(lab_ / "lab.json")
            << R"({"schema": 2, "id": "70-debug", "resolution": [64, 64], "passes": [{"name": "draw",
              "program": {"vertex": "scene.vert", "fragment": "scene.frag"}, "graded": true}],
              "scenes": [{"name": "sphere", "file": "scenes/sphere.gltf"},
                         {"name": "quads", "file": "scenes/tangent_quads.gltf"},
                         {"name": "no_normals", "file": "scenes/cube_no_normals.gltf"}]})";
        const shaderlab::LabSpecResult parsed = shaderlab::parseLabSpec(lab_.string());
        std::string errors;
        for (const std::string& e : parsed.errors) errors += "\n" + e;
        ASSERT_TRUE(parsed.ok) << errors;
        spec_ = parsed.spec;
    }
    void TearDown() override { fs::remove_all(root_); }

    // The view of one scene, through renderLab as the window and the page reach it.
    shaderlab::LabRender render(DebugView view, const std::string& scene, shaderlab::CameraOrbit orbit = {}) {
        shaderlab::RenderOptions options;
        options.debug_view = view;
        options.only_scenes = {scene};
        options.orbit = orbit;
        shaderlab::LabRender r =
            shaderlab::renderLab(spec_, (root_ / "no-such-submission").string(), options);
        EXPECT_EQ(r.status, shaderlab::RenderStatus::Ok) << r.message;
        EXPECT_EQ(r.scenes.size(), 1u);
        if (r.scenes.size() == 1) {
            EXPECT_EQ(r.scenes[0].scene, scene);
            EXPECT_EQ(r.scenes[0].passes.size(), 1u) << r.scenes[0].error;
        }
        return r;
    }

    static std::string notes(const shaderlab::LabRender& r) {
        std::string all;
        for (const shaderlab::Diagnostic& d : r.diagnostics)
            if (d.severity == "note") all += d.message + "\n";
        return all;
    }

    shaderlab::Camera sceneCamera(const std::string& file) {
        shaderlab::Scene scene;
        const shaderlab::SceneLoadResult r =
            shaderlab::loadGltfScene((root_ / "labs" / file).string(), &scene);
        EXPECT_TRUE(r.ok) << r.error;
        return scene.camera;
    }

    fs::path root_, lab_;
    shaderlab::LabSpec spec_;
};

TEST(DebugViewNames, ParseAndNameEveryView) {
    EXPECT_EQ(shaderlab::debugViewNames("|"), "off|normals|tangents|bitangents|handedness|uv|uv-checker");
    for (const shaderlab::DebugViewInfo& v : shaderlab::debugViews()) {
        DebugView parsed = DebugView::Off;
        EXPECT_TRUE(shaderlab::parseDebugView(v.name, &parsed)) << v.name;
        EXPECT_EQ(parsed, v.view);
        EXPECT_STREQ(shaderlab::debugViewName(v.view), v.name);
        EXPECT_GT(std::string(v.label).size(), 20u) << v.name;
    }
    DebugView kept = DebugView::Uv;
    EXPECT_FALSE(shaderlab::parseDebugView("normal", &kept));
    EXPECT_EQ(kept, DebugView::Uv);
    EXPECT_STREQ(shaderlab::debugViewName(DebugView::Off), "off");
}

// The centre pixel looks along the camera's line of sight at the sphere's centre (the camera's
// target), so the surface there faces straight back at the camera.
TEST_F(DebugViewRender, SphereNormalAtTheCentreFacesTheCamera) {
    const shaderlab::LabRender r = render(DebugView::Normals, "sphere");
    ASSERT_EQ(r.scenes.size(), 1u);
    const shaderlab::SceneRender& s = r.scenes[0];
    ASSERT_EQ(s.passes.size(), 1u);
    const shaderlab::PassImage& img = s.passes[0];
    EXPECT_EQ(img.pass, "debug");
    EXPECT_EQ(img.attachment, "normals");
    EXPECT_FALSE(img.graded);
    EXPECT_EQ(img.color.width, kSize) << "the size of the lab's final image";
    EXPECT_EQ(img.color.channels, 4);
    EXPECT_EQ(img.color.at(0, 0, 3), 1.0f) << "opaque: coverage says where the meshes are";

    const shaderlab::Camera cam = sceneCamera("scenes/sphere.gltf");
    ASSERT_NEAR(glm::length(cam.target), 0.0f, 1e-4f) << "the bundled sphere's camera looks at its centre";
    ASSERT_TRUE(covered(s, 32, 32));
    expectNear(pixel(s, 32, 32), encoded(cam.position - cam.target), 0.03f, "centre normal");
    // Every covered pixel is a unit normal, n * 0.5 + 0.5.
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x)
            if (covered(s, x, y)) {
                EXPECT_NEAR(glm::length(pixel(s, x, y) * 2.0f - 1.0f), 1.0f, 1e-3f);
            }
    // Across the middle row the normal turns from the camera's left to its right.
    const glm::vec3 right = glm::normalize(glm::cross(cam.target - cam.position, cam.up));
    float last = -2.0f;
    for (int x = 0; x < kSize; x += 4) {
        if (!covered(s, x, 32)) continue;
        const float along = glm::dot(pixel(s, x, 32) * 2.0f - 1.0f, right);
        EXPECT_GT(along, last) << "column " << x;
        last = along;
    }
    EXPECT_GT(last, 0.5f);
    // The background is the documented colour, uncovered.
    EXPECT_FALSE(covered(s, 0, 0));
    expectNear(
        pixel(s, 0, 0),
        {shaderlab::kDebugBackground[0], shaderlab::kDebugBackground[1], shaderlab::kDebugBackground[2]},
        1e-6f, "background");
    EXPECT_EQ(notes(r), "") << "the sphere has normals";
}

// The viewer's orbit turns the camera of the debug view as it does the lab's: the centre still
// faces the (turned) camera.
TEST_F(DebugViewRender, TurnedCameraStillFacesTheCentre) {
    const shaderlab::CameraOrbit orbit{90.0f, 20.0f, 1.0f};
    const shaderlab::LabRender r = render(DebugView::Normals, "sphere", orbit);
    ASSERT_EQ(r.scenes.size(), 1u);
    shaderlab::Scene scene;
    ASSERT_TRUE(shaderlab::loadGltfScene((root_ / "labs" / "scenes" / "sphere.gltf").string(), &scene).ok);
    shaderlab::Camera cam = scene.camera;
    shaderlab::orbitCamera(scene, orbit, &cam);
    const glm::vec3 n = pixel(r.scenes[0], 32, 32) * 2.0f - 1.0f;
    expectNear(pixel(r.scenes[0], 32, 32), encoded(cam.position - cam.target), 0.03f, "turned centre normal");
    EXPECT_GT(n.x, 0.8f) << "yaw 90 puts the camera on +x";
}

// The sphere's generator (framework/tools/make_scenes.cpp, uvSphere) gives glTF v from the north
// pole down and u with the angle about +y from +z towards +x: so t (= 1 - v) grows up the picture,
// and s grows left to right on either side of the u = 0 seam, which faces +z.
TEST_F(DebugViewRender, SphereTextureCoordinatesGrowAlongTheirAxes) {
    const shaderlab::LabRender r = render(DebugView::Uv, "sphere");
    ASSERT_EQ(r.scenes.size(), 1u);
    const shaderlab::SceneRender& s = r.scenes[0];
    for (int x : {28, 38}) {
        float below = -1.0f;
        int seen = 0;
        for (int y = 56; y >= 8; y -= 4) {
            if (!covered(s, x, y)) continue;
            const glm::vec3 c = pixel(s, x, y);
            EXPECT_GT(c.g, below) << "t grows upwards, column " << x << " row " << y;
            EXPECT_EQ(c.b, 0.0f);
            below = c.g;
            ++seen;
        }
        EXPECT_GE(seen, 8) << "column " << x;
    }
    // Right of the seam s starts near 0 and grows; left of it s runs up towards 1.
    EXPECT_LT(pixel(s, 36, 32).r, pixel(s, 46, 32).r);
    EXPECT_LT(pixel(s, 36, 32).r, 0.1f);
    EXPECT_LT(pixel(s, 18, 32).r, pixel(s, 28, 32).r);
    EXPECT_GT(pixel(s, 28, 32).r, 0.9f);
}

// Three quads: TANGENT +x with w = +1, no TANGENT, and TANGENT -x with w = -1 (u mirrored).
TEST_F(DebugViewRender, QuadsShowTheTangentsTheirFileHolds) {
    const int left = 14, middle = 32, right = 50, row = 32;  // the quads' centres, 64 pixels wide
    const glm::vec3 grey(shaderlab::kDebugNeutral);
    {
        const shaderlab::LabRender r = render(DebugView::Tangents, "quads");
        ASSERT_EQ(r.scenes.size(), 1u);
        const shaderlab::SceneRender& s = r.scenes[0];
        expectNear(pixel(s, left, row), {1.0f, 0.5f, 0.5f}, 1e-4f, "tangent +x");
        expectNear(pixel(s, right, row), {0.0f, 0.5f, 0.5f}, 1e-4f, "tangent -x");
        expectNear(pixel(s, middle, row), grey, 1e-6f, "no TANGENT: grey");
        const std::string n = notes(r);
        EXPECT_NE(n.find("no tangents in scenes/tangent_quads.gltf, mesh no_tangents: drawn grey"),
                  std::string::npos)
            << n;
        EXPECT_NE(n.find("MikkTSpace"), std::string::npos) << "says what lab shaders get instead\n" << n;
        EXPECT_EQ(n.find("right_handed"), std::string::npos) << n;
        EXPECT_EQ(n.find("mirrored"), std::string::npos) << n;
    }
    {
        const shaderlab::LabRender r = render(DebugView::Handedness, "quads");
        ASSERT_EQ(r.scenes.size(), 1u);
        expectNear(pixel(r.scenes[0], left, row), {0.0f, 1.0f, 0.0f}, 1e-6f, "w = +1: green");
        expectNear(pixel(r.scenes[0], right, row), {1.0f, 0.0f, 0.0f}, 1e-6f, "w = -1: red");
        expectNear(pixel(r.scenes[0], middle, row), grey, 1e-6f, "no TANGENT: grey");
    }
    {
        // cross(+z, +x) * +1 and cross(+z, -x) * -1 both point up: +t, up the picture.
        const shaderlab::LabRender r = render(DebugView::Bitangents, "quads");
        ASSERT_EQ(r.scenes.size(), 1u);
        expectNear(pixel(r.scenes[0], left, row), {0.5f, 1.0f, 0.5f}, 1e-4f, "bitangent, right-handed");
        expectNear(pixel(r.scenes[0], right, row), {0.5f, 1.0f, 0.5f}, 1e-4f, "bitangent, mirrored");
        expectNear(pixel(r.scenes[0], middle, row), grey, 1e-6f, "no TANGENT: grey");
    }
    {
        const shaderlab::LabRender r = render(DebugView::Normals, "quads");
        ASSERT_EQ(r.scenes.size(), 1u);
        for (int x : {left, middle, right})
            expectNear(pixel(r.scenes[0], x, row), {0.5f, 0.5f, 1.0f}, 1e-4f, "normal +z");
        EXPECT_EQ(notes(r), "") << "normals need no tangents";
    }
}

// s grows to the right on the first quads and to the left on the mirrored one; t grows upwards on
// all three. The checker is the same coordinates folded into cells, pixel for pixel.
TEST_F(DebugViewRender, QuadTextureCoordinatesAndTheirChecker) {
    const shaderlab::LabRender uv = render(DebugView::Uv, "quads");
    const shaderlab::LabRender checker = render(DebugView::UvChecker, "quads");
    ASSERT_EQ(uv.scenes.size(), 1u);
    ASSERT_EQ(checker.scenes.size(), 1u);
    const shaderlab::SceneRender& s = uv.scenes[0];
    EXPECT_LT(pixel(s, 10, 32).r, pixel(s, 18, 32).r) << "right-handed quad: s along +x";
    EXPECT_LT(pixel(s, 28, 32).r, pixel(s, 36, 32).r) << "no TANGENT, same coordinates";
    EXPECT_GT(pixel(s, 46, 32).r, pixel(s, 54, 32).r) << "mirrored quad: s along -x";
    for (int x : {14, 32, 50}) {
        EXPECT_LT(pixel(s, x, 40).g, pixel(s, x, 24).g) << "t upwards, column " << x;
    }
    EXPECT_EQ(notes(uv), "") << "every quad has TEXCOORD_0";

    int compared = 0, differing = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            if (!covered(s, x, y)) continue;
            const glm::vec2 st(pixel(s, x, y));
            const glm::vec3 ramp(glm::fract(st), 0.0f);
            const float light = std::fmod(std::floor(st.x * 8.0f) + std::floor(st.y * 8.0f), 2.0f);
            const glm::vec3 want = light > 0.5f ? ramp * 0.5f + 0.5f : ramp * 0.5f;
            ++compared;
            const glm::vec3 got = pixel(checker.scenes[0], x, y);
            differing += glm::length(got - want) > 1e-3f;
        }
    EXPECT_GT(compared, 500);
    // On a cell's edge the two renders may round to different sides.
    EXPECT_LT(differing, compared / 20) << differing << " of " << compared;
}

// The bundled sphere has no TANGENT: the tangent views draw it grey and say so; the loader's own
// MikkTSpace tangents, which a lab shader would read, are not shown as if the file had them.
TEST_F(DebugViewRender, SphereWithoutTangentsIsGreyAndNamed) {
    for (DebugView view : {DebugView::Tangents, DebugView::Bitangents, DebugView::Handedness}) {
        const shaderlab::LabRender r = render(view, "sphere");
        ASSERT_EQ(r.scenes.size(), 1u);
        const shaderlab::SceneRender& s = r.scenes[0];
        int grey = 0, drawn = 0;
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x) {
                if (!covered(s, x, y)) continue;
                ++drawn;
                grey += glm::length(pixel(s, x, y) - glm::vec3(shaderlab::kDebugNeutral)) < 1e-6f;
            }
        EXPECT_GT(drawn, 1000);
        EXPECT_EQ(grey, drawn) << shaderlab::debugViewName(view);
        EXPECT_NE(notes(r).find("no tangents in scenes/sphere.gltf, mesh sphere"), std::string::npos)
            << notes(r);
    }
}

TEST_F(DebugViewRender, GeneratedFlatNormalsAreShownAndSaidToBe) {
    const shaderlab::LabRender r = render(DebugView::Normals, "no_normals");
    ASSERT_EQ(r.scenes.size(), 1u);
    EXPECT_NE(notes(r).find("no normals in scenes/cube_no_normals.gltf, mesh "), std::string::npos)
        << notes(r);
    // Flat: one of a few face colours, each a unit axis.
    const shaderlab::SceneRender& s = r.scenes[0];
    ASSERT_TRUE(covered(s, 32, 32));
    const glm::vec3 n = pixel(s, 32, 32) * 2.0f - 1.0f;
    EXPECT_NEAR(std::max({std::abs(n.x), std::abs(n.y), std::abs(n.z)}), 1.0f, 1e-4f);
}

// The notes and images of every scene at once (what `render --debug` writes), and a scene that
// does not load fails alone.
TEST_F(DebugViewRender, EverySceneAndABadOne) {
    std::ofstream(root_ / "labs" / "scenes" / "broken.gltf") << "not json";
    std::ofstream(lab_ / "lab.json")
        << R"({"schema": 2, "id": "70-debug", "resolution": [48, 32], "passes": [{"name": "draw",
          "program": {"vertex": "scene.vert", "fragment": "scene.frag"}, "graded": true}],
          "scenes": [{"name": "sphere", "file": "scenes/sphere.gltf"},
                     {"name": "broken", "file": "scenes/broken.gltf"}]})";
    const shaderlab::LabSpecResult parsed = shaderlab::parseLabSpec(lab_.string());
    ASSERT_TRUE(parsed.ok);
    const shaderlab::LabRender r = shaderlab::renderDebugView(parsed.spec, DebugView::UvChecker, {});
    ASSERT_EQ(r.status, shaderlab::RenderStatus::Ok) << r.message;
    ASSERT_EQ(r.scenes.size(), 2u);
    ASSERT_EQ(r.scenes[0].passes.size(), 1u);
    EXPECT_EQ(r.scenes[0].passes[0].color.width, 48);
    EXPECT_EQ(r.scenes[0].passes[0].color.height, 32);
    EXPECT_TRUE(r.scenes[1].passes.empty());
    EXPECT_FALSE(r.scenes[1].error.empty());
}

}  // namespace
