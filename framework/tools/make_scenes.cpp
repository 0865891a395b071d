// shaderlab_make_scenes <out_dir>: writes the glTF 2.0 scenes bundled in labs/scenes/.
// shaderlab_make_scenes --lab-assets <labs_dir>: writes the labs' own generated assets into
// <labs_dir>/<id>/assets/ (lab_assets.cpp: normal maps and meshes with tangents).
//
// Every mesh is built procedurally here (positions, normals, texcoords, indices) and written
// with tinygltf's writer (scene_writer.h), so the committed scenes can be regenerated and diffed
// (scripts/regenerate_scenes.sh; tests/scenes_fresh_test.cpp and tests/lab_assets_test.cpp fail
// when they are stale). The output is deterministic: no timestamps, geometry computed in double
// and rounded once to float, JSON keys sorted by the writer.
// Each scene has a perspective camera node and a KHR_lights_punctual point light. The scenes
// exercise the loader on purpose: all three index component types, an interleaved bufferView
// with byteStride (torus), a .glb (torus_knot), a mesh without NORMAL (cube_no_normals), a
// non-uniform node scale (nonuniform_scale). The Utah teapot (teapot, teapot_on_plane) is
// tessellated from Newell's Bezier patches and welded along their seams.
// The bundled scenes carry no textures; animations and anything the labs do not draw are never
// written.
#include <array>
#include <map>

#include "lab_assets.h"
#include "scene_writer.h"

