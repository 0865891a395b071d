// The course's sky: an analytic environment (a blue gradient sky with a sun, over a checkered
// ground plane that fades into haze) from which shaderlab_make_sky writes the cube-map faces in
// labs/shared/sky/, and against which tests check them. Display-referred RGB in 0..1.
// Header-only so the tool and the tests evaluate the same function.
#pragma once

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>

namespace shaderlab::sky {

// The sun: direction toward it, angular radius of its disc, and colours.
inline glm::dvec3 sunDirection() { return glm::normalize(glm::dvec3(0.35, 0.45, -0.82)); }
constexpr double kSunRadiusDeg = 3.0;

// Radiance-like colour seen along unit direction `d` from the origin.
inline glm::dvec3 colour(const glm::dvec3& d) {
    const glm::dvec3 horizon(0.82, 0.88, 0.95), zenith(0.18, 0.38, 0.78), haze(0.62, 0.62, 0.60);
    if (d.y >= 0.0) {
        const double cos_sun = glm::dot(d, sunDirection());
        if (cos_sun > std::cos(kSunRadiusDeg * 3.14159265358979323846 / 180.0)) return {1.0, 0.97, 0.90};
        glm::dvec3 c = glm::mix(horizon, zenith, std::sqrt(d.y));
        c += glm::dvec3(1.0, 0.85, 0.6) * (0.35 * std::pow(std::max(cos_sun, 0.0), 24.0));
        return glm::min(c, glm::dvec3(1.0));
    }
    // The ground: a plane one unit below the viewer with a checker of unit squares, fading into
    // haze with distance (so the horizon does not alias).
    const double t = -1.0 / d.y;
    const double px = d.x * t, pz = d.z * t;
    const bool dark =
        (static_cast<long long>(std::floor(px)) + static_cast<long long>(std::floor(pz))) % 2 != 0;
    const glm::dvec3 ground = dark ? glm::dvec3(0.42, 0.36, 0.28) : glm::dvec3(0.58, 0.52, 0.42);
    return glm::mix(haze, ground, std::exp(-t / 12.0));
}

// The direction through texel (i, j) of an n x n cube face (0..5: +x, -x, +y, -y, +z, -z), at
// sub-texel offset (fx, fy) in [0, 1), following the OpenGL cube-map face selection table
// (OpenGL 4.5 core, section 8.13, table 8.19): s = (sc / |ma| + 1) / 2, t = (tc / |ma| + 1) / 2,
// with row j of the face image at t = (j + fy) / n.
inline glm::dvec3 faceDirection(int face, int i, int j, int n, double fx = 0.5, double fy = 0.5) {
    const double sc = 2.0 * (i + fx) / n - 1.0, tc = 2.0 * (j + fy) / n - 1.0;
    glm::dvec3 d;
    switch (face) {
        case 0:  // +x: sc = -z, tc = -y
            d = {1.0, -tc, -sc};
            break;
        case 1:  // -x: sc = +z, tc = -y
            d = {-1.0, -tc, sc};
            break;
        case 2:  // +y: sc = +x, tc = +z
            d = {sc, 1.0, tc};
            break;
        case 3:  // -y: sc = +x, tc = -z
            d = {sc, -1.0, -tc};
            break;
        case 4:  // +z: sc = +x, tc = -y
            d = {sc, -tc, 1.0};
            break;
        default:  // -z: sc = -x, tc = -y
            d = {-sc, -tc, -1.0};
            break;
    }
    return glm::normalize(d);
}

// The face texel's colour: the mean over a k x k grid of sample points inside it.
inline glm::dvec3 texel(int face, int i, int j, int n, int k = 4) {
    glm::dvec3 sum(0.0);
    for (int a = 0; a < k; ++a)
        for (int b = 0; b < k; ++b) sum += colour(faceDirection(face, i, j, n, (a + 0.5) / k, (b + 0.5) / k));
    return sum / double(k * k);
}

}  // namespace shaderlab::sky
