// Tests for the Utah teapot that shaderlab_make_scenes tessellates from Newell's Bezier patches
// (labs/scenes/teapot.gltf and teapot_on_plane.gltf): the stored normals are finite unit vectors,
// the triangles agree with their vertex normals, the normals point out of the pot, the size and
// placement are what the generator promises, and the patch seams are welded (coincident vertices
// remain only at creases, so extruding along the normals opens no cracks).
// The generic checks every bundled scene gets are in gltf_loader_test.cpp.
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <numeric>
#include <string>
#include <tuple>
#include <vector>

#include "shaderlab/scene/gltf_loader.h"

using shaderlab::LightType;
using shaderlab::Mesh;
using shaderlab::Scene;

namespace {

std::string bundled(const std::string& name) {
    return std::string(SHADERLAB_SOURCE_DIR) + "/labs/scenes/" + name;
}

// What the generator promises: the bounding box centred on the origin, the farthest vertex this
// far from it, and equal positions only where the normals differ by more than the weld angle.
constexpr float kRadius = 1.2f;
constexpr float kWeldAngleDeg = 20.0f;

Scene loadTeapot(const std::string& file) {
    Scene scene;
    const auto r = shaderlab::loadGltfScene(bundled(file), &scene);
    EXPECT_TRUE(r.ok) << r.error;
    EXPECT_TRUE(r.warnings.empty());
    return scene;
}

const Mesh& teapotMesh(const Scene& scene) {
    for (const auto& item : scene.draw_items) {
        if (item.node_name == "teapot") return scene.meshes[static_cast<std::size_t>(item.mesh)];
    }
    ADD_FAILURE() << "no node 'teapot'";
    static const Mesh empty;
    return empty;
}

// The loader replaces a zero or NaN normal with +Z, so the stored ones are read here directly.
TEST(Teapot, StoredNormalsAreFiniteUnitVectors) {
    tinygltf::TinyGLTF gltf;
    tinygltf::Model model;
    std::string err, warn;
    ASSERT_TRUE(gltf.LoadASCIIFromFile(&model, &err, &warn, bundled("teapot.gltf"))) << err;
    ASSERT_EQ(model.meshes.size(), 1u);
    const auto& acc =
        model.accessors[static_cast<std::size_t>(model.meshes[0].primitives[0].attributes.at("NORMAL"))];
    ASSERT_EQ(acc.componentType, TINYGLTF_COMPONENT_TYPE_FLOAT);
    ASSERT_EQ(acc.type, TINYGLTF_TYPE_VEC3);
    const auto& view = model.bufferViews[static_cast<std::size_t>(acc.bufferView)];
    ASSERT_EQ(view.byteStride, 0u);
    const auto& data = model.buffers[static_cast<std::size_t>(view.buffer)].data;
    ASSERT_LE(view.byteOffset + acc.byteOffset + acc.count * 12, data.size());
    const unsigned char* p = data.data() + view.byteOffset + acc.byteOffset;
    std::size_t bad = 0;
    for (std::size_t i = 0; i < acc.count; ++i) {
        float n[3];
        std::memcpy(n, p + 12 * i, 12);
        const float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (!std::isfinite(n[0]) || !std::isfinite(n[1]) || !std::isfinite(n[2]) ||
            std::abs(len - 1.0f) > 1e-5f)
            ++bad;
    }
    EXPECT_EQ(bad, 0u) << "of " << acc.count << " normals";
}

TEST(Teapot, IsOneMeshOfReasonableSize) {
    const Scene scene = loadTeapot("teapot.gltf");
    ASSERT_EQ(scene.meshes.size(), 1u);
    const Mesh& mesh = scene.meshes[0];
    EXPECT_TRUE(mesh.had_normals);
    EXPECT_TRUE(mesh.had_texcoords);
    std::printf("teapot: %zu vertices, %zu triangles\n", mesh.positions.size(), mesh.indices.size() / 3);
    // 32 patches of 12 x 12 samples, less what the weld shares (the whole seam network and the
    // two collapsed poles), and 2 x 11 x 11 cells per patch, less those at the collapsed edges.
    EXPECT_GT(mesh.positions.size(), 3000u);
    EXPECT_LT(mesh.positions.size(), 32u * 12u * 12u);
    EXPECT_EQ(mesh.indices.size() / 3, 32u * 2u * 11u * 11u - 8u * 11u);
    for (float t : {0.0f, 1.0f}) {
        EXPECT_TRUE(std::any_of(mesh.texcoords.begin(), mesh.texcoords.end(),
                                [t](const glm::vec2& uv) { return std::abs(uv.y - t) < 1e-6f; }));
    }
    // s may pass 1: the copies of vertices beside the wrap at the back (s + 1, s < 0.5).
    for (const auto& uv : mesh.texcoords) {
        ASSERT_TRUE(uv.x >= 0.0f && uv.x < 1.5f && uv.y >= 0.0f && uv.y <= 1.0f) << uv.x << ", " << uv.y;
    }
    // No triangle interpolates across the wrap (but those around the two poles, where a
    // cylindrical map is singular: the lid's top and the bottom's centre).
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        float lo = 2.0f, hi = -1.0f;
        bool pole = false;
        for (std::size_t k = 0; k < 3; ++k) {
            const float v = mesh.texcoords[mesh.indices[t + k]].y;
            pole = pole || v < 0.01f || v > 0.99f;
        }
        if (pole) continue;
        for (std::size_t k = 0; k < 3; ++k) {
            lo = std::min(lo, mesh.texcoords[mesh.indices[t + k]].x);
            hi = std::max(hi, mesh.texcoords[mesh.indices[t + k]].x);
        }
        EXPECT_LT(hi - lo, 0.5f) << "triangle " << t / 3;
    }
}

