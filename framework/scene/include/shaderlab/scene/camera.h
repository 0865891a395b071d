// Cameras and lights as the renderer uses them: the scene's camera with lab.json overrides,
// a pass's camera (a light's view for a shadow map), near and far planes fitted to the scene
// when an override moves the camera, and the view and projection matrices. No OpenGL here.
#pragma once

#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "shaderlab/lab/lab_spec.h"
#include "shaderlab/scene/scene.h"

namespace shaderlab {

// A light as shaders receive it (docs/student-contract.md).
struct ResolvedLight {
    bool directional = false;
    glm::vec3 position{0.0f};                // point lights
    glm::vec3 direction{0.0f, -1.0f, 0.0f};  // directional: the direction light travels (unit)
    glm::vec3 color{1.0f};                   // colour times intensity
    // KHR_lights_punctual extras (scene lights only; a lab's own lights keep the defaults):
    float range = 0.0f;  // 0 = infinite
    // The specification's precomputed spot falloff: saturate(dot(direction, -l) * x + y)^2 with
    // x = 1 / max(0.001, cos(inner) - cos(outer)), y = -cos(outer) * x; (0, 1) = no falloff.
    glm::vec2 cone{0.0f, 1.0f};
};

// The lights of a scene: the lab's when it gives them, else the file's; a scene without any
// gets one white point light above the camera.
std::vector<ResolvedLight> resolveLights(const Scene& scene, const SceneSpec& spec, const Camera& camera);

// Applies an override to `base`. Moving the camera (position, target or light) without giving
// near and far fits them to the scene's bounding sphere as seen from the new place. Returns ""
// or a problem (a light index the scene does not have).
std::string applyCameraOverride(const Scene& scene, const std::vector<ResolvedLight>& lights,
                                const CameraOverride& override_, Camera* camera);

// Near and far planes that hold the scene's bounding sphere as seen from the camera.
void fitDepthRange(const Scene& scene, Camera* camera);

// A turn of the camera about its target, as a viewer's orbit and zoom give it: yaw about the
// world's up axis, pitch towards it (the elevation stays within 85 degrees of the horizon), and
// the distance to the target (an orthographic camera's height) divided by `zoom`.
struct CameraOrbit {
    float yaw_deg = 0.0f;
    float pitch_deg = 0.0f;
    float zoom = 1.0f;
    bool any() const { return yaw_deg != 0.0f || pitch_deg != 0.0f || zoom != 1.0f; }
    bool operator==(const CameraOrbit& o) const {
        return yaw_deg == o.yaw_deg && pitch_deg == o.pitch_deg && zoom == o.zoom;
    }
    bool operator!=(const CameraOrbit& o) const { return !(*this == o); }
};

// Applies `orbit` to `camera` and fits the near and far planes to the scene again.
void orbitCamera(const Scene& scene, const CameraOrbit& orbit, Camera* camera);

glm::mat4 viewMatrix(const Camera& camera);
glm::mat4 projectionMatrix(const Camera& camera, float aspect);

}  // namespace shaderlab
