// Scenes as instructors bring them (tests/data/gltf_realworld/, written by make_realworld.py
// there): each file either loads like its plain twin, or is refused with a message naming the
// problem (gltf_realworld_render_test.cpp draws them). Also here: MikkTSpace tangents on simple
// meshes, and the default camera fitting a portrait target. No GL: this file also runs in the
// AddressSanitizer build of the loader (shaderlab_gltf_asan_tests).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <string>
#include <vector>

#include "../src/tangent_space.h"
#include "shaderlab/lab/lab_spec.h"
#include "shaderlab/scene/camera.h"
#include "shaderlab/scene/gltf_loader.h"

namespace fs = std::filesystem;
using shaderlab::Scene;
using shaderlab::SceneLoadResult;

namespace {

std::string realworld(const std::string& name) {
    return std::string(SHADERLAB_TEST_DATA) + "/gltf_realworld/" + name;
}

std::string joined(const std::vector<std::string>& lines) {
    std::string s;
    for (const auto& l : lines) s += l + "\n";
    return s;
}

SceneLoadResult load(const std::string& name, Scene* scene) {
    const SceneLoadResult r = shaderlab::loadGltfScene(realworld(name), scene);
    EXPECT_TRUE(r.ok) << r.error;
    return r;
}

std::size_t triangles(const Scene& scene) {
    std::size_t n = 0;
    for (const auto& item : scene.draw_items)
        n += scene.meshes[static_cast<std::size_t>(item.mesh)].indices.size() / 3;
    return n;
}

bool near3(const glm::vec3& a, const glm::vec3& b, float eps) { return glm::length(a - b) <= eps; }

// ---------------------------------------------------------------------------------------------
// Refusals: named before anything is decoded.

struct RefusalCase {
    const char* file;
    const char* phrase;
};
void PrintTo(const RefusalCase& c, std::ostream* os) { *os << c.file; }

class GltfRealWorldRefused : public ::testing::TestWithParam<RefusalCase> {};

TEST_P(GltfRealWorldRefused, NamesTheExtensionAndWhatToDo) {
    Scene scene;
    const SceneLoadResult r = shaderlab::loadGltfScene(realworld(GetParam().file), &scene);
    ASSERT_FALSE(r.ok);
    EXPECT_EQ(r.error.rfind(realworld(GetParam().file) + ": ", 0), 0u) << r.error;
    EXPECT_NE(r.error.find(GetParam().phrase), std::string::npos) << r.error;
    EXPECT_NE(r.error.find("re-export"), std::string::npos) << r.error;
}

INSTANTIATE_TEST_SUITE_P(GltfRealWorld, GltfRealWorldRefused,
                         ::testing::Values(RefusalCase{"basisu_textures.gltf",
                                                       "requires extension 'KHR_texture_basisu'"},
                                           RefusalCase{"msft_lod.gltf", "requires extension 'MSFT_lod'"}),
                         [](const ::testing::TestParamInfo<RefusalCase>& p) {
                             std::string s = p.param.file;
                             for (char& c : s)
                                 if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                             return s;
                         });

// ---------------------------------------------------------------------------------------------
// Compressed meshes decode to the same cube as the plain twin.

class GltfRealWorldCompressed : public ::testing::TestWithParam<const char*> {};

TEST_P(GltfRealWorldCompressed, DecodesToTheTwinsGeometry) {
    Scene twin, scene;
    load("compressed_cube_twin.glb", &twin);
    const SceneLoadResult r = load(GetParam(), &scene);
    ASSERT_TRUE(r.ok);
    EXPECT_EQ(triangles(scene), 12u);
    // Quantization moves vertices by well under a percent of the cube.
    EXPECT_TRUE(near3(scene.bounds_min, twin.bounds_min, 5e-3f)) << GetParam();
    EXPECT_TRUE(near3(scene.bounds_max, twin.bounds_max, 5e-3f)) << GetParam();
    ASSERT_EQ(scene.meshes.size(), 1u);
    const auto& mesh = scene.meshes[0];
    EXPECT_TRUE(mesh.had_normals);  // (gltfpack drops texcoords no texture uses)
    // Every decoded vertex lies on the twin's cube surface with an outward axis normal.
    const glm::mat4 to_local = glm::inverse(twin.draw_items[0].world);
    const glm::mat4 world = scene.draw_items[0].world;
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        const glm::vec3 p = glm::vec3(to_local * world * glm::vec4(mesh.positions[i], 1.0f));
        EXPECT_NEAR(std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}), 0.5f, 5e-3f) << i;
        const glm::vec3 n = glm::normalize(
            glm::mat3(to_local) * glm::mat3(glm::inverseTranspose(glm::mat3(world))) * mesh.normals[i]);
        EXPECT_NEAR(std::max({std::abs(n.x), std::abs(n.y), std::abs(n.z)}), 1.0f, 2e-2f) << i;
        EXPECT_GT(glm::dot(n, p), 0.0f) << i;
    }
}

