// Tests for the glTF loader (framework/scene/src/gltf_loader.cpp): the bundled scenes in labs/scenes/,
// the small fixtures in tests/data/gltf/ (one loader feature each; make_fixtures.py there says
// how each was made), the malformed fixtures (each must fail with the file name and a phrase
// naming the problem), and mutated copies of valid files (must never crash; run this binary
// under the SHADERLAB_SANITIZE build to check "never reads out of bounds" as well).
// It does not render anything: what the scenes look like is the renderer's tests' business.
#include "shaderlab/scene/gltf_loader.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <glm/gtc/matrix_transform.hpp>
#include <iterator>
#include <nlohmann/json.hpp>
#include <ostream>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

namespace fs = std::filesystem;
using shaderlab::LightType;
using shaderlab::Scene;
using shaderlab::SceneLoadResult;

namespace {

std::string fixture(const std::string& name) { return std::string(SHADERLAB_TEST_DATA) + "/gltf/" + name; }
std::string bundled(const std::string& name) {
    return std::string(SHADERLAB_SOURCE_DIR) + "/labs/scenes/" + name;
}

std::string joined(const std::vector<std::string>& lines) {
    std::string s;
    for (const auto& l : lines) s += l + "\n";
    return s;
}

bool near3(const glm::vec3& a, const glm::vec3& b, float eps = 1e-4f) { return glm::length(a - b) <= eps; }

// A scratch folder per test, removed afterwards.
class TempDir {
  public:
    TempDir() {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        std::string name = std::string("shaderlab_gltf_") + std::to_string(::getpid()) + "_" +
                           info->test_suite_name() + "_" + info->name();
        std::replace(name.begin(), name.end(), '/', '_');
        path_ = fs::temp_directory_path() / name;
        fs::remove_all(path_);
        fs::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ec;
        fs::remove_all(path_, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const fs::path& path() const { return path_; }

  private:
    fs::path path_;
};

std::string readBytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void writeBytes(const fs::path& p, const std::string& bytes) {
    std::ofstream out(p, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// Structural checks every successfully loaded scene must pass.
void expectWellFormed(const Scene& scene) {
    for (const auto& mesh : scene.meshes) {
        SCOPED_TRACE("mesh " + mesh.name);
        ASSERT_FALSE(mesh.positions.empty());
        ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
        ASSERT_EQ(mesh.texcoords.size(), mesh.positions.size());
        ASSERT_EQ(mesh.indices.size() % 3, 0u);
        for (std::uint32_t i : mesh.indices) ASSERT_LT(i, mesh.positions.size());
        for (const auto& n : mesh.normals) ASSERT_NEAR(glm::length(n), 1.0f, 1e-4f);
    }
    for (const auto& item : scene.draw_items) {
        ASSERT_GE(item.mesh, 0);
        ASSERT_LT(static_cast<std::size_t>(item.mesh), scene.meshes.size());
        ASSERT_GE(item.material, -1);
        ASSERT_LT(item.material, static_cast<int>(scene.materials.size()));
    }
    for (const auto& light : scene.lights) ASSERT_NEAR(glm::length(light.direction), 1.0f, 1e-4f);
    EXPECT_TRUE(std::isfinite(scene.camera.z_near) && std::isfinite(scene.camera.z_far));
    EXPECT_GT(scene.camera.z_near, 0.0f);
    EXPECT_GT(scene.camera.z_far, scene.camera.z_near);
    EXPECT_GT(scene.camera.fov_y_deg, 0.0f);
    EXPECT_LT(scene.camera.fov_y_deg, 180.0f);
}

// Whether the camera's view cone contains `p`, with a little slack for the horizontal extent
// at aspect 1.
bool cameraSees(const shaderlab::Camera& cam, const glm::vec3& p) {
    const glm::vec3 forward = glm::normalize(cam.target - cam.position);
    const glm::vec3 to = p - cam.position;
    const float cos_angle = glm::dot(forward, glm::normalize(to));
    return cos_angle >= std::cos(glm::radians(cam.fov_y_deg) * 0.5f * 1.42f);
}

// ---------------------------------------------------------------------------------------------
// Bundled scenes.

struct BundledCase {
    const char* file;
    std::size_t meshes;
    std::size_t draw_items;
    std::size_t lights;
    bool had_normals;
};

void PrintTo(const BundledCase& c, std::ostream* os) { *os << c.file; }

class GltfBundledScene : public ::testing::TestWithParam<BundledCase> {};

TEST_P(GltfBundledScene, LoadsWithCameraLightsAndSaneGeometry) {
    const BundledCase& c = GetParam();
    Scene scene;
    const SceneLoadResult r = shaderlab::loadGltfScene(bundled(c.file), &scene);
    ASSERT_TRUE(r.ok) << r.error;
    EXPECT_EQ(scene.source_path, bundled(c.file));
    ASSERT_EQ(scene.meshes.size(), c.meshes);
    ASSERT_EQ(scene.draw_items.size(), c.draw_items);
    ASSERT_EQ(scene.lights.size(), c.lights);
    expectWellFormed(scene);

    EXPECT_TRUE(scene.has_camera);
    EXPECT_NEAR(scene.camera.fov_y_deg, 45.0f, 1e-3f);
    EXPECT_FLOAT_EQ(scene.camera.file_aspect, 1.0f);
    EXPECT_NEAR(glm::length(scene.camera.up), 1.0f, 1e-4f);
    EXPECT_EQ(scene.lights[0].type, LightType::Point);

    // The file's camera frames the scene: the centre of the objects (the ground plane is larger
    // than the view on purpose) is in view, and the light is away from the geometry.
    const glm::vec3 centre = 0.5f * (scene.bounds_min + scene.bounds_max);
    EXPECT_TRUE(cameraSees(scene.camera, centre));
    // Bounds have extent along at least two axes (the plane alone is flat).
    int extended = 0;
    for (int axis = 0; axis < 3; ++axis) extended += scene.bounds_min[axis] < scene.bounds_max[axis];
    EXPECT_GE(extended, 2);

    for (const auto& mesh : scene.meshes) {
        SCOPED_TRACE(mesh.name);
        EXPECT_EQ(mesh.had_normals, c.had_normals);
        EXPECT_TRUE(mesh.had_texcoords);
        // Back-face culling is on in the labs: each triangle must wind counter-clockwise seen
        // from the side its normals point to.
        std::size_t wrong = 0;
        for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
            const auto a = mesh.indices[t], b = mesh.indices[t + 1], cc = mesh.indices[t + 2];
            const glm::vec3 face =
                glm::cross(mesh.positions[b] - mesh.positions[a], mesh.positions[cc] - mesh.positions[a]);
            if (glm::length(face) < 1e-9f) continue;
            if (glm::dot(face, mesh.normals[a] + mesh.normals[b] + mesh.normals[cc]) <= 0.0f) ++wrong;
        }
        EXPECT_EQ(wrong, 0u);
    }
    for (const auto& item : scene.draw_items) {
        ASSERT_GE(item.material, 0) << "every bundled object has a base colour";
        EXPECT_NE(scene.materials[static_cast<std::size_t>(item.material)].base_color, glm::vec4(1.0f));
    }
    EXPECT_LT(fs::file_size(bundled(c.file)), 1u << 20);
}

INSTANTIATE_TEST_SUITE_P(Gltf, GltfBundledScene,
                         ::testing::Values(BundledCase{"sphere.gltf", 1, 1, 1, true},
                                           BundledCase{"sphere_low_poly.gltf", 1, 1, 1, true},
                                           BundledCase{"torus.gltf", 1, 1, 1, true},
                                           BundledCase{"torus_knot.glb", 1, 1, 1, true},
                                           BundledCase{"cube_flat.gltf", 1, 1, 1, true},
                                           BundledCase{"cube_no_normals.gltf", 1, 1, 1, false},
                                           BundledCase{"nonuniform_scale.gltf", 1, 1, 1, true},
                                           BundledCase{"ground_plane.gltf", 2, 2, 2, true},
                                           BundledCase{"teapot.gltf", 1, 1, 1, true},
                                           BundledCase{"teapot_on_plane.gltf", 2, 2, 2, true},
                                           BundledCase{"plane.gltf", 1, 1, 1, true}),
                         [](const ::testing::TestParamInfo<BundledCase>& param_info) {
                             std::string name = param_info.param.file;
                             std::replace(name.begin(), name.end(), '.', '_');
                             return name;
                         });

TEST(GltfBundledScenes, EveryBundledSceneIsCovered) {
    std::set<std::string> files;
    for (const auto& e : fs::directory_iterator(bundled(""))) {
        const auto ext = e.path().extension();
        if (ext == ".gltf" || ext == ".glb") files.insert(e.path().filename().string());
    }
    const std::set<std::string> tested = {"sphere.gltf",
                                          "sphere_low_poly.gltf",
                                          "torus.gltf",
                                          "torus_knot.glb",
                                          "cube_flat.gltf",
                                          "cube_no_normals.gltf",
                                          "nonuniform_scale.gltf",
                                          "ground_plane.gltf",
                                          "teapot.gltf",
                                          "teapot_on_plane.gltf",
                                          "plane.gltf"};
    EXPECT_EQ(files, tested) << "add new scenes to GltfBundledScene";
}

TEST(GltfBundledScenes, CubeFlatHasTwentyFourVerticesAndSixFaceNormals) {
    Scene scene;
    const auto r = shaderlab::loadGltfScene(bundled("cube_flat.gltf"), &scene);
    ASSERT_TRUE(r.ok) << r.error;
    const auto& mesh = scene.meshes[0];
    EXPECT_EQ(mesh.positions.size(), 24u);
    EXPECT_EQ(mesh.indices.size(), 36u);
    std::set<std::tuple<int, int, int>> normals;
    for (const auto& n : mesh.normals) {
        normals.insert({static_cast<int>(std::lround(n.x)), static_cast<int>(std::lround(n.y)),
                        static_cast<int>(std::lround(n.z))});
    }
    EXPECT_EQ(normals.size(), 6u);
    EXPECT_TRUE(r.warnings.empty()) << joined(r.warnings);
}

TEST(GltfBundledScenes, NonuniformScaleKeepsTheNodeScaleInTheWorldMatrix) {
    Scene scene;
    const auto r = shaderlab::loadGltfScene(bundled("nonuniform_scale.gltf"), &scene);
    ASSERT_TRUE(r.ok) << r.error;
    const glm::mat4& w = scene.draw_items[0].world;
    EXPECT_NEAR(glm::length(glm::vec3(w[0])), 2.0f, 1e-4f);
    EXPECT_NEAR(glm::length(glm::vec3(w[1])), 0.5f, 1e-4f);
    EXPECT_NEAR(glm::length(glm::vec3(w[2])), 1.0f, 1e-4f);
    // The unit sphere scaled by (2, 0.5, 1), then turned 25 degrees about Z: the ellipse's
    // half-extents are sqrt((2 cos a)^2 + (0.5 sin a)^2) in x and sqrt((2 sin a)^2 + (0.5 cos a)^2)
    // in y (the 64x32 tessellation lands within a percent of them).
    const float a = glm::radians(25.0f);
    const float half_x = std::sqrt(std::pow(2.0f * std::cos(a), 2.0f) + std::pow(0.5f * std::sin(a), 2.0f));
    const float half_y = std::sqrt(std::pow(2.0f * std::sin(a), 2.0f) + std::pow(0.5f * std::cos(a), 2.0f));
    EXPECT_NEAR(scene.bounds_max.x, half_x, 0.02f);
    EXPECT_NEAR(scene.bounds_min.x, -half_x, 0.02f);
    EXPECT_NEAR(scene.bounds_max.y, half_y, 0.02f);
    EXPECT_NEAR(scene.bounds_max.z, 1.0f, 0.02f);
}

TEST(GltfBundledScenes, GroundPlaneHasAPointAndADirectionalLight) {
    Scene scene;
    const auto r = shaderlab::loadGltfScene(bundled("ground_plane.gltf"), &scene);
    ASSERT_TRUE(r.ok) << r.error;
    ASSERT_EQ(scene.lights.size(), 2u);
    EXPECT_EQ(scene.lights[0].type, LightType::Point);
    EXPECT_TRUE(near3(scene.lights[0].position, glm::vec3(3.0f, 4.0f, 5.0f)));
    EXPECT_EQ(scene.lights[1].type, LightType::Directional);
    EXPECT_TRUE(near3(scene.lights[1].direction, glm::normalize(glm::vec3(0.3f, -1.0f, -0.5f)), 1e-4f));
    EXPECT_TRUE(near3(scene.lights[1].color, glm::vec3(0.4f, 0.5f, 0.8f)));
    EXPECT_FLOAT_EQ(scene.lights[1].intensity, 0.5f);
    // The knot stands on the plane (y = 0) without sinking into it.
    EXPECT_NEAR(scene.bounds_min.y, 0.0f, 1e-4f);
    float knot_low = 1e9f;
    for (const auto& p : scene.meshes[static_cast<std::size_t>(scene.draw_items[1].mesh)].positions) {
        knot_low = std::min(knot_low, (scene.draw_items[1].world * glm::vec4(p, 1.0f)).y);
    }
    EXPECT_GT(knot_low, 0.0f);
    EXPECT_LT(knot_low, 0.1f);
}

TEST(GltfBundledScenes, CameraPoseComesFromTheCameraNode) {
    Scene scene;
    const auto r = shaderlab::loadGltfScene(bundled("cube_flat.gltf"), &scene);
    ASSERT_TRUE(r.ok) << r.error;
    // make_scenes puts this camera at (2.2, 1.8, 2.8) looking at the origin.
    EXPECT_TRUE(near3(scene.camera.position, glm::vec3(2.2f, 1.8f, 2.8f)));
    const glm::vec3 forward = glm::normalize(scene.camera.target - scene.camera.position);
    EXPECT_TRUE(near3(forward, glm::normalize(-scene.camera.position), 1e-4f));
    EXPECT_GT(scene.camera.up.y, 0.5f);
    EXPECT_NEAR(glm::dot(scene.camera.up, forward), 0.0f, 1e-4f);
    EXPECT_FLOAT_EQ(scene.camera.z_near, 0.1f);
    EXPECT_FLOAT_EQ(scene.camera.z_far, 100.0f);
}

// ---------------------------------------------------------------------------------------------
// Features, one fixture each.

TEST(GltfFlatNormals, CubeWithoutNormalsGetsOneNormalPerFace) {
    Scene scene;
    const auto r = shaderlab::loadGltfScene(bundled("cube_no_normals.gltf"), &scene);
    ASSERT_TRUE(r.ok) << r.error;
    ASSERT_EQ(scene.meshes.size(), 1u);
    const auto& mesh = scene.meshes[0];
    EXPECT_FALSE(mesh.had_normals);
    EXPECT_NE(joined(r.warnings).find("normals generated flat"), std::string::npos) << joined(r.warnings);
    // Un-shared: one vertex per triangle corner.
    ASSERT_EQ(mesh.positions.size(), 36u);
    ASSERT_EQ(mesh.indices.size(), 36u);
    std::set<std::tuple<int, int, int>> faces;
    for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
        const glm::vec3 a = mesh.positions[mesh.indices[t]];
        const glm::vec3 b = mesh.positions[mesh.indices[t + 1]];
        const glm::vec3 c = mesh.positions[mesh.indices[t + 2]];
        const glm::vec3 face = glm::normalize(glm::cross(b - a, c - a));
        for (int k = 0; k < 3; ++k)
            EXPECT_TRUE(near3(mesh.normals[mesh.indices[t + static_cast<std::size_t>(k)]], face));
        // Outward: the cube is centred on the origin.
        EXPECT_GT(glm::dot(face, (a + b + c) / 3.0f), 0.0f);
        faces.insert({static_cast<int>(std::lround(face.x)), static_cast<int>(std::lround(face.y)),
                      static_cast<int>(std::lround(face.z))});
    }
    EXPECT_EQ(faces.size(), 6u);
}

TEST(GltfNodeTransforms, ParentScaleAndChildTranslationCompose) {
    Scene scene;
    const auto r = shaderlab::loadGltfScene(fixture("node_transforms.gltf"), &scene);
    ASSERT_TRUE(r.ok) << r.error;
    expectWellFormed(scene);
    ASSERT_EQ(scene.draw_items.size(), 2u);
    // The mesh is instanced twice but converted once.
    ASSERT_EQ(scene.meshes.size(), 1u);
    EXPECT_EQ(scene.draw_items[0].mesh, scene.draw_items[1].mesh);
    EXPECT_EQ(scene.draw_items[0].node_name, "child");
    EXPECT_EQ(scene.draw_items[1].node_name, "grandchild");

    // child: scale(2) * translate(1,0,0): the origin lands at (2,0,0) and lengths double.
    const glm::mat4 expected_child =
        glm::translate(glm::scale(glm::mat4(1.0f), glm::vec3(2.0f)), glm::vec3(1, 0, 0));
    const glm::mat4& child = scene.draw_items[0].world;
    for (int c = 0; c < 4; ++c) EXPECT_TRUE(near3(glm::vec3(child[c]), glm::vec3(expected_child[c]))) << c;
    EXPECT_TRUE(near3(glm::vec3(child * glm::vec4(0, 0, 0, 1)), glm::vec3(2, 0, 0)));
    EXPECT_TRUE(near3(glm::vec3(child * glm::vec4(1, 0, 0, 1)), glm::vec3(4, 0, 0)));
    // grandchild: its matrix (translation (0,0,3)) is in the parent's scaled space.
    EXPECT_TRUE(near3(glm::vec3(scene.draw_items[1].world * glm::vec4(0, 0, 0, 1)), glm::vec3(2, 0, 6)));

    EXPECT_TRUE(near3(scene.bounds_min, glm::vec3(2, 0, 0)));
    EXPECT_TRUE(near3(scene.bounds_max, glm::vec3(4, 2, 6)));

    // The spot light under the child: at the child's origin, shining along +X (its -Z turned
    // by -90 degrees about Y); the parent's scale must not stretch the direction.
    ASSERT_EQ(scene.lights.size(), 1u);
    const auto& light = scene.lights[0];
    EXPECT_EQ(light.type, LightType::Spot);
    EXPECT_TRUE(near3(light.position, glm::vec3(2, 0, 0)));
    EXPECT_TRUE(near3(light.direction, glm::vec3(1, 0, 0)));
    EXPECT_TRUE(near3(light.color, glm::vec3(1.0f, 0.5f, 0.25f)));
    EXPECT_FLOAT_EQ(light.intensity, 3.0f);
    EXPECT_FLOAT_EQ(light.range, 10.0f);
}

TEST(GltfDefaultCamera, FramesTheBoundsFromThePlusZSide) {
    Scene scene;
    const auto r = shaderlab::loadGltfScene(fixture("node_transforms.gltf"), &scene);
    ASSERT_TRUE(r.ok) << r.error;
    EXPECT_FALSE(scene.has_camera);
    const glm::vec3 centre = 0.5f * (scene.bounds_min + scene.bounds_max);
    EXPECT_TRUE(near3(scene.camera.target, centre));
    EXPECT_GT(scene.camera.position.z, centre.z);
    EXPECT_GT(scene.camera.position.y, centre.y);
    EXPECT_TRUE(near3(scene.camera.up, glm::vec3(0, 1, 0)));
    // Every corner of the bounds is in view and between the clip planes.
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 corner((i & 1) ? scene.bounds_max.x : scene.bounds_min.x,
                               (i & 2) ? scene.bounds_max.y : scene.bounds_min.y,
                               (i & 4) ? scene.bounds_max.z : scene.bounds_min.z);
        EXPECT_TRUE(cameraSees(scene.camera, corner)) << i;
        const float depth = glm::dot(corner - scene.camera.position,
                                     glm::normalize(scene.camera.target - scene.camera.position));
        EXPECT_GT(depth, scene.camera.z_near);
        EXPECT_LT(depth, scene.camera.z_far);
    }
}

class GltfIndexType : public ::testing::TestWithParam<const char*> {};

TEST_P(GltfIndexType, ReadsIndicesHonouringTheAccessorOffset) {
    Scene scene;
    const auto r = shaderlab::loadGltfScene(fixture(GetParam()), &scene);
    ASSERT_TRUE(r.ok) << r.error;
    expectWellFormed(scene);
    ASSERT_EQ(scene.meshes.size(), 1u);
    EXPECT_EQ(scene.meshes[0].positions.size(), 4u);
    EXPECT_EQ(scene.meshes[0].indices, (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3}));
    EXPECT_FALSE(scene.meshes[0].had_texcoords);
    EXPECT_EQ(scene.meshes[0].texcoords, std::vector<glm::vec2>(4, glm::vec2(0.0f)));
}

INSTANTIATE_TEST_SUITE_P(Gltf, GltfIndexType,
                         ::testing::Values("indices_ubyte.gltf", "indices_ushort.gltf", "indices_uint.gltf"),
                         [](const ::testing::TestParamInfo<const char*>& param_info) {
                             std::string name = param_info.param;
                             return name.substr(0, name.find('.'));
                         });

TEST(GltfFeatures, NonIndexedPrimitiveGetsSequentialIndices) {
    Scene scene;
    const auto r = shaderlab::loadGltfScene(fixture("non_indexed.gltf"), &scene);
    ASSERT_TRUE(r.ok) << r.error;
    EXPECT_EQ(scene.meshes[0].indices, (std::vector<std::uint32_t>{0, 1, 2}));
}

// TANGENT is read as the file gives it (w the handedness); a mesh without it gets generated
// tangents, flagged so that the debug view can tell them apart (render/debug_view.h).
TEST(GltfFeatures, TangentsFromTheFileAndGeneratedOnesAreToldApart) {
    shaderlab::Scene scene;
    const auto r = shaderlab::loadGltfScene(fixture("tangent_quads.gltf"), &scene);
    ASSERT_TRUE(r.ok) << r.error;
    ASSERT_EQ(scene.meshes.size(), 3u);
    EXPECT_TRUE(scene.has_camera);
    const glm::vec4 want[] = {{1, 0, 0, 1}, {0, 0, 0, 0}, {-1, 0, 0, -1}};
    for (std::size_t m = 0; m < 3; ++m) {
        const shaderlab::Mesh& mesh = scene.meshes[m];
        ASSERT_EQ(mesh.tangents.size(), mesh.positions.size()) << mesh.name;
        EXPECT_EQ(mesh.tangents_generated, m == 1) << mesh.name;
        if (m == 1) continue;
        for (const glm::vec4& t : mesh.tangents) EXPECT_EQ(t, want[m]) << mesh.name;
    }
    EXPECT_EQ(scene.meshes[1].name, "no_tangents");
}

TEST(GltfFeatures, SparseAccessorOverridesZeros) {
    Scene scene;
    const auto r = shaderlab::loadGltfScene(fixture("sparse.gltf"), &scene);
    ASSERT_TRUE(r.ok) << r.error;
    const auto& p = scene.meshes[0].positions;
    ASSERT_EQ(p.size(), 3u);
    EXPECT_TRUE(near3(p[0], glm::vec3(0, 0, 0)));
    EXPECT_TRUE(near3(p[1], glm::vec3(1, 0, 0)));
    EXPECT_TRUE(near3(p[2], glm::vec3(0, 1, 0)));
}

TEST(GltfFeatures, ManyInstancesOfABigMeshGetBoundsFromTheirBoxes) {
    Scene scene;
    const auto r = shaderlab::loadGltfScene(fixture("many_instances.gltf"), &scene);
    ASSERT_TRUE(r.ok) << r.error;
    ASSERT_EQ(scene.meshes.size(), 1u);
    EXPECT_EQ(scene.draw_items.size(), 21u);
    EXPECT_EQ(scene.meshes[0].positions.size(), 1048575u);
    EXPECT_TRUE(near3(scene.bounds_min, glm::vec3(0, 0, 0)));
    EXPECT_TRUE(near3(scene.bounds_max, glm::vec3(21, 1, 0)));
}

TEST(GltfFeatures, NormalizedByteTexcoordsWithByteStride) {
    Scene scene;
    const auto r = shaderlab::loadGltfScene(fixture("texcoords_normalized.gltf"), &scene);
    ASSERT_TRUE(r.ok) << r.error;
    const auto& mesh = scene.meshes[0];
    EXPECT_TRUE(mesh.had_texcoords);
    // Flat normals un-share the vertices, keeping the corners in order for a non-indexed
    // triangle.
    // The file's (u, v) are (0, 0), (1, 0), (0, 1); the mesh holds OpenGL's (u, 1 - v).
    ASSERT_EQ(mesh.texcoords.size(), 3u);
    EXPECT_EQ(mesh.texcoords[0], glm::vec2(0.0f, 1.0f));
    EXPECT_EQ(mesh.texcoords[1], glm::vec2(1.0f, 1.0f));
    EXPECT_EQ(mesh.texcoords[2], glm::vec2(0.0f, 0.0f));
    EXPECT_TRUE(near3(mesh.normals[0], glm::vec3(0, 0, 1)));
}

TEST(GltfFeatures, SkipsNonTriangleModesAndReadsAnInfiniteCamera) {
    Scene scene;
    const auto r = shaderlab::loadGltfScene(fixture("modes_and_camera.gltf"), &scene);
    ASSERT_TRUE(r.ok) << r.error;
    expectWellFormed(scene);
    EXPECT_EQ(scene.draw_items.size(), 1u);
    EXPECT_NE(joined(r.warnings).find("mode 0 (POINTS) skipped"), std::string::npos) << joined(r.warnings);
    ASSERT_TRUE(scene.has_camera);
    EXPECT_NEAR(scene.camera.fov_y_deg, glm::degrees(0.5f), 1e-4f);
    EXPECT_FLOAT_EQ(scene.camera.z_near, 0.05f);
    EXPECT_GE(scene.camera.z_far, 50.0f);  // no zfar in the file: a large finite far plane
    EXPECT_FLOAT_EQ(scene.camera.file_aspect, 0.0f);
    EXPECT_TRUE(near3(scene.camera.position, glm::vec3(0, 0, 5)));
    EXPECT_TRUE(near3(glm::normalize(scene.camera.target - scene.camera.position), glm::vec3(0, 0, -1)));
    EXPECT_TRUE(near3(scene.camera.up, glm::vec3(0, 1, 0)));
    EXPECT_TRUE(scene.lights.empty());
}

TEST(GltfFeatures, LoadsABinaryGlb) {
    Scene scene;
    const auto r = shaderlab::loadGltfScene(fixture("triangle.glb"), &scene);
    ASSERT_TRUE(r.ok) << r.error;
    expectWellFormed(scene);
    ASSERT_EQ(scene.meshes.size(), 1u);
    EXPECT_EQ(scene.meshes[0].indices, (std::vector<std::uint32_t>{0, 1, 2}));
    EXPECT_TRUE(near3(scene.meshes[0].positions[1], glm::vec3(1, 0, 0)));
}

TEST(GltfFeatures, GlbIsRecognisedByItsMagicWhateverTheExtension) {
    TempDir dir;
    fs::copy_file(fixture("triangle.glb"), dir.path() / "triangle.gltf");
    Scene scene;
    const auto r = shaderlab::loadGltfScene((dir.path() / "triangle.gltf").string(), &scene);
    ASSERT_TRUE(r.ok) << r.error;
    EXPECT_EQ(scene.meshes.size(), 1u);
}

TEST(GltfFeatures, ExternalBinInTheSameFolderLoads) {
    // The bundled .gltf scenes use external .bin files; loading one from a copy with a relative
    // path checks URIs are resolved against the file's folder, not the working directory.
    TempDir dir;
    fs::copy_file(bundled("sphere.gltf"), dir.path() / "sphere.gltf");
    fs::copy_file(bundled("sphere.bin"), dir.path() / "sphere.bin");
    Scene scene;
    const auto r = shaderlab::loadGltfScene((dir.path() / "sphere.gltf").string(), &scene);
    ASSERT_TRUE(r.ok) << r.error;
    EXPECT_EQ(scene.meshes.size(), 1u);
}

// ---------------------------------------------------------------------------------------------
// Malformed files: ok=false, the error names the file and the problem, the scene is left empty.

struct MalformedCase {
    const char* file;
    const char* phrase;
};

void PrintTo(const MalformedCase& c, std::ostream* os) { *os << c.file; }

class GltfMalformed : public ::testing::TestWithParam<MalformedCase> {};

TEST_P(GltfMalformed, FailsWithTheFileNameAndTheProblem) {
    const MalformedCase& c = GetParam();
    Scene scene;
    scene.meshes.resize(3);  // must be cleared, not left half-filled
    const std::string path = fixture(c.file);
    if (std::string(c.file) != "no_such_file.gltf") {
        ASSERT_TRUE(fs::exists(path)) << path;
    }
    const SceneLoadResult r = shaderlab::loadGltfScene(path, &scene);
    EXPECT_FALSE(r.ok);
    EXPECT_EQ(r.error.rfind(path + ": ", 0), 0u) << r.error;
    EXPECT_NE(r.error.find(c.phrase), std::string::npos)
        << "error: " << r.error << "\nexpected: " << c.phrase;
    EXPECT_TRUE(scene.meshes.empty());
    EXPECT_TRUE(scene.draw_items.empty());
}

INSTANTIATE_TEST_SUITE_P(
    Gltf, GltfMalformed,
    ::testing::Values(
        MalformedCase{
            "accessor_out_of_range.gltf",
            "accessor 0 (POSITION of mesh 'tri'): reads bytes 0..48 of bufferView 0 which has 36 bytes"},
        MalformedCase{"accessor_offset_overflow.gltf", "of bufferView 0 which has 36 bytes"},
        MalformedCase{"huge_count.gltf", "count 4000000000 is over the limit"},
        MalformedCase{"unbacked_huge_count.gltf", "count 5000000 without a bufferView is over the limit"},
        MalformedCase{"bad_buffer_view.gltf",
                      "bufferView 1: bytes 36..436 lie outside buffer 0 which has 80 bytes"},
        MalformedCase{"buffer_view_overflow.gltf", "lie outside buffer 0"},
        MalformedCase{"bad_stride.gltf", "byteStride 8 of bufferView 0 is invalid"},
        MalformedCase{"missing_bin.gltf", "missing file 'missing_bin.bin'"},
        MalformedCase{"uri_escapes_folder.gltf",
                      "URI '../secret.bin' uses '..' and escapes the scene's folder"},
        MalformedCase{"uri_percent_escape.gltf", "escapes the scene's folder"},
        MalformedCase{"uri_absolute.gltf", "URI '/etc/passwd' is an absolute path"},
        MalformedCase{"wrong_type_position.gltf", "is VEC2 of FLOAT, expected VEC3 of FLOAT"},
        MalformedCase{"wrong_type_indices.gltf", "(indices of mesh 'tri'): is SCALAR of FLOAT"},
        MalformedCase{"index_out_of_range.gltf",
                      "index 7 at position 2 is out of range: the primitive has 3 vertices"},
        MalformedCase{"missing_position.gltf", "has no POSITION attribute"},
        MalformedCase{"sparse_index_out_of_range.gltf", "sparse index 7 at position 1"},
        MalformedCase{"node_cycle.gltf", "the node hierarchy must be a tree"},
        MalformedCase{"bad_node_child.gltf", "node 99 does not exist"},
        MalformedCase{"bad_mesh_index.gltf", "mesh 5 does not exist"},
        MalformedCase{"bad_light_index.gltf", "light 5 does not exist"},
        MalformedCase{"bad_matrix.gltf", "matrix must be 16 finite numbers"},
        MalformedCase{"bad_default_scene.gltf", "default scene 3 does not exist"},
        MalformedCase{"required_extension.gltf",
                      "requires extension 'KHR_texture_basisu': its textures use an image format"},
        MalformedCase{"data_uri_too_short.gltf", "tinygltf: Failed to decode 'uri'"},
        MalformedCase{"truncated.glb", "truncated GLB: the header declares 856 bytes but the file has 816"},
        MalformedCase{"glb_bin_chunk_overrun.glb", "the BIN chunk of 88 bytes at byte 768 runs past the end"},
        MalformedCase{"glb_empty_buffer.glb", "tinygltf"},
        MalformedCase{"not_glb.glb", "does not start with the 'glTF' magic"},
        MalformedCase{"json_too_deep.gltf", "JSON nests deeper than 128 levels"},
        MalformedCase{"not_json.gltf", "not valid glTF JSON"},
        MalformedCase{"json_not_gltf.gltf", "Root element is not a JSON object"},
        MalformedCase{"empty.gltf", "file is empty"}, MalformedCase{"no_such_file.gltf", "file not found"}),
    [](const ::testing::TestParamInfo<MalformedCase>& param_info) {
        std::string name = param_info.param.file;
        std::replace(name.begin(), name.end(), '.', '_');
        return name;
    });

// no_such_file.gltf is deliberately absent; the parameterized test asserts the others exist.
TEST(GltfMalformedSetup, NoSuchFileReallyIsAbsent) { EXPECT_FALSE(fs::exists(fixture("no_such_file.gltf"))); }

TEST(GltfSecurity, SymlinkedBinOutsideTheFolderIsRefused) {
    TempDir dir;
    fs::create_directories(dir.path() / "scene");
    fs::copy_file(bundled("cube_flat.bin"), dir.path() / "outside.bin");
    fs::copy_file(bundled("cube_flat.gltf"), dir.path() / "scene" / "cube_flat.gltf");
    fs::create_symlink(dir.path() / "outside.bin", dir.path() / "scene" / "cube_flat.bin");
    Scene scene;
    const std::string path = (dir.path() / "scene" / "cube_flat.gltf").string();
    const auto r = shaderlab::loadGltfScene(path, &scene);
    EXPECT_FALSE(r.ok);
    EXPECT_EQ(r.error.rfind(path + ": ", 0), 0u) << r.error;
    EXPECT_NE(r.error.find("refused"), std::string::npos) << r.error;
}

TEST(GltfSecurity, MissingBinIsNotLookedUpInTheWorkingDirectory) {
    // tinygltf retries a missing file relative to the working directory; the loader must not.
    TempDir dir;
    fs::create_directories(dir.path() / "scene");
    fs::copy_file(bundled("cube_flat.gltf"), dir.path() / "scene" / "cube_flat.gltf");
    fs::copy_file(bundled("cube_flat.bin"), dir.path() / "cube_flat.bin");
    const fs::path old_cwd = fs::current_path();
    fs::current_path(dir.path());
    Scene scene;
    const auto r = shaderlab::loadGltfScene("scene/cube_flat.gltf", &scene);
    fs::current_path(old_cwd);
    EXPECT_FALSE(r.ok);
    EXPECT_NE(r.error.find("missing file 'cube_flat.bin'"), std::string::npos) << r.error;
}

TEST(GltfSecurity, NullSceneIsAnErrorNotACrash) {
    const auto r = shaderlab::loadGltfScene(fixture("triangle.glb"), nullptr);
    EXPECT_FALSE(r.ok);
    EXPECT_FALSE(r.error.empty());
}

// ---------------------------------------------------------------------------------------------
// Mutations of valid files: whatever comes back, it must come back (run under ASan to also catch
// silent out-of-bounds reads).

void expectSaneResult(const std::string& path, const std::string& what) {
    Scene scene;
    const SceneLoadResult r = shaderlab::loadGltfScene(path, &scene);
    if (r.ok) {
        expectWellFormed(scene);
    } else {
        EXPECT_EQ(r.error.rfind(path + ": ", 0), 0u) << what << ": " << r.error;
        EXPECT_GT(r.error.size(), path.size() + 2) << what;
    }
}

// Calls `visit` on every number in `doc` (depth first), letting it replace the value.
void forEachNumber(nlohmann::json& doc, const std::function<void(nlohmann::json&)>& visit) {
    if (doc.is_number()) {
        visit(doc);
    } else if (doc.is_object() || doc.is_array()) {
        for (auto& child : doc) forEachNumber(child, visit);
    }
}

TEST(GltfMutations, EveryNumberReplacedByHostileValues) {
    TempDir dir;
    const std::vector<nlohmann::json> hostile = {
        -1,    0,      3,  255, 65536, 2147483647, 4294967295u, std::uint64_t{18446744073709551615u},
        1e300, -1e300, 0.5};
    for (const char* name : {"node_transforms.gltf", "sparse.gltf", "texcoords_normalized.gltf",
                             "indices_ushort.gltf", "modes_and_camera.gltf"}) {
        std::ifstream in(fixture(name));
        const nlohmann::json original = nlohmann::json::parse(in);
        std::size_t numbers = 0;
        nlohmann::json counter = original;
        forEachNumber(counter, [&](nlohmann::json&) { ++numbers; });
        for (std::size_t target = 0; target < numbers; ++target) {
            for (const auto& value : hostile) {
                nlohmann::json doc = original;
                std::size_t seen = 0;
                forEachNumber(doc, [&](nlohmann::json& v) {
                    if (seen++ == target) v = value;
                });
                const fs::path path = dir.path() / name;
                writeBytes(path, doc.dump());
                expectSaneResult(path.string(), std::string(name) + " number " + std::to_string(target) +
                                                    " = " + value.dump());
            }
        }
    }
}

TEST(GltfMutations, GlbBytesFlippedAndTruncated) {
    TempDir dir;
    const std::string original = readBytes(fixture("triangle.glb"));
    ASSERT_GT(original.size(), 100u);
    const fs::path path = dir.path() / "mutated.glb";
    std::uint32_t json_length = 0;
    std::memcpy(&json_length, original.data() + 12, 4);
    const std::size_t bin_header = 20 + json_length;
    for (std::size_t at = 0; at < original.size(); ++at) {
        // The header and chunk headers get every variant; the JSON and BIN bodies a sample.
        const bool header = at < 24 || (at >= bin_header && at < bin_header + 8);
        if (!header && at % 7 != 0) continue;
        for (unsigned char value : {0x00, 0xff, 0x7f, 0x80}) {
            std::string bytes = original;
            bytes[at] = static_cast<char>(value);
            writeBytes(path, bytes);
            expectSaneResult(path.string(), "byte " + std::to_string(at) + " = " + std::to_string(value));
        }
    }
    for (std::size_t length = 0; length < original.size(); length += 3) {
        writeBytes(path, original.substr(0, length));
        expectSaneResult(path.string(), "truncated to " + std::to_string(length));
    }
}

}  // namespace