namespace shaderlab::scenegen {
namespace {

// Torus in the XZ plane (hole along Y), so a camera slightly above sees into the hole.
Geometry torus(double major, double minor, int segments, int sides) {
    Geometry g;
    for (int i = 0; i <= segments; ++i) {
        const double u = 2.0 * kPi * i / segments;
        for (int j = 0; j <= sides; ++j) {
            const double v = 2.0 * kPi * j / sides;
            const glm::dvec3 n(std::cos(v) * std::cos(u), std::sin(v), std::cos(v) * std::sin(u));
            const glm::dvec3 centre(major * std::cos(u), 0.0, major * std::sin(u));
            g.vertices.push_back(
                {centre + minor * n, n, glm::dvec2(double(i) / segments, double(j) / sides)});
        }
    }
    addGridTriangles(&g, segments, sides, false);
    return g;
}

// A tube around the (p, q) torus knot, framed with the curve's Frenet frame (the curvature of a
// torus knot never vanishes, so the frame is defined everywhere). Derivatives are analytic.
Geometry torusKnot(int p, int q, double scale, double tube, int segments, int sides) {
    Geometry g;
    for (int i = 0; i <= segments; ++i) {
        const double t = 2.0 * kPi * i / segments;
        const double cq = std::cos(q * t), sq = std::sin(q * t), cp = std::cos(p * t), sp = std::sin(p * t);
        const double r = 2.0 + cq;
        // The knot winds around the Z axis, so it faces a camera on +Z.
        const glm::dvec3 pos(r * cp, r * sp, sq);
        const glm::dvec3 d1(-q * sq * cp - p * r * sp, -q * sq * sp + p * r * cp, q * cq);
        const glm::dvec3 d2(-q * q * cq * cp + 2.0 * p * q * sq * sp - p * p * r * cp,
                            -q * q * cq * sp - 2.0 * p * q * sq * cp - p * p * r * sp, -q * q * sq);
        const glm::dvec3 tangent = glm::normalize(d1);
        const glm::dvec3 binormal = glm::normalize(glm::cross(d1, d2));
        const glm::dvec3 normal = glm::cross(binormal, tangent);
        for (int j = 0; j <= sides; ++j) {
            const double v = 2.0 * kPi * j / sides;
            const glm::dvec3 n = std::cos(v) * normal + std::sin(v) * binormal;
            g.vertices.push_back(
                {scale * pos + tube * n, n, glm::dvec2(double(i) / segments, double(j) / sides)});
        }
    }
    addGridTriangles(&g, segments, sides, false);
    return g;
}

// Unit cube centred on the origin: 4 vertices per face so each face has its own flat normal.
Geometry cube(double size) {
    Geometry g;
    const glm::dvec3 axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (int axis = 0; axis < 3; ++axis) {
        for (double sign : {1.0, -1.0}) {
            const glm::dvec3 n = sign * axes[axis];
            const glm::dvec3 u = axes[(axis + 1) % 3];
            const glm::dvec3 v = axes[(axis + 2) % 3];
            const auto base = static_cast<std::uint32_t>(g.vertices.size());
            const double corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
            for (const auto& c : corners) {
                const glm::dvec3 pos = 0.5 * size * (n + c[0] * u + c[1] * v);
                g.vertices.push_back({pos, n, glm::dvec2(0.5 * (c[0] + 1.0), 0.5 * (1.0 - c[1]))});
            }
            g.indices.insert(g.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
        }
    }
    orientTriangles(&g);
    return g;
}

// Square in the XZ plane facing +Y, subdivided so per-vertex lighting has vertices to work with.
Geometry plane(double size, int cells) {
    Geometry g;
    for (int i = 0; i <= cells; ++i) {
        for (int j = 0; j <= cells; ++j) {
            const double x = size * (double(j) / cells - 0.5);
            const double z = size * (double(i) / cells - 0.5);
            g.vertices.push_back({{x, 0.0, z}, {0.0, 1.0, 0.0}, {double(j) / cells, double(i) / cells}});
        }
    }
    addGridTriangles(&g, cells, cells, false);
    return g;
}

// Martin Newell's teapot (1975): 306 control points and 32 bicubic Bezier patches of 16 of them,
// z up, in Newell's units, as published by Frank Crow, "The Origins of the Teapot", IEEE Computer
// Graphics and Applications 7(1), 1987. The patch table keeps the published one-based point
// numbers so it can be checked against that listing; points 205, 206, 216 and 223 are listed
// there but used by no patch. The four bottom patches were added after Newell (his teapot had
// no bottom).
// clang-format off
constexpr double kTeapotPoints[306][3] = {
    // rim
    {1.4, 0.0, 2.4}, {1.4, -0.784, 2.4}, {0.784, -1.4, 2.4}, {0.0, -1.4, 2.4},
    {1.3375, 0.0, 2.53125}, {1.3375, -0.749, 2.53125}, {0.749, -1.3375, 2.53125}, {0.0, -1.3375, 2.53125},
    {1.4375, 0.0, 2.53125}, {1.4375, -0.805, 2.53125}, {0.805, -1.4375, 2.53125}, {0.0, -1.4375, 2.53125},
    {1.5, 0.0, 2.4}, {1.5, -0.84, 2.4}, {0.84, -1.5, 2.4}, {0.0, -1.5, 2.4},
    {-0.784, -1.4, 2.4}, {-1.4, -0.784, 2.4}, {-1.4, 0.0, 2.4}, {-0.749, -1.3375, 2.53125},
    {-1.3375, -0.749, 2.53125}, {-1.3375, 0.0, 2.53125}, {-0.805, -1.4375, 2.53125}, {-1.4375, -0.805, 2.53125},
    {-1.4375, 0.0, 2.53125}, {-0.84, -1.5, 2.4}, {-1.5, -0.84, 2.4}, {-1.5, 0.0, 2.4},
    {-1.4, 0.784, 2.4}, {-0.784, 1.4, 2.4}, {0.0, 1.4, 2.4}, {-1.3375, 0.749, 2.53125},
    {-0.749, 1.3375, 2.53125}, {0.0, 1.3375, 2.53125}, {-1.4375, 0.805, 2.53125}, {-0.805, 1.4375, 2.53125},
    {0.0, 1.4375, 2.53125}, {-1.5, 0.84, 2.4}, {-0.84, 1.5, 2.4}, {0.0, 1.5, 2.4},
    {0.784, 1.4, 2.4}, {1.4, 0.784, 2.4}, {0.749, 1.3375, 2.53125}, {1.3375, 0.749, 2.53125},
    {0.805, 1.4375, 2.53125}, {1.4375, 0.805, 2.53125}, {0.84, 1.5, 2.4}, {1.5, 0.84, 2.4},
    // body (from 49)
    {1.75, 0.0, 1.875}, {1.75, -0.98, 1.875}, {0.98, -1.75, 1.875}, {0.0, -1.75, 1.875},
    {2.0, 0.0, 1.35}, {2.0, -1.12, 1.35}, {1.12, -2.0, 1.35}, {0.0, -2.0, 1.35},
    {2.0, 0.0, 0.9}, {2.0, -1.12, 0.9}, {1.12, -2.0, 0.9}, {0.0, -2.0, 0.9},
    {-0.98, -1.75, 1.875}, {-1.75, -0.98, 1.875}, {-1.75, 0.0, 1.875}, {-1.12, -2.0, 1.35},
    {-2.0, -1.12, 1.35}, {-2.0, 0.0, 1.35}, {-1.12, -2.0, 0.9}, {-2.0, -1.12, 0.9},
    {-2.0, 0.0, 0.9}, {-1.75, 0.98, 1.875}, {-0.98, 1.75, 1.875}, {0.0, 1.75, 1.875},
    {-2.0, 1.12, 1.35}, {-1.12, 2.0, 1.35}, {0.0, 2.0, 1.35}, {-2.0, 1.12, 0.9},
    {-1.12, 2.0, 0.9}, {0.0, 2.0, 0.9}, {0.98, 1.75, 1.875}, {1.75, 0.98, 1.875},
    {1.12, 2.0, 1.35}, {2.0, 1.12, 1.35}, {1.12, 2.0, 0.9}, {2.0, 1.12, 0.9},
    {2.0, 0.0, 0.45}, {2.0, -1.12, 0.45}, {1.12, -2.0, 0.45}, {0.0, -2.0, 0.45},
    {1.5, 0.0, 0.225}, {1.5, -0.84, 0.225}, {0.84, -1.5, 0.225}, {0.0, -1.5, 0.225},
    {1.5, 0.0, 0.15}, {1.5, -0.84, 0.15}, {0.84, -1.5, 0.15}, {0.0, -1.5, 0.15},
    {-1.12, -2.0, 0.45}, {-2.0, -1.12, 0.45}, {-2.0, 0.0, 0.45}, {-0.84, -1.5, 0.225},
    {-1.5, -0.84, 0.225}, {-1.5, 0.0, 0.225}, {-0.84, -1.5, 0.15}, {-1.5, -0.84, 0.15},
    {-1.5, 0.0, 0.15}, {-2.0, 1.12, 0.45}, {-1.12, 2.0, 0.45}, {0.0, 2.0, 0.45},
    {-1.5, 0.84, 0.225}, {-0.84, 1.5, 0.225}, {0.0, 1.5, 0.225}, {-1.5, 0.84, 0.15},
    {-0.84, 1.5, 0.15}, {0.0, 1.5, 0.15}, {1.12, 2.0, 0.45}, {2.0, 1.12, 0.45},
    {0.84, 1.5, 0.225}, {1.5, 0.84, 0.225}, {0.84, 1.5, 0.15}, {1.5, 0.84, 0.15},
    // handle (from 121)
    {-1.6, 0.0, 2.025}, {-1.6, -0.3, 2.025}, {-1.5, -0.3, 2.25}, {-1.5, 0.0, 2.25},
    {-2.3, 0.0, 2.025}, {-2.3, -0.3, 2.025}, {-2.5, -0.3, 2.25}, {-2.5, 0.0, 2.25},
    {-2.7, 0.0, 2.025}, {-2.7, -0.3, 2.025}, {-3.0, -0.3, 2.25}, {-3.0, 0.0, 2.25},
    {-2.7, 0.0, 1.8}, {-2.7, -0.3, 1.8}, {-3.0, -0.3, 1.8}, {-3.0, 0.0, 1.8},
    {-1.5, 0.3, 2.25}, {-1.6, 0.3, 2.025}, {-2.5, 0.3, 2.25}, {-2.3, 0.3, 2.025},
    {-3.0, 0.3, 2.25}, {-2.7, 0.3, 2.025}, {-3.0, 0.3, 1.8}, {-2.7, 0.3, 1.8},
    {-2.7, 0.0, 1.575}, {-2.7, -0.3, 1.575}, {-3.0, -0.3, 1.35}, {-3.0, 0.0, 1.35},
    {-2.5, 0.0, 1.125}, {-2.5, -0.3, 1.125}, {-2.65, -0.3, 0.9375}, {-2.65, 0.0, 0.9375},
    {-2.0, -0.3, 0.9}, {-1.9, -0.3, 0.6}, {-1.9, 0.0, 0.6}, {-3.0, 0.3, 1.35},
    {-2.7, 0.3, 1.575}, {-2.65, 0.3, 0.9375}, {-2.5, 0.3, 1.125}, {-1.9, 0.3, 0.6},
    {-2.0, 0.3, 0.9},
    // spout (from 162)
    {1.7, 0.0, 1.425}, {1.7, -0.66, 1.425}, {1.7, -0.66, 0.6},
    {1.7, 0.0, 0.6}, {2.6, 0.0, 1.425}, {2.6, -0.66, 1.425}, {3.1, -0.66, 0.825},
    {3.1, 0.0, 0.825}, {2.3, 0.0, 2.1}, {2.3, -0.25, 2.1}, {2.4, -0.25, 2.025},
    {2.4, 0.0, 2.025}, {2.7, 0.0, 2.4}, {2.7, -0.25, 2.4}, {3.3, -0.25, 2.4},
    {3.3, 0.0, 2.4}, {1.7, 0.66, 0.6}, {1.7, 0.66, 1.425}, {3.1, 0.66, 0.825},
    {2.6, 0.66, 1.425}, {2.4, 0.25, 2.025}, {2.3, 0.25, 2.1}, {3.3, 0.25, 2.4},
    {2.7, 0.25, 2.4}, {2.8, 0.0, 2.475}, {2.8, -0.25, 2.475}, {3.525, -0.25, 2.49375},
    {3.525, 0.0, 2.49375}, {2.9, 0.0, 2.475}, {2.9, -0.15, 2.475}, {3.45, -0.15, 2.5125},
    {3.45, 0.0, 2.5125}, {2.8, 0.0, 2.4}, {2.8, -0.15, 2.4}, {3.2, -0.15, 2.4},
    {3.2, 0.0, 2.4}, {3.525, 0.25, 2.49375}, {2.8, 0.25, 2.475}, {3.45, 0.15, 2.5125},
    {2.9, 0.15, 2.475}, {3.2, 0.15, 2.4}, {2.8, 0.15, 2.4},
    // lid (from 204)
    {0.0, 0.0, 3.15}, {0.0, -0.002, 3.15}, {0.002, 0.0, 3.15}, {0.8, 0.0, 3.15},
    {0.8, -0.45, 3.15}, {0.45, -0.8, 3.15}, {0.0, -0.8, 3.15}, {0.0, 0.0, 2.85},
    {0.2, 0.0, 2.7}, {0.2, -0.112, 2.7}, {0.112, -0.2, 2.7}, {0.0, -0.2, 2.7},
    {-0.002, 0.0, 3.15}, {-0.45, -0.8, 3.15}, {-0.8, -0.45, 3.15}, {-0.8, 0.0, 3.15},
    {-0.112, -0.2, 2.7}, {-0.2, -0.112, 2.7}, {-0.2, 0.0, 2.7}, {0.0, 0.002, 3.15},
    {-0.8, 0.45, 3.15}, {-0.45, 0.8, 3.15}, {0.0, 0.8, 3.15}, {-0.2, 0.112, 2.7},
    {-0.112, 0.2, 2.7}, {0.0, 0.2, 2.7}, {0.45, 0.8, 3.15}, {0.8, 0.45, 3.15},
    {0.112, 0.2, 2.7}, {0.2, 0.112, 2.7}, {0.4, 0.0, 2.55}, {0.4, -0.224, 2.55},
    {0.224, -0.4, 2.55}, {0.0, -0.4, 2.55}, {1.3, 0.0, 2.55}, {1.3, -0.728, 2.55},
    {0.728, -1.3, 2.55}, {0.0, -1.3, 2.55}, {1.3, 0.0, 2.4}, {1.3, -0.728, 2.4},
    {0.728, -1.3, 2.4}, {0.0, -1.3, 2.4}, {-0.224, -0.4, 2.55}, {-0.4, -0.224, 2.55},
    {-0.4, 0.0, 2.55}, {-0.728, -1.3, 2.55}, {-1.3, -0.728, 2.55}, {-1.3, 0.0, 2.55},
    {-0.728, -1.3, 2.4}, {-1.3, -0.728, 2.4}, {-1.3, 0.0, 2.4}, {-0.4, 0.224, 2.55},
    {-0.224, 0.4, 2.55}, {0.0, 0.4, 2.55}, {-1.3, 0.728, 2.55}, {-0.728, 1.3, 2.55},
    {0.0, 1.3, 2.55}, {-1.3, 0.728, 2.4}, {-0.728, 1.3, 2.4}, {0.0, 1.3, 2.4},
    {0.224, 0.4, 2.55}, {0.4, 0.224, 2.55}, {0.728, 1.3, 2.55}, {1.3, 0.728, 2.55},
    {0.728, 1.3, 2.4}, {1.3, 0.728, 2.4},
    // bottom (from 270)
    {0.0, 0.0, 0.0}, {1.5, 0.0, 0.15},
    {1.5, 0.84, 0.15}, {0.84, 1.5, 0.15}, {0.0, 1.5, 0.15}, {1.5, 0.0, 0.075},
    {1.5, 0.84, 0.075}, {0.84, 1.5, 0.075}, {0.0, 1.5, 0.075}, {1.425, 0.0, 0.0},
    {1.425, 0.798, 0.0}, {0.798, 1.425, 0.0}, {0.0, 1.425, 0.0}, {-0.84, 1.5, 0.15},
    {-1.5, 0.84, 0.15}, {-1.5, 0.0, 0.15}, {-0.84, 1.5, 0.075}, {-1.5, 0.84, 0.075},
    {-1.5, 0.0, 0.075}, {-0.798, 1.425, 0.0}, {-1.425, 0.798, 0.0}, {-1.425, 0.0, 0.0},
    {-1.5, -0.84, 0.15}, {-0.84, -1.5, 0.15}, {0.0, -1.5, 0.15}, {-1.5, -0.84, 0.075},
    {-0.84, -1.5, 0.075}, {0.0, -1.5, 0.075}, {-1.425, -0.798, 0.0}, {-0.798, -1.425, 0.0},
    {0.0, -1.425, 0.0}, {0.84, -1.5, 0.15}, {1.5, -0.84, 0.15}, {0.84, -1.5, 0.075},
    {1.5, -0.84, 0.075}, {0.798, -1.425, 0.0}, {1.425, -0.798, 0.0},
};

// Each patch's 4 x 4 control points, row by row (one-based, as published).
constexpr int kTeapotPatches[32][16] = {
    // rim
    {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16},
    {4, 17, 18, 19, 8, 20, 21, 22, 12, 23, 24, 25, 16, 26, 27, 28},
    {19, 29, 30, 31, 22, 32, 33, 34, 25, 35, 36, 37, 28, 38, 39, 40},
    {31, 41, 42, 1, 34, 43, 44, 5, 37, 45, 46, 9, 40, 47, 48, 13},
    // body
    {13, 14, 15, 16, 49, 50, 51, 52, 53, 54, 55, 56, 57, 58, 59, 60},
    {16, 26, 27, 28, 52, 61, 62, 63, 56, 64, 65, 66, 60, 67, 68, 69},
    {28, 38, 39, 40, 63, 70, 71, 72, 66, 73, 74, 75, 69, 76, 77, 78},
    {40, 47, 48, 13, 72, 79, 80, 49, 75, 81, 82, 53, 78, 83, 84, 57},
    {57, 58, 59, 60, 85, 86, 87, 88, 89, 90, 91, 92, 93, 94, 95, 96},
    {60, 67, 68, 69, 88, 97, 98, 99, 92, 100, 101, 102, 96, 103, 104, 105},
    {69, 76, 77, 78, 99, 106, 107, 108, 102, 109, 110, 111, 105, 112, 113, 114},
    {78, 83, 84, 57, 108, 115, 116, 85, 111, 117, 118, 89, 114, 119, 120, 93},
    // handle
    {121, 122, 123, 124, 125, 126, 127, 128, 129, 130, 131, 132, 133, 134, 135, 136},
    {124, 137, 138, 121, 128, 139, 140, 125, 132, 141, 142, 129, 136, 143, 144, 133},
    {133, 134, 135, 136, 145, 146, 147, 148, 149, 150, 151, 152, 69, 153, 154, 155},
    {136, 143, 144, 133, 148, 156, 157, 145, 152, 158, 159, 149, 155, 160, 161, 69},
    // spout
    {162, 163, 164, 165, 166, 167, 168, 169, 170, 171, 172, 173, 174, 175, 176, 177},
    {165, 178, 179, 162, 169, 180, 181, 166, 173, 182, 183, 170, 177, 184, 185, 174},
    {174, 175, 176, 177, 186, 187, 188, 189, 190, 191, 192, 193, 194, 195, 196, 197},
    {177, 184, 185, 174, 189, 198, 199, 186, 193, 200, 201, 190, 197, 202, 203, 194},
    // lid
    {204, 204, 204, 204, 207, 208, 209, 210, 211, 211, 211, 211, 212, 213, 214, 215},
    {204, 204, 204, 204, 210, 217, 218, 219, 211, 211, 211, 211, 215, 220, 221, 222},
    {204, 204, 204, 204, 219, 224, 225, 226, 211, 211, 211, 211, 222, 227, 228, 229},
    {204, 204, 204, 204, 226, 230, 231, 207, 211, 211, 211, 211, 229, 232, 233, 212},
    {212, 213, 214, 215, 234, 235, 236, 237, 238, 239, 240, 241, 242, 243, 244, 245},
    {215, 220, 221, 222, 237, 246, 247, 248, 241, 249, 250, 251, 245, 252, 253, 254},
    {222, 227, 228, 229, 248, 255, 256, 257, 251, 258, 259, 260, 254, 261, 262, 263},
    {229, 232, 233, 212, 257, 264, 265, 234, 260, 266, 267, 238, 263, 268, 269, 242},
    // bottom
    {270, 270, 270, 270, 279, 280, 281, 282, 275, 276, 277, 278, 271, 272, 273, 274},
    {270, 270, 270, 270, 282, 289, 290, 291, 278, 286, 287, 288, 274, 283, 284, 285},
    {270, 270, 270, 270, 291, 298, 299, 300, 288, 295, 296, 297, 285, 292, 293, 294},
    {270, 270, 270, 270, 300, 305, 306, 279, 297, 303, 304, 275, 294, 301, 302, 271},
};
// clang-format on

// Cubic Bernstein weights and their derivatives at t, given s = 1 - t as well. Grid samples pass
// t = i / n and s = (n - i) / n, both exact ratios, so the weights at (n - i) / n are those at
// i / n reversed, bit for bit: two patches that run along a shared edge in opposite directions
// then compute identical seam points, which the weld in teapot() relies on.
struct Cubic {
    double b[4];
    double d[4];
};

Cubic bernstein(double t, double s) {
    const double ts = t * s;
    return {{s * s * s, 3.0 * ts * s, 3.0 * ts * t, t * t * t},
            {-3.0 * s * s, 3.0 * s * s - 6.0 * ts, 6.0 * ts - 3.0 * t * t, 3.0 * t * t}};
}

// w[0] p[0] + ... + w[3] p[3], summed in an order that reversing both arrays does not change.
glm::dvec3 blend(const double w[4], const glm::dvec3 p[4]) {
    return (w[0] * p[0] + w[3] * p[3]) + (w[1] * p[1] + w[2] * p[2]);
}

struct PatchPoint {
    glm::dvec3 position, du, dv;
};

// The bicubic patch at (u, v): u runs down the rows of the 4 x 4 control net, v along them.
PatchPoint evalPatch(const glm::dvec3 (&net)[4][4], const Cubic& u, const Cubic& v) {
    glm::dvec3 row[4], row_dv[4];
    for (int i = 0; i < 4; ++i) {
        const auto& p = net[i];
        // A row of four equal points (the collapsed edge at the lid's top and the bottom's centre)
        // must give that point exactly, not a rounding of it that differs with v.
        row[i] = p[0] == p[1] && p[1] == p[2] && p[2] == p[3] ? p[0] : blend(v.b, p);
        row_dv[i] = blend(v.d, p);
    }
    return {blend(u.b, row), blend(u.d, row), blend(u.b, row_dv)};
}

// Newell's patches all wind the same way (each shared edge is G1 and runs consistently), with
// dP/du x dP/dv pointing into the pot, so the outward normal is dP/dv x dP/du. Returns false
// where that is undefined: where one patch edge collapses to a point (the lid's top, the
// bottom's centre) dP/dv vanishes.
bool outwardNormal(const PatchPoint& p, glm::dvec3* normal) {
    const glm::dvec3 n = glm::cross(p.dv, p.du);
    const double scale = glm::dot(p.du, p.du) + glm::dot(p.dv, p.dv);
    if (!(glm::dot(n, n) > 1e-20 * scale * scale)) return false;
    *normal = glm::normalize(n);
    return true;
}

// The Utah teapot standing on +Y with the spout towards +X, its bounding box centred on the
// origin and its farthest vertex `radius` from it. Each patch is sampled on an (n + 1) x (n + 1)
// grid. Vertices the patches share along their seams (equal float positions, normals within
// kWeldAngle) are welded into one with the mean normal, so that pushing vertices out along their
// normals (an inverted-hull outline) cannot open cracks along the seams; equal positions with
// normals further apart (where the handle's end meets the body) stay separate, a crease.
// Texcoords are a cylindrical map around the pot's axis, s = angle (0.5 facing +Z, wrapping at
// -Z, the back; triangles across the wrap use vertex copies at s + 1) and t = 0 at the lid's top
// to 1 at the bottom: it depends on the position only, so welded vertices agree on it, which
// per-patch (u, v) would not.
// The data itself leaves openings, kept as they are: the spout's mouth, the ends of the spout and
// the handle (inside the body), and a gap between the lid (radius 1.3) and the rim (1.4). With
// back-face culling the background shows through the last two.
Geometry teapot(int n, double radius) {
    constexpr double kWeldAngle = 20.0 * kPi / 180.0;
    Geometry raw;
    for (const auto& patch : kTeapotPatches) {
        glm::dvec3 net[4][4];
        for (int k = 0; k < 16; ++k) {
            const double* p = kTeapotPoints[patch[k] - 1];
            // Newell's z up turned into +Y up by a quarter turn about X (not an axis swap, which
            // would mirror the pot); his spout already points to +X.
            net[k / 4][k % 4] = glm::dvec3(p[0], p[2], -p[1]);
        }
        const auto base = static_cast<std::uint32_t>(raw.vertices.size());
        for (int i = 0; i <= n; ++i) {
            const double u = double(i) / n;
            for (int j = 0; j <= n; ++j) {
                const double v = double(j) / n;
                const PatchPoint p =
                    evalPatch(net, bernstein(u, double(n - i) / n), bernstein(v, double(n - j) / n));
                glm::dvec3 normal;
                if (!outwardNormal(p, &normal)) {
                    // A hair inside the patch it is defined, and within about 1e-6 rad of its limit.
                    const double uu = u < 0.5 ? u + 1e-6 : u - 1e-6, vv = v < 0.5 ? v + 1e-6 : v - 1e-6;
                    if (!outwardNormal(evalPatch(net, bernstein(uu, 1.0 - uu), bernstein(vv, 1.0 - vv)),
                                       &normal)) {
                        std::fprintf(stderr, "shaderlab_make_scenes: teapot normal undefined\n");
                        std::exit(1);
                    }
                }
                const glm::dvec3& q = p.position;
                const glm::dvec2 uv(0.5 + std::atan2(q.x, q.z) / (2.0 * kPi), 1.0 - q.y / 3.15);
                raw.vertices.push_back({q, normal, uv});
            }
        }
        const auto at = [base, n](int i, int j) {
            return base + static_cast<std::uint32_t>(i * (n + 1) + j);
        };
        for (int i = 0; i < n; ++i) {
            for (int j = 0; j < n; ++j) {
                raw.indices.insert(raw.indices.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1)});
                raw.indices.insert(raw.indices.end(), {at(i, j), at(i + 1, j + 1), at(i, j + 1)});
            }
        }
    }