INSTANTIATE_TEST_SUITE_P(GltfRealWorld, GltfRealWorldCompressed,
                         ::testing::Values("draco_cube.glb", "meshopt_cube.glb",
                                           "meshopt_quantized_cube.glb"),
                         [](const ::testing::TestParamInfo<const char*>& p) {
                             std::string s = p.param;
                             return s.substr(0, s.find('.'));
                         });

TEST(GltfRealWorld, CorruptDracoDataIsAnErrorNotACrash) {
    std::ifstream in(realworld("draco_cube.glb"), std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::size_t json = *reinterpret_cast<const std::uint32_t*>(bytes.data() + 12);
    // Scribble over the BIN chunk (the Draco stream) after its header.
    for (std::size_t i = 20 + json + 8 + 4; i < bytes.size(); i += 3)
        bytes[i] = static_cast<char>(bytes[i] ^ 0x5a);
    const fs::path tmp =
        fs::temp_directory_path() / ("shaderlab_corrupt_draco_" + std::to_string(::getpid()) + ".glb");
    std::ofstream(tmp, std::ios::binary) << bytes;
    Scene scene;
    const SceneLoadResult r = shaderlab::loadGltfScene(tmp.string(), &scene);
    fs::remove(tmp);
    // Draco may decode scribbled data to some mesh; whatever it gives must be safe to draw.
    if (r.ok) {
        for (const auto& mesh : scene.meshes)
            for (std::uint32_t i : mesh.indices) ASSERT_LT(i, mesh.positions.size());
    } else {
        EXPECT_NE(r.error.find(tmp.string() + ": "), std::string::npos) << r.error;
    }
}

// ---------------------------------------------------------------------------------------------
// Geometry.

TEST(GltfRealWorld, MirroringNodeIsFlaggedAndItsTwinIsNot) {
    Scene mirrored, twin;
    load("mirrored_cube.gltf", &mirrored);
    load("mirrored_cube_twin.gltf", &twin);
    ASSERT_EQ(mirrored.draw_items.size(), 1u);
    EXPECT_TRUE(mirrored.draw_items[0].mirrored);
    EXPECT_FALSE(twin.draw_items[0].mirrored);
}

TEST(GltfRealWorld, StripsAndFansBecomeTrianglesFacingTheirFirstTriangle) {
    Scene scene;
    const SceneLoadResult r = load("strip_fan.gltf", &scene);
    ASSERT_EQ(scene.meshes.size(), 2u);
    for (const auto& mesh : scene.meshes) {
        ASSERT_EQ(mesh.indices.size(), 6u) << mesh.name;
        for (std::size_t t = 0; t < 6; t += 3) {
            const glm::vec3 n =
                glm::cross(mesh.positions[mesh.indices[t + 1]] - mesh.positions[mesh.indices[t]],
                           mesh.positions[mesh.indices[t + 2]] - mesh.positions[mesh.indices[t]]);
            EXPECT_GT(n.z, 0.0f) << mesh.name << " triangle " << t / 3;  // counter-clockwise seen from +Z
        }
    }
    EXPECT_TRUE(r.warnings.empty()) << joined(r.warnings);
}

TEST(GltfRealWorld, LinesAndPointsAreSkippedWithAWarningNamingTheMode) {
    Scene scene;
    const SceneLoadResult r = load("strip_fan_lines_points.gltf", &scene);
    EXPECT_EQ(scene.draw_items.size(), 2u);
    const std::string w = joined(r.warnings);
    EXPECT_NE(w.find("mode 2 (LINE_LOOP) skipped; shaderlab draws only triangles"), std::string::npos) << w;
    EXPECT_NE(w.find("mode 0 (POINTS) skipped"), std::string::npos) << w;
}

TEST(GltfRealWorld, InterleavedBufferReadsLikeTightlyPackedOne) {
    Scene scene, twin;
    load("interleaved_cube.glb", &scene);
    load("interleaved_cube_twin.gltf", &twin);
    ASSERT_EQ(scene.meshes.size(), 1u);
    ASSERT_EQ(twin.meshes.size(), 1u);
    EXPECT_EQ(scene.meshes[0].positions, twin.meshes[0].positions);
    EXPECT_EQ(scene.meshes[0].normals, twin.meshes[0].normals);
    EXPECT_EQ(scene.meshes[0].texcoords, twin.meshes[0].texcoords);
    EXPECT_EQ(scene.meshes[0].indices, twin.meshes[0].indices);
}

TEST(GltfRealWorld, SkinAndMorphTargetsLoadInBindPoseWithWarnings) {
    Scene scene;
    const SceneLoadResult r = load("skinned_morphed_cube.gltf", &scene);
    const std::string w = joined(r.warnings);
    EXPECT_NE(w.find("skin 0 ignored; mesh 'character' is drawn in its bind pose"), std::string::npos) << w;
    EXPECT_NE(w.find("1 morph targets ignored"), std::string::npos) << w;
    EXPECT_TRUE(near3(scene.bounds_max, glm::vec3(0.5f), 1e-5f));  // the morph (+0.5 y) not applied
}

TEST(GltfRealWorld, GpuInstancesAreDrawnLikeSeparateNodes) {
    Scene scene, twin;
    const SceneLoadResult r = load("instanced_cubes.gltf", &scene);
    load("instanced_cubes_twin.gltf", &twin);
    ASSERT_EQ(scene.draw_items.size(), 3u);
    ASSERT_EQ(twin.draw_items.size(), 3u);
    for (std::size_t i = 0; i < 3; ++i) {
        for (int c = 0; c < 4; ++c)
            EXPECT_TRUE(
                near3(glm::vec3(scene.draw_items[i].world[c]), glm::vec3(twin.draw_items[i].world[c]), 1e-6f))
                << "instance " << i;
    }
    EXPECT_TRUE(near3(scene.bounds_min, twin.bounds_min, 1e-6f));
    EXPECT_TRUE(near3(scene.bounds_max, twin.bounds_max, 1e-6f));
    EXPECT_TRUE(r.warnings.empty()) << joined(r.warnings);
}

// ---------------------------------------------------------------------------------------------
// Materials, attributes, lights, cameras.

TEST(GltfRealWorld, PbrMaterialSlotsSamplersAndAttributes) {
    Scene scene;
    load("pbr_material_cube.gltf", &scene);
    ASSERT_EQ(scene.materials.size(), 1u);
    const auto& m = scene.materials[0];
    EXPECT_EQ(m.base_color, glm::vec4(0.8f, 0.4f, 0.3f, 1.0f));
    EXPECT_FLOAT_EQ(m.metallic, 0.25f);
    EXPECT_FLOAT_EQ(m.roughness, 0.75f);
    EXPECT_TRUE(near3(m.emissive, glm::vec3(0.1f, 0.05f, 0.0f), 1e-6f));
    EXPECT_EQ(m.base_color_texture.texture, 0);
    EXPECT_EQ(m.metallic_roughness_texture.texcoord, 1);
    EXPECT_FLOAT_EQ(m.normal_texture.scale, 0.5f);
    EXPECT_FLOAT_EQ(m.occlusion_texture.scale, 0.8f);
    EXPECT_EQ(m.emissive_texture.texture, 0);
    ASSERT_EQ(scene.textures.size(), 1u);
    EXPECT_EQ(scene.textures[0].image_uri, "brick.png");
    EXPECT_TRUE(scene.textures[0].srgb);  // used as base colour and emissive
    EXPECT_EQ(scene.textures[0].wrap_s, 33648);
    EXPECT_EQ(scene.textures[0].min_filter, 9987);
    const auto& mesh = scene.meshes[0];
    ASSERT_EQ(mesh.colors.size(), mesh.positions.size());
    EXPECT_EQ(mesh.colors[1], glm::vec4(1.0f, 64.0f / 255.0f, 0.0f, 1.0f));
    ASSERT_EQ(mesh.texcoords1.size(), mesh.positions.size());
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        EXPECT_FLOAT_EQ(mesh.texcoords1[i].x, 0.5f * mesh.texcoords[i].x);
        EXPECT_FLOAT_EQ(mesh.texcoords1[i].y, 1.0f - 0.5f * (1.0f - mesh.texcoords[i].y));  // t = 1 - v
    }
    ASSERT_EQ(mesh.tangents.size(), mesh.positions.size());
    EXPECT_TRUE(mesh.tangents_generated);
}

