// The glTF loader's node tree: the chosen scene's nodes walked from their roots with their
// transforms composed (matrix or TRS), one draw item per triangle primitive and per
// EXT_mesh_gpu_instancing instance, KHR_lights_punctual lights placed, the scene's world-space
// bounds, and the camera: the file's first (perspective or orthographic), or one that frames the
// bounds when the file has none.
// What it does not: animate (no skins, morph targets or animations), draw points or lines (skipped
// with a warning), or convert a primitive's data (gltf_primitives.cpp).
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <limits>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "gltf_converter.h"

namespace shaderlab::gltf_detail {

namespace {

// glTF numbers are doubles; 1e300 is finite there but infinite as the float we store.
bool finiteMatrix(const glm::mat4& m) {
    for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) {
            if (!std::isfinite(m[c][r])) return false;
        }
    }
    return true;
}

bool finiteVec(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

glm::mat4 Converter::localMatrix(std::size_t node_index) const {
    const glm::mat4 m = localMatrixUnchecked(node_index);
    if (!finiteMatrix(m))
        fail("node " + std::to_string(node_index) + ": its transform is too large for floats");
    return m;
}

glm::mat4 Converter::localMatrixUnchecked(std::size_t node_index) const {
    const tinygltf::Node& node = model_.nodes[node_index];
    const std::string who = "node " + std::to_string(node_index);
    if (!node.matrix.empty()) {
        if (node.matrix.size() != 16 || !finite(node.matrix))
            fail(who + ": matrix must be 16 finite numbers");
        glm::mat4 m(1.0f);
        for (int c = 0; c < 4; ++c) {
            for (int r = 0; r < 4; ++r)
                m[c][r] = static_cast<float>(node.matrix[static_cast<std::size_t>(c * 4 + r)]);
        }
        return m;  // glTF stores column-major, as glm does
    }
    glm::mat4 m(1.0f);
    if (!node.translation.empty()) {
        if (node.translation.size() != 3 || !finite(node.translation)) {
            fail(who + ": translation must be 3 finite numbers");
        }
        m = glm::translate(
            m, glm::vec3(static_cast<float>(node.translation[0]), static_cast<float>(node.translation[1]),
                         static_cast<float>(node.translation[2])));
    }
    if (!node.rotation.empty()) {
        if (node.rotation.size() != 4 || !finite(node.rotation))
            fail(who + ": rotation must be 4 finite numbers");
        // glTF quaternions are (x, y, z, w); glm's constructor takes w first.
        glm::quat q(static_cast<float>(node.rotation[3]), static_cast<float>(node.rotation[0]),
                    static_cast<float>(node.rotation[1]), static_cast<float>(node.rotation[2]));
        const float len = glm::length(q);
        if (!(len > 1e-6f)) fail(who + ": rotation quaternion has zero length");
        m = m * glm::mat4_cast(q / len);
    }
    if (!node.scale.empty()) {
        if (node.scale.size() != 3 || !finite(node.scale)) fail(who + ": scale must be 3 finite numbers");
        m = glm::scale(m, glm::vec3(static_cast<float>(node.scale[0]), static_cast<float>(node.scale[1]),
                                    static_cast<float>(node.scale[2])));
    }
    return m;
}

std::vector<int> Converter::rootNodes() const {
    const int chosen = model_.defaultScene;
    if (chosen < -1 || (chosen >= 0 && static_cast<std::size_t>(chosen) >= model_.scenes.size())) {
        fail("default scene " + std::to_string(chosen) + " does not exist (the file has " +
             std::to_string(model_.scenes.size()) + " scenes)");
    }
    if (chosen >= 0) return model_.scenes[static_cast<std::size_t>(chosen)].nodes;
    if (!model_.scenes.empty()) return model_.scenes[0].nodes;
    // No scenes at all: every node that is nobody's child is a root.
    std::vector<char> is_child(model_.nodes.size(), 0);
    for (const auto& node : model_.nodes) {
        for (int child : node.children) {
            if (child >= 0 && static_cast<std::size_t>(child) < model_.nodes.size()) {
                is_child[static_cast<std::size_t>(child)] = 1;
            }
        }
    }
    std::vector<int> roots;
    for (std::size_t i = 0; i < model_.nodes.size(); ++i) {
        if (!is_child[i]) roots.push_back(static_cast<int>(i));
    }
    return roots;
}

void Converter::walkNodes() {
    // Iterative pre-order walk: a hostile file can nest nodes deeper than the call stack allows.
    std::vector<char> visited(model_.nodes.size(), 0);
    std::vector<std::pair<int, glm::mat4>> stack;
    const std::vector<int> roots = rootNodes();
    for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.emplace_back(*it, glm::mat4(1.0f));
    while (!stack.empty()) {
        const auto [index, parent] = stack.back();
        stack.pop_back();
        if (index < 0 || static_cast<std::size_t>(index) >= model_.nodes.size()) {
            fail("node " + std::to_string(index) + " does not exist (the file has " +
                 std::to_string(model_.nodes.size()) + " nodes)");
        }
        const auto node_index = static_cast<std::size_t>(index);
        if (visited[node_index]) {
            fail("node " + std::to_string(index) + " is reached twice; the node hierarchy must be a tree");
        }
        visited[node_index] = 1;
        const glm::mat4 world = parent * localMatrix(node_index);
        if (!finiteMatrix(world)) {
            fail("node " + std::to_string(index) + ": its world transform overflows to infinity or NaN");
        }
        visitNode(node_index, world);
        const auto& children = model_.nodes[node_index].children;
        for (auto child = children.rbegin(); child != children.rend(); ++child)
            stack.emplace_back(*child, world);
    }
}

// EXT_mesh_gpu_instancing: one local transform per instance (TRS from accessors), applied after
// the node's own. Empty when the node has no instancing.
std::vector<glm::mat4> Converter::instanceTransforms(std::size_t node_index) const {
    const tinygltf::Node& node = model_.nodes[node_index];
    const auto ext = node.extensions.find(kInstancing);
    if (ext == node.extensions.end()) return {};
    const std::string who = "node " + std::to_string(node_index) + " (" + kInstancing + ")";
    if (!ext->second.IsObject() || !ext->second.Has("attributes") ||
        !ext->second.Get("attributes").IsObject())
        fail(who + ": the extension needs an \"attributes\" object");
    const tinygltf::Value& attributes = ext->second.Get("attributes");
    std::size_t count = 0;
    std::vector<float> t, r, s;
    const auto read = [&](const char* name, Use use, std::vector<float>* out) {
        if (!attributes.Has(name)) return;
        const tinygltf::Value& index = attributes.Get(name);
        if (!index.IsNumber()) fail(who + ": " + name + " must be an accessor index");
        const std::size_t n =
            readAccessor(index.GetNumberAsInt(), std::string(name) + " of " + who, use, out);
        if (count != 0 && n != count)
            fail(who + ": " + name + " has " + std::to_string(n) + " instances, not " +
                 std::to_string(count));
        count = n;
    };
    read("TRANSLATION", Use::Translation, &t);
    read("ROTATION", Use::Rotation, &r);
    read("SCALE", Use::Scale, &s);
    if (count == 0) fail(who + ": no TRANSLATION, ROTATION or SCALE accessor");
    if (count > kMaxDrawItems)
        fail(who + ": " + std::to_string(count) + " instances is over the limit of " +
             std::to_string(kMaxDrawItems));
    std::vector<glm::mat4> out(count, glm::mat4(1.0f));
    for (std::size_t i = 0; i < count; ++i) {
        glm::mat4 m(1.0f);
        if (!t.empty()) m = glm::translate(m, glm::vec3(t[3 * i], t[3 * i + 1], t[3 * i + 2]));
        if (!r.empty()) {
            glm::quat q(r[4 * i + 3], r[4 * i], r[4 * i + 1], r[4 * i + 2]);
            const float len = glm::length(q);
            if (len > 1e-6f && std::isfinite(len)) m = m * glm::mat4_cast(q / len);
        }
        if (!s.empty()) m = glm::scale(m, glm::vec3(s[3 * i], s[3 * i + 1], s[3 * i + 2]));
        out[i] = m;
    }
    return out;
}

void Converter::visitNode(std::size_t node_index, const glm::mat4& world) {
    const tinygltf::Node& node = model_.nodes[node_index];
    const std::string who = "node " + std::to_string(node_index);
    if (node.mesh != -1) {
        if (node.mesh < 0 || static_cast<std::size_t>(node.mesh) >= model_.meshes.size()) {
            fail(who + ": mesh " + std::to_string(node.mesh) + " does not exist (the file has " +
                 std::to_string(model_.meshes.size()) + " meshes)");
        }
        const auto mesh_index = static_cast<std::size_t>(node.mesh);
        const auto& prims = model_.meshes[mesh_index].primitives;
        if (node.skin != -1 && warned_.insert("skin node " + std::to_string(node_index)).second) {
            warnings_.push_back(who + ": skin " + std::to_string(node.skin) + " ignored; " +
                                meshLabel(mesh_index) + " is drawn in its bind pose");
        }
        const std::vector<glm::mat4> instances = instanceTransforms(node_index);
        for (std::size_t p = 0; p < prims.size(); ++p) {
            const int mode = prims[p].mode;
            if (mode != -1 && mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
                mode != TINYGLTF_MODE_TRIANGLE_FAN) {
                static const char* const kModeNames[] = {"POINTS", "LINES", "LINE_LOOP", "LINE_STRIP"};
                const std::string name =
                    mode >= 0 && mode <= 3 ? std::string(" (") + kModeNames[mode] + ")" : "";
                if (warned_.insert("mode " + std::to_string(mesh_index) + "/" + std::to_string(p)).second) {
                    warnings_.push_back(meshLabel(mesh_index) + " primitive " + std::to_string(p) +
                                        ": mode " + std::to_string(mode) + name +
                                        " skipped; shaderlab draws only triangles (lists, strips and fans)");
                }
                continue;
            }
            const int material = prims[p].material;
            if (material < -1 ||
                (material >= 0 && static_cast<std::size_t>(material) >= model_.materials.size())) {
                fail(meshLabel(mesh_index) + " primitive " + std::to_string(p) + ": material " +
                     std::to_string(material) + " does not exist (the file has " +
                     std::to_string(model_.materials.size()) + " materials)");
            }
            const int mesh_id = convertPrimitive(mesh_index, p);
            for (std::size_t k = 0; k < std::max<std::size_t>(instances.size(), 1); ++k) {
                if (scene_.draw_items.size() >= kMaxDrawItems) {
                    fail("the scene has more than " + std::to_string(kMaxDrawItems) + " draw items");
                }
                DrawItem item;
                item.node_name = node.name.empty() ? "node" + std::to_string(node_index) : node.name;
                item.mesh = mesh_id;
                item.material = material;
                item.world = instances.empty() ? world : world * instances[k];
                if (!finiteMatrix(item.world))
                    fail(who + ": an instance's transform overflows to infinity or NaN");
                item.mirrored = glm::determinant(glm::mat3(item.world)) < 0.0f;
                scene_.draw_items.push_back(std::move(item));
            }
        }
    }
    if (node.camera != -1) {
        if (node.camera < 0 || static_cast<std::size_t>(node.camera) >= model_.cameras.size()) {
            fail(who + ": camera " + std::to_string(node.camera) + " does not exist (the file has " +
                 std::to_string(model_.cameras.size()) + " cameras)");
        }
        const auto& cam = model_.cameras[static_cast<std::size_t>(node.camera)];
        if (cam.type != "perspective" && cam.type != "orthographic") {
            warnings_.push_back(who + ": camera " + std::to_string(node.camera) + " has unknown type " +
                                inQuotes(cam.type) + "; ignored");
        } else if (camera_node_ < 0) {
            camera_node_ = static_cast<int>(node_index);
            camera_world_ = world;
        }
    }
    addLight(node_index, world);
}

void Converter::addLight(std::size_t node_index, const glm::mat4& world) {
    const tinygltf::Node& node = model_.nodes[node_index];
    const auto ext = node.extensions.find("KHR_lights_punctual");
    if (ext == node.extensions.end()) return;
    const std::string who = "node " + std::to_string(node_index);
    if (!ext->second.IsObject() || !ext->second.Has("light") || !ext->second.Get("light").IsNumber()) {
        fail(who + ": KHR_lights_punctual must be an object with a numeric \"light\"");
    }
    const double index = ext->second.Get("light").GetNumberAsDouble();
    if (!(index >= 0.0) || index >= static_cast<double>(model_.lights.size()) || index != std::floor(index)) {
        std::ostringstream shown;
        shown << index;
        fail(who + ": light " + shown.str() + " does not exist (the file has " +
             std::to_string(model_.lights.size()) + " KHR_lights_punctual lights)");
    }
    const auto light_index = static_cast<std::size_t>(index);
    const tinygltf::Light& src = model_.lights[light_index];
    const std::string lwho = "light " + std::to_string(light_index);
    Light light;
    if (src.type == "directional") {
        light.type = LightType::Directional;
    } else if (src.type == "point") {
        light.type = LightType::Point;
    } else if (src.type == "spot") {
        light.type = LightType::Spot;
    } else {
        fail(lwho + ": unknown type " + inQuotes(src.type));
    }
    if (!src.color.empty()) {
        if (src.color.size() != 3 || !finite(src.color)) fail(lwho + ": color must be 3 finite numbers");
        light.color = glm::vec3(static_cast<float>(src.color[0]), static_cast<float>(src.color[1]),
                                static_cast<float>(src.color[2]));
    }
    if (!std::isfinite(src.intensity) || src.intensity < 0.0)
        fail(lwho + ": intensity must be finite and >= 0");
    if (!std::isfinite(src.range) || src.range < 0.0) fail(lwho + ": range must be finite and >= 0");
    light.intensity = static_cast<float>(src.intensity);
    light.range = static_cast<float>(src.range);
    if (light.type == LightType::Spot) {
        const double inner = src.spot.innerConeAngle, outer = src.spot.outerConeAngle;
        // KHR_lights_punctual: 0 <= innerConeAngle < outerConeAngle <= pi/2.
        if (!(inner >= 0.0) || !(outer > inner) || !(outer <= 1.5707964)) {
            fail(lwho + ": spot cone angles must satisfy 0 <= innerConeAngle < outerConeAngle <= pi/2");
        }
        light.inner_cone = static_cast<float>(inner);
        light.outer_cone = static_cast<float>(outer);
    }
    if (!finiteVec(light.color) || !std::isfinite(light.intensity) || !std::isfinite(light.range)) {
        fail(lwho + ": color, intensity or range is too large for a float");
    }
    light.position = glm::vec3(world * glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    // Lights shine down their local -Z; a scaled node must not change the direction's length.
    const glm::vec3 dir = glm::vec3(world * glm::vec4(0.0f, 0.0f, -1.0f, 0.0f));
    const float len = glm::length(dir);
    light.direction = len > 0.0f && std::isfinite(len) ? dir / len : glm::vec3(0.0f, 0.0f, -1.0f);
    scene_.lights.push_back(light);
}

void Converter::computeBounds() {
    glm::vec3 lo(std::numeric_limits<float>::max());
    glm::vec3 hi(std::numeric_limits<float>::lowest());
    std::size_t work = 0;
    for (const DrawItem& item : scene_.draw_items) {
        work += scene_.meshes[static_cast<std::size_t>(item.mesh)].positions.size();
    }
    if (work <= kExactBoundsBudget) {
        // Tight bounds: every vertex of every item in world space.
        for (const DrawItem& item : scene_.draw_items) {
            for (const glm::vec3& p : scene_.meshes[static_cast<std::size_t>(item.mesh)].positions) {
                const glm::vec3 w = glm::vec3(item.world * glm::vec4(p, 1.0f));
                lo = glm::min(lo, w);
                hi = glm::max(hi, w);
            }
        }
    } else {
        // A big mesh instanced many times: the corners of each mesh's own box, transformed.
        // Looser for rotated items, but linear in the number of items.
        std::vector<std::pair<glm::vec3, glm::vec3>> boxes;
        for (const Mesh& mesh : scene_.meshes) {
            glm::vec3 mlo(std::numeric_limits<float>::max()), mhi(std::numeric_limits<float>::lowest());
            for (const glm::vec3& p : mesh.positions) {
                mlo = glm::min(mlo, p);
                mhi = glm::max(mhi, p);
            }
            boxes.emplace_back(mlo, mhi);
        }
        for (const DrawItem& item : scene_.draw_items) {
            const auto& box = boxes[static_cast<std::size_t>(item.mesh)];
            for (int corner = 0; corner < 8; ++corner) {
                const glm::vec3 p((corner & 1) ? box.second.x : box.first.x,
                                  (corner & 2) ? box.second.y : box.first.y,
                                  (corner & 4) ? box.second.z : box.first.z);
                const glm::vec3 w = glm::vec3(item.world * glm::vec4(p, 1.0f));
                lo = glm::min(lo, w);
                hi = glm::max(hi, w);
            }
        }
    }
    if (scene_.draw_items.empty()) {
        lo = hi = glm::vec3(0.0f);
        warnings_.push_back("the scene has no triangles to draw");
    }
    if (!std::isfinite(lo.x + lo.y + lo.z + hi.x + hi.y + hi.z)) {
        fail("node transforms take the scene's bounds to infinity");
    }
    scene_.bounds_min = lo;
    scene_.bounds_max = hi;
}

void Converter::placeCamera() {
    const glm::vec3 centre = 0.5f * (scene_.bounds_min + scene_.bounds_max);
    float radius = 0.5f * glm::length(scene_.bounds_max - scene_.bounds_min);
    if (!(radius > 1e-6f)) radius = 1.0f;
    Camera& cam = scene_.camera;

    if (camera_node_ < 0) {
        // No camera in the file: look from +Z and a little above at the centre, far enough back
        // that the bounding sphere fits the vertical field of view.
        scene_.has_camera = false;
        cam = Camera{};
        const float half_fov = glm::radians(cam.fov_y_deg) * 0.5f;
        const float distance = radius / std::sin(half_fov) * 1.05f;
        cam.target = centre;
        cam.position = centre + glm::normalize(glm::vec3(0.0f, 0.35f, 1.0f)) * distance;
        cam.up = glm::vec3(0.0f, 1.0f, 0.0f);
        cam.z_near = std::max((distance - radius) * 0.5f, distance * 1e-3f);
        cam.z_far = (distance + radius) * 2.0f;
        // The distance fits the vertical field of view; a portrait target widens the projection
        // so the sphere fits across as well (camera.cpp).
        cam.fit_both_axes = true;
        checkCamera();
        return;
    }

    const auto& node = model_.nodes[static_cast<std::size_t>(camera_node_)];
    const tinygltf::Camera& file_camera = model_.cameras[static_cast<std::size_t>(node.camera)];
    const std::string who = "camera " + std::to_string(node.camera);
    scene_.has_camera = true;
    if (file_camera.type == "orthographic") {
        const auto& o = file_camera.orthographic;
        if (!std::isfinite(o.xmag) || o.xmag == 0.0 || !std::isfinite(o.ymag) || o.ymag == 0.0)
            fail(who + ": xmag and ymag must be finite and not 0");
        if (!std::isfinite(o.znear) || o.znear < 0.0) fail(who + ": znear must be >= 0");
        if (!std::isfinite(o.zfar) || o.zfar <= o.znear) fail(who + ": zfar must be > znear");
        cam.orthographic = true;
        cam.ortho_height = static_cast<float>(2.0 * std::abs(o.ymag));
        cam.file_aspect = static_cast<float>(std::abs(o.xmag / o.ymag));
        // An orthographic near plane may be 0; checkCamera() wants it positive.
        cam.z_near = static_cast<float>(std::max(o.znear, o.zfar * 1e-6));
        cam.z_far = static_cast<float>(o.zfar);
    } else {
        const auto& p = file_camera.perspective;
        if (!std::isfinite(p.yfov) || p.yfov <= 0.0 || p.yfov >= 3.14159)
            fail(who + ": yfov must be in (0, pi)");
        if (!std::isfinite(p.znear) || p.znear <= 0.0) fail(who + ": znear must be > 0");
        if (!std::isfinite(p.zfar) || (p.zfar != 0.0 && p.zfar <= p.znear))
            fail(who + ": zfar must be > znear");
        if (!std::isfinite(p.aspectRatio) || p.aspectRatio < 0.0) fail(who + ": aspectRatio must be > 0");
        cam.fov_y_deg = static_cast<float>(p.yfov * 180.0 / 3.14159265358979323846);
        cam.z_near = static_cast<float>(p.znear);
        cam.file_aspect = static_cast<float>(p.aspectRatio);
    }
    // glTF cameras look down their local -Z with +Y up.
    cam.position = glm::vec3(camera_world_ * glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    glm::vec3 forward = glm::vec3(camera_world_ * glm::vec4(0.0f, 0.0f, -1.0f, 0.0f));
    glm::vec3 up = glm::vec3(camera_world_ * glm::vec4(0.0f, 1.0f, 0.0f, 0.0f));
    if (!(glm::length(forward) > 1e-8f) || !(glm::length(up) > 1e-8f)) {
        fail("node " + std::to_string(camera_node_) + ": the camera's transform is degenerate");
    }
    forward = glm::normalize(forward);
    cam.up = glm::normalize(up);
    // The target only fixes a direction; put it at the scene's depth so orbiting tools have a
    // sensible pivot.
    float distance = glm::length(centre - cam.position);
    if (!(distance > 1e-4f)) distance = 1.0f;
    cam.target = cam.position + forward * distance;
    if (cam.orthographic) {
        // z_far was set above.
    } else if (file_camera.perspective.zfar > 0.0) {
        cam.z_far = static_cast<float>(file_camera.perspective.zfar);
    } else {
        // Infinite projection in the file: a finite far plane well behind the whole scene.
        cam.z_far = std::max(cam.z_near * 1000.0f, 2.0f * (glm::length(centre - cam.position) + radius));
    }
    checkCamera();
}

// Huge but finite coordinates can still overflow the float arithmetic above; a camera with an
// infinite or NaN field would only fail later, in the renderer, with a black image.
void Converter::checkCamera() const {
    const Camera& cam = scene_.camera;
    if (!finiteVec(cam.position) || !finiteVec(cam.target) || !finiteVec(cam.up) ||
        !std::isfinite(cam.fov_y_deg) || !std::isfinite(cam.z_near) || !std::isfinite(cam.z_far) ||
        !std::isfinite(cam.file_aspect) || !(cam.z_near > 0.0f) || !(cam.z_far > cam.z_near) ||
        cam.position == cam.target) {
        fail(std::string(scene_.has_camera ? "the file's camera" : "the default camera framing the scene") +
             " is not finite or not valid (are the scene's coordinates within float range?)");
    }
}

}  // namespace shaderlab::gltf_detail