    glm::dvec3 lo(std::numeric_limits<double>::max()), hi(std::numeric_limits<double>::lowest());
    for (const Vertex& v : raw.vertices) {
        lo = glm::min(lo, v.position);
        hi = glm::max(hi, v.position);
    }
    const glm::dvec3 centre = 0.5 * (lo + hi);
    double farthest = 0.0;
    for (const Vertex& v : raw.vertices) farthest = std::max(farthest, glm::length(v.position - centre));
    for (Vertex& v : raw.vertices) v.position = (v.position - centre) * (radius / farthest);

    // The weld, in vertex order so the output is deterministic: each vertex joins the first
    // welded vertex at its float position whose mean normal is within kWeldAngle of its own.
    const auto key = [](const glm::dvec3& p) {
        return std::array<float, 3>{static_cast<float>(p.x), static_cast<float>(p.y),
                                    static_cast<float>(p.z)};
    };
    Geometry g;
    std::map<std::array<float, 3>, std::vector<std::uint32_t>> at_position;
    std::vector<std::uint32_t> welded(raw.vertices.size());
    for (std::size_t i = 0; i < raw.vertices.size(); ++i) {
        const Vertex& v = raw.vertices[i];
        std::vector<std::uint32_t>& candidates = at_position[key(v.position)];
        auto joined = std::find_if(candidates.begin(), candidates.end(), [&](std::uint32_t w) {
            return glm::dot(glm::normalize(g.vertices[w].normal), v.normal) > std::cos(kWeldAngle);
        });
        if (joined == candidates.end()) {
            candidates.push_back(static_cast<std::uint32_t>(g.vertices.size()));
            g.vertices.push_back(v);
            joined = candidates.end() - 1;
        } else {
            g.vertices[*joined].normal += v.normal;
        }
        welded[i] = *joined;
    }
    for (Vertex& v : g.vertices) v.normal = glm::normalize(v.normal);