TEST(GltfRealWorld, SpotLightConesRangeAndOrthographicCamera) {
    Scene scene;
    load("spot_light_ortho_camera.gltf", &scene);
    ASSERT_EQ(scene.lights.size(), 2u);
    const auto& spot = scene.lights[0];
    EXPECT_EQ(spot.type, shaderlab::LightType::Spot);
    EXPECT_FLOAT_EQ(spot.inner_cone, 0.3f);
    EXPECT_FLOAT_EQ(spot.outer_cone, 0.6f);
    EXPECT_FLOAT_EQ(spot.range, 12.5f);
    EXPECT_FLOAT_EQ(spot.intensity, 54.35f);
    EXPECT_TRUE(near3(spot.direction, glm::vec3(0, -1, 0), 1e-5f));  // pointing down from y = 4
    ASSERT_TRUE(scene.has_camera);
    EXPECT_TRUE(scene.camera.orthographic);
    EXPECT_FLOAT_EQ(scene.camera.ortho_height, 2.0f);
    EXPECT_FLOAT_EQ(scene.camera.file_aspect, 1.5f);
    EXPECT_GT(scene.camera.z_near, 0.0f);
    EXPECT_FLOAT_EQ(scene.camera.z_far, 20.0f);

    // What shaders receive for the spot: the specification's precomputed cone falloff.
    shaderlab::SceneSpec spec;
    const auto lights = shaderlab::resolveLights(scene, spec, scene.camera);
    ASSERT_EQ(lights.size(), 2u);
    const float scale = 1.0f / (std::cos(0.3f) - std::cos(0.6f));
    EXPECT_NEAR(lights[0].cone.x, scale, 1e-3f);
    EXPECT_NEAR(lights[0].cone.y, -std::cos(0.6f) * scale, 1e-3f);
    EXPECT_EQ(lights[1].cone, glm::vec2(0.0f, 1.0f));  // not a spot: no falloff
    EXPECT_FLOAT_EQ(lights[0].range, 12.5f);
}

