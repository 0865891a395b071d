// Cameras, overrides and light views; see camera.h.
#include "shaderlab/scene/camera.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

namespace shaderlab {

namespace {

void boundingSphere(const Scene& scene, glm::vec3* centre, float* radius) {
    *centre = 0.5f * (scene.bounds_min + scene.bounds_max);
    *radius = 0.5f * glm::length(scene.bounds_max - scene.bounds_min);
    if (!(*radius > 1e-6f)) *radius = 1.0f;
}

// Any unit vector not parallel to `forward`, for lookAt.
glm::vec3 upFor(const glm::vec3& forward) {
    const glm::vec3 y(0.0f, 1.0f, 0.0f);
    return std::abs(glm::dot(glm::normalize(forward), y)) > 0.99f ? glm::vec3(0.0f, 0.0f, 1.0f) : y;
}

}  // namespace

std::vector<ResolvedLight> resolveLights(const Scene& scene, const SceneSpec& spec, const Camera& camera) {
    std::vector<ResolvedLight> out;
    auto add = [&out](bool directional, glm::vec3 pos, glm::vec3 dir, glm::vec3 color) {
        ResolvedLight l;
        l.directional = directional;
        l.position = pos;
        l.direction = glm::length(dir) > 0.0f ? glm::normalize(dir) : glm::vec3(0.0f, -1.0f, 0.0f);
        l.color = color;
        out.push_back(l);
    };
    if (spec.lights) {
        for (const LightSpec& l : *spec.lights)
            add(l.type == "directional", l.position, l.direction, l.color * l.intensity);
    } else {
        for (const Light& l : scene.lights) {
            add(l.type == LightType::Directional, l.position, l.direction, l.color * l.intensity);
            out.back().range = l.range;
            if (l.type == LightType::Spot) {
                const float cos_inner = std::cos(l.inner_cone), cos_outer = std::cos(l.outer_cone);
                const float scale = 1.0f / std::max(0.001f, cos_inner - cos_outer);
                out.back().cone = glm::vec2(scale, -cos_outer * scale);
            }
        }
    }
    if (out.empty()) add(false, camera.position + glm::vec3(0.0f, 2.0f, 0.0f), {}, glm::vec3(1.0f));
    return out;
}

void fitDepthRange(const Scene& scene, Camera* camera) {
    glm::vec3 centre;
    float radius;
    boundingSphere(scene, &centre, &radius);
    const glm::vec3 forward = glm::normalize(camera->target - camera->position);
    const float d = glm::dot(centre - camera->position, forward);
    const float far_plane = std::max(d + radius, radius) * 1.05f;
    float near_plane = (d - radius) * 0.95f;
    if (!(near_plane > far_plane * 1e-3f)) near_plane = far_plane * 1e-3f;
    camera->z_near = near_plane;
    camera->z_far = far_plane;
}

std::string applyCameraOverride(const Scene& scene, const std::vector<ResolvedLight>& lights,
                                const CameraOverride& o, Camera* c) {
    bool moved = false;
    if (o.light) {
        const int i = *o.light;
        if (i < 0 || static_cast<std::size_t>(i) >= lights.size())
            return "camera.light " + std::to_string(i) + ": the scene has " + std::to_string(lights.size()) +
                   (lights.size() == 1 ? " light" : " lights");
        const ResolvedLight& l = lights[static_cast<std::size_t>(i)];
        glm::vec3 centre;
        float radius;
        boundingSphere(scene, &centre, &radius);
        c->target = centre;
        if (l.directional) {
            // Parallel rays: an orthographic view along the light that holds the bounding sphere.
            c->position = centre - l.direction * (2.0f * radius);
            c->orthographic = true;
            c->ortho_height = 2.0f * radius * 1.02f;
        } else {
            c->position = l.position;
            const float d = glm::length(centre - l.position);
            c->orthographic = false;
            c->fov_y_deg = d > radius * 1.02f ? glm::degrees(2.0f * std::asin(radius * 1.02f / d)) : 120.0f;
            if (!(d > 1e-6f)) c->target = l.position + glm::vec3(0.0f, -1.0f, 0.0f);
        }
        c->up = upFor(c->target - c->position);
        moved = true;
    }
    if (o.position) c->position = *o.position;
    if (o.target) c->target = *o.target;
    // A file camera's up is perpendicular to its own view (tilted when it looks down); moved
    // elsewhere, it would roll the horizon. World +y unless the lab says otherwise.
    if ((o.position || o.target) && !o.light) c->up = upFor(c->target - c->position);
    if (o.up) c->up = *o.up;
    moved = moved || o.position || o.target;
    if (o.projection) c->orthographic = *o.projection == Projection::Orthographic;
    if (o.fov_y_deg) c->fov_y_deg = *o.fov_y_deg;
    if (o.height) c->ortho_height = *o.height;
    if (moved && !o.up &&
        std::abs(glm::dot(glm::normalize(c->target - c->position), glm::normalize(c->up))) > 0.999f)
        c->up = upFor(c->target - c->position);
    // The default framing no longer holds once the lab places or shapes the camera itself.
    if (moved || o.fov_y_deg || o.height || o.projection) c->fit_both_axes = false;
    if (moved) fitDepthRange(scene, c);
    if (o.z_near) c->z_near = *o.z_near;
    if (o.z_far) c->z_far = *o.z_far;
    if (o.z_near && !o.z_far && c->z_far <= c->z_near) c->z_far = c->z_near * 1000.0f;
    if (o.z_far && !o.z_near && c->z_near >= c->z_far) c->z_near = c->z_far * 1e-3f;
    return {};
}

void orbitCamera(const Scene& scene, const CameraOrbit& orbit, Camera* c) {
    if (!orbit.any()) return;
    glm::vec3 offset = c->position - c->target;
    const float distance = glm::length(offset);
    if (!(distance > 1e-6f)) return;
    const glm::vec3 axis = upFor(-offset);
    const glm::quat yaw = glm::angleAxis(glm::radians(orbit.yaw_deg), axis);
    offset = yaw * offset;
    // Elevation above the plane normal to the axis, kept off the poles so lookAt stays defined.
    const float elevation = std::asin(std::clamp(glm::dot(offset / distance, axis), -1.0f, 1.0f));
    const float limit = glm::radians(85.0f);
    const float wanted = std::clamp(elevation + glm::radians(orbit.pitch_deg), -limit, limit);
    const glm::vec3 right = glm::cross(axis, offset);
    if (glm::length(right) > 1e-6f)
        offset = glm::angleAxis(elevation - wanted, glm::normalize(right)) * offset;
    const float zoom = orbit.zoom > 1e-3f ? orbit.zoom : 1e-3f;
    c->position = c->target + offset / zoom;
    c->ortho_height /= zoom;
    c->up = upFor(c->target - c->position);
    fitDepthRange(scene, c);
}

glm::mat4 viewMatrix(const Camera& camera) { return glm::lookAt(camera.position, camera.target, camera.up); }

glm::mat4 projectionMatrix(const Camera& camera, float aspect) {
    // A default framing fits the bounding sphere vertically; on a target taller than wide the
    // horizontal extent is the smaller one, so the vertical one grows until the sphere fits across.
    const bool widen = camera.fit_both_axes && aspect > 0.0f && aspect < 1.0f;
    if (camera.orthographic) {
        const float h = 0.5f * camera.ortho_height / (widen ? aspect : 1.0f), w = h * aspect;
        return glm::ortho(-w, w, -h, h, camera.z_near, camera.z_far);
    }
    float fov_y = glm::radians(camera.fov_y_deg);
    if (widen) fov_y = 2.0f * std::atan(std::tan(0.5f * fov_y) / aspect);
    return glm::perspective(fov_y, aspect, camera.z_near, camera.z_far);
}

}  // namespace shaderlab