// A triangle's own normal should point the way its three vertex normals do. Where the surface
// bends sharply within one triangle (the spout's lip) one of them may not; report how often.
TEST(Teapot, TrianglesAgreeWithTheirVertexNormals) {
    const Scene scene = loadTeapot("teapot.gltf");
    const Mesh& mesh = teapotMesh(scene);
    std::size_t agree = 0, triangles = 0;
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const std::uint32_t i[3] = {mesh.indices[t], mesh.indices[t + 1], mesh.indices[t + 2]};
        const glm::vec3 face = glm::cross(mesh.positions[i[1]] - mesh.positions[i[0]],
                                          mesh.positions[i[2]] - mesh.positions[i[0]]);
        ASSERT_GT(glm::length(face), 0.0f) << "degenerate triangle " << t / 3;
        ++triangles;
        if (std::all_of(i, i + 3, [&](std::uint32_t v) { return glm::dot(face, mesh.normals[v]) > 0.0f; }))
            ++agree;
    }
    const double fraction = double(agree) / double(triangles);
    std::printf("teapot: %zu of %zu triangles (%.4f%%) agree with all three vertex normals\n", agree,
                triangles, 100.0 * fraction);
    EXPECT_GE(fraction, 0.995);
}

// At the vertex that reaches farthest in a direction, the outward normal points that way. Many
// directions reach every part (body, lid, knob, bottom, handle, spout): an inverted part fails.
TEST(Teapot, NormalsPointOutwardWhereThePotReachesFarthest) {
    const Scene scene = loadTeapot("teapot.gltf");
    const Mesh& mesh = teapotMesh(scene);
    constexpr int kDirections = 400;
    float worst = 1.0f;
    for (int k = 0; k < kDirections; ++k) {
        // Fibonacci points on the sphere: evenly spread, deterministic.
        const float y = 1.0f - 2.0f * (float(k) + 0.5f) / kDirections;
        const float r = std::sqrt(1.0f - y * y), phi = float(k) * 2.39996323f;
        const glm::vec3 d(r * std::cos(phi), y, r * std::sin(phi));
        std::size_t best = 0;
        for (std::size_t v = 1; v < mesh.positions.size(); ++v) {
            if (glm::dot(mesh.positions[v], d) > glm::dot(mesh.positions[best], d)) best = v;
        }
        // Not 1: where the farthest vertex is on an open edge (the spout's mouth, whose lip curls
        // over, for directions near +X) the normal leans away from the direction, but not past 90°.
        const float agreement = glm::dot(mesh.normals[best], d);
        worst = std::min(worst, agreement);
        EXPECT_GT(agreement, 0.0f) << "direction " << d.x << ", " << d.y << ", " << d.z << " reaches vertex "
                                   << best;
    }
    std::printf("teapot: the farthest vertices' normals are all within %.1f degrees of their directions\n",
                glm::degrees(std::acos(worst)));
}