    // Triangles with two corners at one float position (one per cell beside a collapsed edge)
    // have no area and are dropped.
    for (std::size_t t = 0; t + 2 < raw.indices.size(); t += 3) {
        const std::uint32_t a = welded[raw.indices[t]], b = welded[raw.indices[t + 1]],
                            c = welded[raw.indices[t + 2]];
        const auto ka = key(g.vertices[a].position), kb = key(g.vertices[b].position),
                   kc = key(g.vertices[c].position);
        if (ka == kb || kb == kc || ka == kc) continue;
        g.indices.insert(g.indices.end(), {a, b, c});
    }
    // The cylindrical map wraps at the back, where s jumps from 1 to 0: a triangle across the
    // wrap would interpolate over the whole texture. Its corners on the s < 0.5 side use copies
    // at s + 1 (same position and normal, so an outline pushed along the normals stays closed).
    std::map<std::uint32_t, std::uint32_t> shifted;
    for (std::size_t t = 0; t + 2 < g.indices.size(); t += 3) {
        double lo_s = 1.0, hi_s = 0.0;
        for (std::size_t k = 0; k < 3; ++k) {
            lo_s = std::min(lo_s, g.vertices[g.indices[t + k]].uv.x);
            hi_s = std::max(hi_s, g.vertices[g.indices[t + k]].uv.x);
        }
        if (hi_s - lo_s <= 0.5) continue;
        for (std::size_t k = 0; k < 3; ++k) {
            const std::uint32_t i = g.indices[t + k];
            if (g.vertices[i].uv.x >= 0.5) continue;
            auto it = shifted.find(i);
            if (it == shifted.end()) {
                Vertex copy = g.vertices[i];
                copy.uv.x += 1.0;
                it = shifted.emplace(i, static_cast<std::uint32_t>(g.vertices.size())).first;
                g.vertices.push_back(copy);
            }
            g.indices[t + k] = it->second;
        }
    }
    orientTriangles(&g);
    return g;
}

// The knot used twice: alone (as .glb) and on the ground plane. 256 x 24 keeps the file small.
Geometry knot() { return torusKnot(2, 3, 0.42, 0.17, 256, 24); }

const glm::dvec3 kWhite(1.0, 1.0, 1.0);
const glm::dvec3 kKeyLight(3.0, 4.0, 5.0);  // above, right and in front of the subject

// The red sphere, finely tessellated ("sphere") and coarsely ("sphere_low_poly", 12 x 6): on the
// coarse one per-vertex (Gouraud) lighting loses or smears the highlight inside its large
// triangles, while per-fragment lighting does not.
bool writeSphere(const fs::path& dir, const std::string& name, int segments, int rings, int index_type) {
    SceneWriter w;
    const int mat = w.addMaterial("red_clay", {0.8, 0.3, 0.2, 1.0});
    w.addMeshNode("sphere",
                  w.addMesh("sphere", uvSphere(1.0, segments, rings), mat, index_type, Layout::Separate));
    w.addCamera({0.0, 0.8, 3.6}, {0.0, 0.0, 0.0});
    w.addPointLight(kKeyLight, kWhite, 1.0);
    return w.write(dir, name, false);
}

bool writeTorus(const fs::path& dir) {
    SceneWriter w;
    const int mat = w.addMaterial("teal", {0.2, 0.6, 0.8, 1.0});
    w.addMeshNode("torus", w.addMesh("torus", torus(1.0, 0.35, 64, 32), mat, kUShort, Layout::Interleaved));
    w.addCamera({0.0, 2.2, 3.2}, {0.0, 0.0, 0.0});
    w.addPointLight(kKeyLight, kWhite, 1.0);
    return w.write(dir, "torus", false);
}

bool writeTorusKnot(const fs::path& dir) {
    SceneWriter w;
    const int mat = w.addMaterial("gold", {0.9, 0.7, 0.2, 1.0});
    w.addMeshNode("torus_knot", w.addMesh("torus_knot", knot(), mat, kUInt, Layout::Separate));
    w.addCamera({0.0, 0.6, 4.4}, {0.0, 0.0, 0.0});
    w.addPointLight(kKeyLight, kWhite, 1.0);
    return w.write(dir, "torus_knot", true);
}

// The cube is turned so that three faces, each flat-shaded, face the camera.
bool writeCube(const fs::path& dir, const std::string& name, bool normals) {
    SceneWriter w;
    const int mat = w.addMaterial("green", {0.3, 0.8, 0.4, 1.0});
    Geometry g = cube(1.4);
    g.write_normals = normals;
    w.addMeshNode(name, w.addMesh(name, g, mat, kUByte, Layout::Separate));
    w.addCamera({2.2, 1.8, 2.8}, {0.0, 0.0, 0.0});
    w.addPointLight(kKeyLight, kWhite, 1.0);
    return w.write(dir, name, false);
}

// A sphere squashed by the node's scale and turned: normals transformed with the model matrix
// instead of its inverse transpose come out visibly wrong here.
bool writeNonuniformScale(const fs::path& dir) {
    SceneWriter w;
    const int mat = w.addMaterial("violet", {0.7, 0.4, 0.8, 1.0});
    const int n = w.addMeshNode("ellipsoid",
                                w.addMesh("sphere", uvSphere(1.0, 64, 32), mat, kUShort, Layout::Separate));
    w.node(n).scale = {2.0, 0.5, 1.0};
    const glm::dquat q = glm::angleAxis(25.0 * kPi / 180.0, glm::dvec3(0.0, 0.0, 1.0));
    w.node(n).rotation = {0.0, 0.0, std::round(q.z * 1e6) / 1e6, std::round(q.w * 1e6) / 1e6};
    w.addCamera({0.0, 1.0, 5.5}, {0.0, 0.0, 0.0});
    w.addPointLight(kKeyLight, kWhite, 1.0);
    return w.write(dir, "nonuniform_scale", false);
}

bool writeGroundPlane(const fs::path& dir) {
    SceneWriter w;
    const int grey = w.addMaterial("ground", {0.6, 0.6, 0.6, 1.0});
    const int gold = w.addMaterial("gold", {0.9, 0.7, 0.2, 1.0});
    w.addMeshNode("ground", w.addMesh("ground", plane(8.0, 8), grey, kUByte, Layout::Separate));
    // The knot stands upright; its lowest point is 3 * 0.42 + 0.17 = 1.43 below its centre.
    w.addMeshNode("torus_knot", w.addMesh("torus_knot", knot(), gold, kUInt, Layout::Separate),
                  {0.0, 1.45, 0.0});
    w.addCamera({0.0, 2.6, 6.5}, {0.0, 1.0, 0.0});
    w.addPointLight(kKeyLight, kWhite, 1.0);
    w.addDirectionalLight({0.3, -1.0, -0.5}, {0.4, 0.5, 0.8}, 0.5);
    return w.write(dir, "ground_plane", false);
}

// The Utah teapot, 12 x 12 samples per patch. Built once: both teapot scenes share it.
const Geometry& utahTeapot() {
    static const Geometry g = teapot(11, 1.2);
    return g;
}

const glm::dvec3 kPorcelain(0.85, 0.8, 0.7);

// The camera is in front, to the right and above, so both the spout (+X) and the handle show.
bool writeTeapot(const fs::path& dir) {
    SceneWriter w;
    const int mat = w.addMaterial("porcelain", glm::dvec4(kPorcelain, 1.0));
    w.addMeshNode("teapot", w.addMesh("teapot", utahTeapot(), mat, kUShort, Layout::Separate));
    w.addCamera({1.5, 1.4, 3.1}, {0.0, 0.0, 0.0});
    w.addPointLight(kKeyLight, kWhite, 1.0);
    return w.write(dir, "teapot", false);
}

// The teapot standing on the ground plane, for shadow mapping: a point and a directional light,
// like ground_plane. The node lifts it by exactly its lowest stored y, so it touches y = 0.
bool writeTeapotOnPlane(const fs::path& dir) {
    SceneWriter w;
    const int grey = w.addMaterial("ground", {0.6, 0.6, 0.6, 1.0});
    const int porcelain = w.addMaterial("porcelain", glm::dvec4(kPorcelain, 1.0));
    w.addMeshNode("ground", w.addMesh("ground", plane(8.0, 8), grey, kUByte, Layout::Separate));
    const Geometry& pot = utahTeapot();
    float lowest = std::numeric_limits<float>::max();
    for (const Vertex& v : pot.vertices) lowest = std::min(lowest, static_cast<float>(v.position.y));
    w.addMeshNode("teapot", w.addMesh("teapot", pot, porcelain, kUShort, Layout::Separate),
                  {0.0, -double(lowest), 0.0});
    w.addCamera({2.0, 2.3, 4.6}, {0.0, 0.5, 0.0});
    w.addPointLight(kKeyLight, kWhite, 1.0);
    w.addDirectionalLight({0.3, -1.0, -0.5}, {0.4, 0.5, 0.8}, 0.5);
    return w.write(dir, "teapot_on_plane", false);
}

// A large plane alone, texture coordinates 0..1 across it: for procedural patterns seen at
// grazing angles, where a pattern aliases (the labs set the camera).
bool writePlane(const fs::path& dir) {
    SceneWriter w;
    const int grey = w.addMaterial("white", {0.9, 0.9, 0.9, 1.0});
    w.addMeshNode("plane", w.addMesh("plane", plane(40.0, 4), grey, kUByte, Layout::Separate));
    w.addCamera({0.0, 1.0, 8.0}, {0.0, 0.0, -6.0});
    w.addPointLight(kKeyLight, kWhite, 1.0);
    return w.write(dir, "plane", false);
}

}  // namespace
}  // namespace shaderlab::scenegen

