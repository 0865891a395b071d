// The in-memory scene a lab pass draws: flattened draw items with world transforms, one camera,
// punctual lights. Filled by the glTF loader (gltf_loader.h); knows nothing about OpenGL.
// It does not hold textures or PBR material data beyond the base colour factor: the labs do not
// need them, and the shading is the student's.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace shaderlab {

// One triangle list: per-vertex attributes and 32-bit indices. Normals are always
// present (generated flat when the file has none); texcoords are zero when absent, and in
// OpenGL's convention: t = 0 is an image's bottom row (glTF's v runs down: t = 1 - v).
struct Mesh {
    std::string name;
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<glm::vec2> texcoords;
    std::vector<std::uint32_t> indices;  // size is a multiple of 3
    bool had_normals = true;             // false when normals were generated flat
    bool had_texcoords = false;
};

struct Material {
    std::string name;
    glm::vec4 base_color{1.0f};  // pbrMetallicRoughness.baseColorFactor
};

// One mesh primitive placed in the world.
struct DrawItem {
    std::string node_name;
    int mesh = -1;      // index into Scene::meshes
    int material = -1;  // index into Scene::materials, -1 = default material
    glm::mat4 world{1.0f};
};

struct Camera {
    glm::vec3 position{0.0f, 0.0f, 3.0f};
    glm::vec3 target{0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float fov_y_deg = 45.0f;
    float z_near = 0.1f;
    float z_far = 100.0f;
    // When non-zero, the aspect ratio stored in the file; the renderer uses the target's aspect.
    float file_aspect = 0.0f;
    bool orthographic = false;
    float ortho_height = 2.0f;  // orthographic: the visible height in world units
};

enum class LightType { Directional, Point, Spot };

// KHR_lights_punctual, resolved into world space.
struct Light {
    LightType type = LightType::Point;
    glm::vec3 position{0.0f};                // world space (point, spot)
    glm::vec3 direction{0.0f, 0.0f, -1.0f};  // world space, the direction the light travels
    glm::vec3 color{1.0f};
    float intensity = 1.0f;
    float range = 0.0f;  // 0 = infinite
};

struct Scene {
    std::string source_path;
    std::vector<Mesh> meshes;
    std::vector<Material> materials;
    std::vector<DrawItem> draw_items;
    bool has_camera = false;  // false: `camera` holds a default framing the bounds
    Camera camera;
    std::vector<Light> lights;
    glm::vec3 bounds_min{0.0f};
    glm::vec3 bounds_max{0.0f};
};

}  // namespace shaderlab