TEST(Teapot, StandsUprightCentredWithTheSpoutToPlusX) {
    const Scene scene = loadTeapot("teapot.gltf");
    const Mesh& mesh = teapotMesh(scene);
    const glm::vec3 centre = 0.5f * (scene.bounds_min + scene.bounds_max);
    const glm::vec3 size = scene.bounds_max - scene.bounds_min;
    EXPECT_LT(glm::length(centre), 1e-5f);
    float farthest = 0.0f;
    for (const auto& p : mesh.positions) farthest = std::max(farthest, glm::length(p));
    EXPECT_NEAR(farthest, kRadius, 1e-5f);
    // Newell's pot is about 6.4 wide from handle to spout, 4 deep and 3.15 tall (spout mouth and
    // handle are sampled, not their exact extremes, hence the tolerance).
    const float unit = size.y / 3.15f;
    EXPECT_NEAR(size.z, 4.0f * unit, 0.01f);
    EXPECT_NEAR(size.x, 6.43f * unit, 0.05f);

    const auto extreme = [&](auto better) {
        return static_cast<std::size_t>(
            std::max_element(mesh.positions.begin(), mesh.positions.end(), better) - mesh.positions.begin());
    };
    const std::size_t top = extreme([](const glm::vec3& a, const glm::vec3& b) { return a.y < b.y; });
    const std::size_t bottom = extreme([](const glm::vec3& a, const glm::vec3& b) { return a.y > b.y; });
    const std::size_t spout = extreme([](const glm::vec3& a, const glm::vec3& b) { return a.x < b.x; });
    const std::size_t handle = extreme([](const glm::vec3& a, const glm::vec3& b) { return a.x > b.x; });
    // The knob's top and the bottom's centre lie on the vertical axis, which the spout moves off
    // the box centre towards -X; their normals are the axis (the collapsed patch edges).
    const glm::vec3 axis_top = mesh.positions[top], axis_bottom = mesh.positions[bottom];
    EXPECT_NEAR(axis_top.x, axis_bottom.x, 1e-6f);
    EXPECT_LT(axis_top.x, 0.0f);
    EXPECT_NEAR(axis_top.z, 0.0f, 1e-6f);
    EXPECT_NEAR(axis_bottom.z, 0.0f, 1e-6f);
    EXPECT_GT(mesh.normals[top].y, 0.99999f);
    EXPECT_LT(mesh.normals[bottom].y, -0.99999f);
    // The spout's mouth is high on the +X side, the handle's back on the -X side at mid height.
    EXPECT_GT(mesh.positions[spout].y, 0.25f * size.y);
    EXPECT_NEAR(mesh.positions[spout].z, 0.0f, 0.1f * size.z);
    EXPECT_NEAR(mesh.positions[handle].z, 0.0f, 0.1f * size.z);
    EXPECT_LT(mesh.normals[handle].x, -0.9f);
}