// Every corner of the bounding sphere's enclosing square, seen from the default camera, lands
// inside the clip volume whatever the target's aspect: portrait targets are not cropped.
TEST(GltfRealWorld, DefaultCameraFitsTheSceneInPortraitAndLandscapeTargets) {
    Scene scene;
    load("instanced_cubes_twin.gltf", &scene);  // wide: 3.5 x 1 x 1
    ASSERT_FALSE(scene.has_camera);
    const glm::vec3 lo = scene.bounds_min, hi = scene.bounds_max;
    for (float aspect : {0.4f, 1.0f, 2.0f}) {
        const glm::mat4 vp =
            shaderlab::projectionMatrix(scene.camera, aspect) * shaderlab::viewMatrix(scene.camera);
        for (int corner = 0; corner < 8; ++corner) {
            const glm::vec4 c = vp * glm::vec4((corner & 1) ? hi.x : lo.x, (corner & 2) ? hi.y : lo.y,
                                               (corner & 4) ? hi.z : lo.z, 1.0f);
            EXPECT_LE(std::abs(c.x / c.w), 1.0f) << "aspect " << aspect << " corner " << corner;
            EXPECT_LE(std::abs(c.y / c.w), 1.0f) << "aspect " << aspect << " corner " << corner;
        }
    }
    // Square targets (every bundled lab) see exactly the vertical fit, as before.
    shaderlab::Camera vertical_only = scene.camera;
    vertical_only.fit_both_axes = false;
    EXPECT_EQ(shaderlab::projectionMatrix(scene.camera, 1.0f),
              shaderlab::projectionMatrix(vertical_only, 1.0f));
}

// ---------------------------------------------------------------------------------------------
// MikkTSpace tangents.

TEST(TangentSpace, TangentFollowsTheUGradientAndIsOrthogonalToTheNormal) {
    // A quad in the XY plane, u along +x, v along +y; then the same with u mirrored.
    const std::vector<glm::vec3> pos = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}};
    const std::vector<glm::vec3> nrm(4, glm::vec3(0, 0, 1));
    const std::vector<std::uint32_t> idx = {0, 1, 2, 0, 2, 3};
    const std::vector<glm::vec2> uv = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (const glm::vec4& t : shaderlab::generateTangents(pos, nrm, uv, idx)) {
        EXPECT_TRUE(near3(glm::vec3(t), glm::vec3(1, 0, 0), 1e-6f));
        EXPECT_EQ(t.w, 1.0f);  // bitangent cross(N, T) = +y, along +v
    }
    const std::vector<glm::vec2> mirrored_uv = {{1, 0}, {0, 0}, {0, 1}, {1, 1}};
    for (const glm::vec4& t : shaderlab::generateTangents(pos, nrm, mirrored_uv, idx)) {
        EXPECT_TRUE(near3(glm::vec3(t), glm::vec3(-1, 0, 0), 1e-6f));
        EXPECT_EQ(t.w, -1.0f);  // cross(N, T) = -y, but v still runs along +y
    }
}

