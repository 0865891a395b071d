// MikkTSpace-style tangents; see tangent_space.h.
#include "tangent_space.h"

#include <cmath>

namespace shaderlab {

namespace {

// A unit vector orthogonal to unit `n`.
glm::vec3 anyOrthogonal(const glm::vec3& n) {
    const glm::vec3 axis = std::abs(n.x) < 0.9f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
    return glm::normalize(glm::cross(n, glm::cross(axis, n)));
}

glm::vec3 projectOnPlane(const glm::vec3& v, const glm::vec3& n) { return v - n * glm::dot(n, v); }

float cornerAngle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
    const glm::vec3 u = b - a, v = c - a;
    const float lu = glm::length(u), lv = glm::length(v);
    if (!(lu > 0.0f) || !(lv > 0.0f)) return 0.0f;
    return std::acos(glm::clamp(glm::dot(u, v) / (lu * lv), -1.0f, 1.0f));
}

}  // namespace

std::vector<glm::vec4> generateTangents(const std::vector<glm::vec3>& positions,
                                        const std::vector<glm::vec3>& normals,
                                        const std::vector<glm::vec2>& texcoords,
                                        const std::vector<std::uint32_t>& indices) {
    const std::size_t n = positions.size();
    std::vector<glm::vec3> tangent_sum(n, glm::vec3(0.0f));
    std::vector<float> sign_sum(n, 0.0f);
    for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
        const std::uint32_t i[3] = {indices[t], indices[t + 1], indices[t + 2]};
        if (i[0] >= n || i[1] >= n || i[2] >= n) continue;
        const glm::vec3 e1 = positions[i[1]] - positions[i[0]], e2 = positions[i[2]] - positions[i[0]];
        const glm::vec2 d1 = texcoords[i[1]] - texcoords[i[0]], d2 = texcoords[i[2]] - texcoords[i[0]];
        // Solve [e1 e2] = [T B] [d1 d2] for the position derivatives along u (T) and v (B).
        const float det = d1.x * d2.y - d2.x * d1.y;
        if (!(std::abs(det) > 1e-20f) || !std::isfinite(det)) continue;
        const glm::vec3 tu = (e1 * d2.y - e2 * d1.y) / det;
        const glm::vec3 tv = (e2 * d1.x - e1 * d2.x) / det;
        if (!std::isfinite(tu.x + tu.y + tu.z + tv.x + tv.y + tv.z)) continue;
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t v = i[k];
            const glm::vec3& nv = normals[v];
            const glm::vec3 projected = projectOnPlane(tu, nv);
            const float len = glm::length(projected);
            if (!(len > 0.0f) || !std::isfinite(len)) continue;
            const float weight =
                cornerAngle(positions[v], positions[i[(k + 1) % 3]], positions[i[(k + 2) % 3]]);
            tangent_sum[v] += weight * (projected / len);
            // Right-handed (w = +1) when B runs the way cross(N, T) does.
            sign_sum[v] += weight * (glm::dot(glm::cross(nv, tu), tv) < 0.0f ? -1.0f : 1.0f);
        }
    }
    std::vector<glm::vec4> out(n);
    for (std::size_t v = 0; v < n; ++v) {
        const glm::vec3 nv = normals[v];
        glm::vec3 tangent = projectOnPlane(tangent_sum[v], nv);
        const float len = glm::length(tangent);
        tangent = len > 1e-12f && std::isfinite(len) ? tangent / len : anyOrthogonal(nv);
        out[v] = glm::vec4(tangent, sign_sum[v] < 0.0f ? -1.0f : 1.0f);
    }
    return out;
}

}  // namespace shaderlab