// Welded seams: any two vertices at (nearly) the same place must be a crease, their normals
// further apart than the weld angle. A pair with close normals would be an unwelded seam, which
// an inverted-hull outline (vertices pushed out along their normals) would tear open.
TEST(Teapot, PatchSeamsAreWeldedAndOnlyCreasesKeepTwoVertices) {
    const Scene scene = loadTeapot("teapot.gltf");
    const Mesh& mesh = teapotMesh(scene);
    std::vector<std::size_t> order(mesh.positions.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t b) { return mesh.positions[a].x < mesh.positions[b].x; });
    constexpr float kNear = 1e-5f;
    std::size_t coincident = 0;
    float smallest_crease_deg = 180.0f;
    for (std::size_t i = 0; i < order.size(); ++i) {
        for (std::size_t j = i + 1;
             j < order.size() && mesh.positions[order[j]].x - mesh.positions[order[i]].x <= kNear; ++j) {
            const std::size_t a = order[i], b = order[j];
            if (glm::length(mesh.positions[a] - mesh.positions[b]) > kNear) continue;
            // A copy for the texture wrap: same normal, s one further.
            if (mesh.normals[a] == mesh.normals[b] &&
                std::abs(std::abs(mesh.texcoords[a].x - mesh.texcoords[b].x) - 1.0f) < 1e-6f)
                continue;
            const float cosine = std::clamp(glm::dot(mesh.normals[a], mesh.normals[b]), -1.0f, 1.0f);
            const float angle = glm::degrees(std::acos(cosine));
            ++coincident;
            smallest_crease_deg = std::min(smallest_crease_deg, angle);
            EXPECT_GT(angle, kWeldAngleDeg)
                << "vertices " << a << " and " << b << " at " << mesh.positions[a].x << ", "
                << mesh.positions[a].y << ", " << mesh.positions[a].z;
        }
    }
    std::printf(
        "teapot: %zu coincident vertex pairs; the smallest angle between their normals is %.1f degrees\n",
        coincident, smallest_crease_deg);

    // Pushing every vertex out along its normal keeps every interior edge shared by the same
    // two triangles: the offset surface has exactly as many open edges as the pot itself.
    const auto openEdges = [&](const std::vector<glm::vec3>& positions) {
        std::vector<std::array<float, 6>> edges;
        for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
            for (int k = 0; k < 3; ++k) {
                glm::vec3 a = positions[mesh.indices[t + static_cast<std::size_t>(k)]];
                glm::vec3 b = positions[mesh.indices[t + static_cast<std::size_t>((k + 1) % 3)]];
                if (std::tie(b.x, b.y, b.z) < std::tie(a.x, a.y, a.z)) std::swap(a, b);
                edges.push_back({a.x, a.y, a.z, b.x, b.y, b.z});
            }
        }
        std::sort(edges.begin(), edges.end());
        std::size_t open = 0;
        for (std::size_t i = 0; i < edges.size();) {
            std::size_t j = i;
            while (j < edges.size() && edges[j] == edges[i]) ++j;
            if (j - i == 1) ++open;
            i = j;
        }
        return open;
    };
    std::vector<glm::vec3> pushed(mesh.positions.size());
    for (std::size_t v = 0; v < pushed.size(); ++v) pushed[v] = mesh.positions[v] + 0.02f * mesh.normals[v];
    const std::size_t open = openEdges(mesh.positions);
    EXPECT_EQ(openEdges(pushed), open);
    // Only the data's openings, loops of 11-segment patch edges: both ends of the spout and of the
    // handle (2 edges each), the rim's inner edge and the lid's edge (4 each).
    EXPECT_EQ(open, (4u * 2u + 2u * 4u) * 11u);
    std::printf("teapot: %zu open edges\n", open);
}

TEST(TeapotOnPlane, StandsOnTheGroundWithAPointAndADirectionalLight) {
    const Scene scene = loadTeapot("teapot_on_plane.gltf");
    ASSERT_EQ(scene.draw_items.size(), 2u);
    ASSERT_EQ(scene.lights.size(), 2u);
    EXPECT_EQ(scene.lights[0].type, LightType::Point);
    EXPECT_EQ(scene.lights[1].type, LightType::Directional);
    // The ground is the plane at y = 0; the pot's lowest point touches it.
    EXPECT_FLOAT_EQ(scene.bounds_min.y, 0.0f);
    const Mesh& pot = teapotMesh(scene);
    const auto& item = *std::find_if(scene.draw_items.begin(), scene.draw_items.end(),
                                     [](const auto& d) { return d.node_name == "teapot"; });
    float lowest = 1e9f, highest = -1e9f;
    for (const auto& p : pot.positions) {
        const float y = (item.world * glm::vec4(p, 1.0f)).y;
        lowest = std::min(lowest, y);
        highest = std::max(highest, y);
    }
    EXPECT_NEAR(lowest, 0.0f, 1e-6f);
    EXPECT_GE(lowest, -1e-6f);
    EXPECT_GT(highest, 1.0f);
    // The same teapot as teapot.gltf, moved up.
    const Scene alone = loadTeapot("teapot.gltf");
    EXPECT_EQ(pot.positions, teapotMesh(alone).positions);
    EXPECT_EQ(pot.indices, teapotMesh(alone).indices);
}

}  // namespace