TEST(TangentSpace, BundledSphereTangentsAreUnitOrthogonalAndAlongU) {
    Scene scene;
    const SceneLoadResult r =
        shaderlab::loadGltfScene(std::string(SHADERLAB_SOURCE_DIR) + "/labs/scenes/sphere.gltf", &scene);
    ASSERT_TRUE(r.ok) << r.error;
    const auto& mesh = scene.meshes[0];
    ASSERT_TRUE(mesh.had_texcoords);
    ASSERT_EQ(mesh.tangents.size(), mesh.positions.size());
    std::size_t along = 0, triangles_checked = 0;
    for (std::size_t i = 0; i < mesh.tangents.size(); ++i) {
        const glm::vec3 t(mesh.tangents[i]);
        EXPECT_NEAR(glm::length(t), 1.0f, 1e-4f);
        EXPECT_NEAR(glm::dot(t, mesh.normals[i]), 0.0f, 1e-4f);
    }
    // Per triangle, position changes along +u in the direction of its corners' tangents.
    for (std::size_t k = 0; k + 2 < mesh.indices.size(); k += 3) {
        const std::uint32_t a = mesh.indices[k], b = mesh.indices[k + 1], c = mesh.indices[k + 2];
        const glm::vec3 e1 = mesh.positions[b] - mesh.positions[a],
                        e2 = mesh.positions[c] - mesh.positions[a];
        const glm::vec2 d1 = mesh.texcoords[b] - mesh.texcoords[a],
                        d2 = mesh.texcoords[c] - mesh.texcoords[a];
        const float det = d1.x * d2.y - d2.x * d1.y;
        if (std::abs(det) < 1e-9f) continue;
        const glm::vec3 du = (e1 * d2.y - e2 * d1.y) / det;
        ++triangles_checked;
        if (glm::dot(du, glm::vec3(mesh.tangents[a])) > 0.0f) ++along;
    }
    ASSERT_GT(triangles_checked, 100u);
    // Only triangles at the u seam (where u wraps from 1 to 0) may disagree.
    EXPECT_GE(static_cast<double>(along) / static_cast<double>(triangles_checked), 0.97);
}

// Images are kept as the file stores them, undecoded (the renderer decodes those a program
// samples): from a data: URI, from a bufferView; a missing file leaves the bytes empty, with
// tinygltf's warning, and the scene still loads.
TEST(GltfRealWorld, ImagesAreKeptEncodedFromDataUrisAndBufferViews) {
    // "SGVsbG8=" is "Hello"; the buffer holds "PNGBYTES" + "JPEG".
    const std::string gltf = R"({"asset": {"version": "2.0"},
      "buffers": [{"byteLength": 12, "uri": "data:application/octet-stream;base64,UE5HQllURVNKUEVH"}],
      "bufferViews": [{"buffer": 0, "byteOffset": 8, "byteLength": 4}],
      "images": [{"name": "greeting", "uri": "data:image/png;base64,SGVsbG8="},
                 {"bufferView": 0, "mimeType": "image/jpeg"}, {"uri": "absent.png"}],
      "textures": [{"source": 1}, {"source": 0}]})";
    shaderlab::Scene scene;
    const auto r = shaderlab::loadGltfSceneFromBytes(gltf, realworld("images_in_memory.gltf"), &scene);
    ASSERT_TRUE(r.ok) << r.error;
    ASSERT_EQ(scene.images.size(), 3u);
    EXPECT_EQ(scene.images[0].name, "greeting");
    EXPECT_EQ(std::string(scene.images[0].bytes.begin(), scene.images[0].bytes.end()), "Hello");
    EXPECT_EQ(scene.images[1].name, "image1");
    EXPECT_EQ(std::string(scene.images[1].bytes.begin(), scene.images[1].bytes.end()), "JPEG");
    EXPECT_TRUE(scene.images[2].bytes.empty());
    EXPECT_NE(joined(r.warnings).find("image[2]"), std::string::npos) << joined(r.warnings);
    ASSERT_EQ(scene.textures.size(), 2u);
    EXPECT_EQ(scene.textures[0].image, 1);
    EXPECT_EQ(scene.textures[1].image, 0);
}

}  // namespace