int main(int argc, char** argv) {
    using namespace shaderlab::scenegen;
    const bool lab_assets = argc == 3 && std::string(argv[1]) == "--lab-assets";
    if (argc != 2 && !lab_assets) {
        std::fprintf(
            stderr,
            "usage: shaderlab_make_scenes <out_dir>                the bundled scenes (labs/scenes/)\n"
            "       shaderlab_make_scenes --lab-assets <labs_dir>  the labs' generated assets "
            "(<labs_dir>/<id>/assets/)\n");
        return 2;
    }
    const fs::path dir = argv[argc - 1];
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec || !fs::is_directory(dir)) {
        std::fprintf(stderr, "shaderlab_make_scenes: cannot create %s\n", dir.string().c_str());
        return 1;
    }
    if (lab_assets) return writeLabAssets(dir) ? 0 : 1;
    const bool ok = writeSphere(dir, "sphere", 64, 32, kUShort) &&
                    writeSphere(dir, "sphere_low_poly", 12, 6, kUByte) && writeTorus(dir) &&
                    writeTorusKnot(dir) && writeCube(dir, "cube_flat", true) &&
                    writeCube(dir, "cube_no_normals", false) && writeNonuniformScale(dir) &&
                    writeGroundPlane(dir) && writeTeapot(dir) && writeTeapotOnPlane(dir) && writePlane(dir);
    return ok ? 0 : 1;
}
