// The glTF writer of shaderlab_make_scenes: procedural meshes computed in double (Vertex,
// Geometry), the helpers that wind and grid them, and SceneWriter, which accumulates one glTF 2.0
// model with a single buffer and writes it with tinygltf (keys sorted, no timestamps, so the same
// geometry gives the same bytes). make_scenes.cpp writes the bundled scenes with it,
// lab_assets.cpp the labs' own meshes. It does not write images: a texture is a PNG beside the
// scene, written by the caller.
#pragma once

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <limits>
#include <string>
#include <system_error>
#include <vector>

namespace shaderlab::scenegen {

namespace fs = std::filesystem;

constexpr double kPi = 3.14159265358979323846;

// Computed in double: the float rounding happens once, when vertices are stored, so libm
// differences in the last double bit almost never change a stored byte.
struct Vertex {
    glm::dvec3 position;
    glm::dvec3 normal;
    glm::dvec2 uv;
    glm::dvec4 tangent{1.0, 0.0, 0.0, 1.0};  // glTF TANGENT: xyz unit, w = +1 or -1 (handedness)
};

struct Geometry {
    std::vector<Vertex> vertices;
    std::vector<std::uint32_t> indices;
    bool write_normals = true;
    bool write_tangents = false;  // TANGENT (VEC4) beside NORMAL; Layout::Separate only
};

// Makes every triangle wind counter-clockwise seen from the side its vertex normals point to,
// which is what back-face culling in the labs expects.
void orientTriangles(Geometry* g);

// Two triangles per cell of a (rows + 1) x (cols + 1) vertex grid stored row by row, then wound
// counter-clockwise; `skip_pole_triangles` leaves out the degenerate triangle of each cell in the
// first and last rows (a UV sphere's poles).
void addGridTriangles(Geometry* g, int rows, int cols, bool skip_pole_triangles);

// Per-vertex tangents (Vertex::tangent) from the texture coordinates, by E. Lengyel's method,
// "Computing Tangent Space Basis Vectors for an Arbitrary Mesh" (Terathon Software, 2001; also
// Mathematics for 3D Game Programming and Computer Graphics, 3rd ed., 2012, section 7.8): per
// triangle, the derivatives of the position along s and t are solved from its edges and their
// texture-coordinate differences; each vertex sums those of its triangles; the s-derivative is
// made orthogonal to the vertex normal (Gram-Schmidt) and normalised, and w = -1 where
// cross(normal, tangent) points against the summed t-derivative (a mirrored texture). s = u and
// t = 1 - v: glTF 2.0's bitangent, cross(normal, tangent.xyz) * w (3.7.2.1), must point up the
// image, where a normal texture's +Y points (3.9.3), and up the image is decreasing v. Vertices
// are never split: a mesh whose texture is mirrored gives each side its own seam vertices.
void computeTangents(Geometry* g);

// UV sphere, +Y up, seam at -Z: u = phi / 2pi around from +Z towards +X, v = theta / pi from the
// north pole down.
Geometry uvSphere(double radius, int segments, int rings);

enum class Layout { Separate, Interleaved };

// Accumulates one glTF model with a single buffer.
class SceneWriter {
  public:
    SceneWriter() {
        model_.asset.version = "2.0";
        model_.asset.generator = "shaderlab_make_scenes";
        model_.buffers.emplace_back();
        model_.scenes.emplace_back();
        model_.defaultScene = 0;
    }

    int addMaterial(const std::string& name, const glm::dvec4& color) {
        tinygltf::Material m;
        m.name = name;
        m.pbrMetallicRoughness.baseColorFactor = {color.r, color.g, color.b, color.a};
        m.pbrMetallicRoughness.metallicFactor = 0.0;
        m.pbrMetallicRoughness.roughnessFactor = 0.5;
        m.emissiveFactor = {0.0, 0.0, 0.0};  // the writer would print an empty array otherwise
        model_.materials.push_back(m);
        return static_cast<int>(model_.materials.size() - 1);
    }

    int addMesh(const std::string& name, const Geometry& g, int material, int index_type, Layout layout) {
        tinygltf::Primitive prim;
        prim.mode = TINYGLTF_MODE_TRIANGLES;
        prim.material = material;
        const std::size_t n = g.vertices.size();
        const bool normals = g.write_normals;
        if (g.write_tangents && layout != Layout::Separate) {
            std::fprintf(stderr, "shaderlab_make_scenes: mesh %s: tangents need Layout::Separate\n",
                         name.c_str());
            std::exit(1);
        }
        if (layout == Layout::Interleaved) {
            // position, normal, uv in one 32-byte element: exercises byteStride and byteOffset.
            const std::size_t stride = normals ? 32 : 20;
            std::vector<unsigned char> bytes(n * stride);
            for (std::size_t i = 0; i < n; ++i) {
                unsigned char* e = bytes.data() + i * stride;
                putVec(e, g.vertices[i].position);
                if (normals) putVec(e + 12, g.vertices[i].normal);
                putVec(e + (normals ? 24 : 12), g.vertices[i].uv);
            }
            const int view = addView(bytes, TINYGLTF_TARGET_ARRAY_BUFFER, stride);
            prim.attributes["POSITION"] = addAccessor(view, 0, TINYGLTF_TYPE_VEC3, n, positionBounds(g));
            if (normals) prim.attributes["NORMAL"] = addAccessor(view, 12, TINYGLTF_TYPE_VEC3, n);
            prim.attributes["TEXCOORD_0"] = addAccessor(view, normals ? 24 : 12, TINYGLTF_TYPE_VEC2, n);
        } else {
            std::vector<unsigned char> pos(n * 12), nrm(n * 12), uv(n * 8);
            for (std::size_t i = 0; i < n; ++i) {
                putVec(pos.data() + i * 12, g.vertices[i].position);
                putVec(nrm.data() + i * 12, glm::normalize(g.vertices[i].normal));
                putVec(uv.data() + i * 8, g.vertices[i].uv);
            }
            prim.attributes["POSITION"] = addAccessor(addView(pos, TINYGLTF_TARGET_ARRAY_BUFFER), 0,
                                                      TINYGLTF_TYPE_VEC3, n, positionBounds(g));
            if (normals) {
                prim.attributes["NORMAL"] =
                    addAccessor(addView(nrm, TINYGLTF_TARGET_ARRAY_BUFFER), 0, TINYGLTF_TYPE_VEC3, n);
            }
            prim.attributes["TEXCOORD_0"] =
                addAccessor(addView(uv, TINYGLTF_TARGET_ARRAY_BUFFER), 0, TINYGLTF_TYPE_VEC2, n);
            if (g.write_tangents) {
                std::vector<unsigned char> tan(n * 16);
                for (std::size_t i = 0; i < n; ++i) putVec(tan.data() + i * 16, g.vertices[i].tangent);
                prim.attributes["TANGENT"] =
                    addAccessor(addView(tan, TINYGLTF_TARGET_ARRAY_BUFFER), 0, TINYGLTF_TYPE_VEC4, n);
            }
        }
        prim.indices = addIndices(g.indices, index_type, n);

        tinygltf::Mesh mesh;
        mesh.name = name;
        mesh.primitives.push_back(prim);
        model_.meshes.push_back(mesh);
        return static_cast<int>(model_.meshes.size() - 1);
    }

    // Adds a node to the scene's roots (or under `parent`).
    int addNode(const std::string& name, int parent = -1) {
        tinygltf::Node node;
        node.name = name;
        model_.nodes.push_back(node);
        const int index = static_cast<int>(model_.nodes.size() - 1);
        if (parent < 0) {
            model_.scenes[0].nodes.push_back(index);
        } else {
            model_.nodes[static_cast<std::size_t>(parent)].children.push_back(index);
        }
        return index;
    }

    tinygltf::Node& node(int index) { return model_.nodes[static_cast<std::size_t>(index)]; }

    int addMeshNode(const std::string& name, int mesh, const glm::dvec3& translation = glm::dvec3(0.0)) {
        const int n = addNode(name);
        node(n).mesh = mesh;
        if (translation != glm::dvec3(0.0))
            node(n).translation = {translation.x, translation.y, translation.z};
        return n;
    }

    // A camera node at `eye` looking at `target` with +Y up: glTF cameras look down their -Z.
    void addCamera(const glm::dvec3& eye, const glm::dvec3& target) {
        tinygltf::Camera cam;
        cam.name = "camera";
        cam.type = "perspective";
        cam.perspective.yfov = round6(45.0 * kPi / 180.0);
        cam.perspective.znear = 0.1;
        cam.perspective.zfar = 100.0;  // the writer always writes zfar; 0 would be invalid glTF
        cam.perspective.aspectRatio = 1.0;
        model_.cameras.push_back(cam);
        const int n = addNode("camera");
        node(n).camera = static_cast<int>(model_.cameras.size() - 1);
        node(n).translation = {round6(eye.x), round6(eye.y), round6(eye.z)};
        setRotation(n, lookRotation(target - eye));
    }

    void addPointLight(const glm::dvec3& position, const glm::dvec3& color, double intensity) {
        const int n = addLight("point", color, intensity);
        node(n).translation = {position.x, position.y, position.z};
    }

    void addDirectionalLight(const glm::dvec3& direction, const glm::dvec3& color, double intensity) {
        const int n = addLight("directional", color, intensity);
        setRotation(n, lookRotation(direction));
    }

    // Writes `<dir>/<name>.gltf` + `<name>.bin`, or `<dir>/<name>.glb`.
    bool write(const fs::path& dir, const std::string& name, bool binary) {
        tinygltf::Buffer& buffer = model_.buffers[0];
        pad(&buffer.data);
        buffer.uri = binary ? "" : name + ".bin";
        const fs::path file = dir / (name + (binary ? ".glb" : ".gltf"));
        tinygltf::TinyGLTF gltf;
        if (!gltf.WriteGltfSceneToFile(&model_, file.string(), false, false, true, binary)) {
            std::fprintf(stderr, "shaderlab_make_scenes: cannot write %s\n", file.string().c_str());
            return false;
        }
        // The writer does not check its streams; a full disk would otherwise pass silently.
        std::error_code ec;
        const bool ok = fs::file_size(file, ec) > 0 && !ec &&
                        (binary || fs::file_size(dir / buffer.uri, ec) == buffer.data.size());
        if (!ok || ec) {
            std::fprintf(stderr, "shaderlab_make_scenes: %s was not written completely\n",
                         file.string().c_str());
            return false;
        }
        std::printf("wrote %s\n", file.string().c_str());
        return true;
    }

  private:
    // Six decimals keep the JSON readable; "+ 0.0" turns -0 into 0.
    static double round6(double v) { return std::round(v * 1e6) / 1e6 + 0.0; }

    // Rotation whose -Z axis points along `direction`, keeping +Y as close to world up as it can.
    static glm::dquat lookRotation(const glm::dvec3& direction) {
        const glm::dvec3 back = -glm::normalize(direction);
        glm::dvec3 up(0.0, 1.0, 0.0);
        if (std::abs(glm::dot(up, back)) > 0.999) up = glm::dvec3(0.0, 0.0, -1.0);
        const glm::dvec3 right = glm::normalize(glm::cross(up, back));
        const glm::dvec3 true_up = glm::cross(back, right);
        return glm::normalize(glm::quat_cast(glm::dmat3(right, true_up, back)));
    }

    void setRotation(int n, const glm::dquat& q) {
        node(n).rotation = {round6(q.x), round6(q.y), round6(q.z), round6(q.w)};
    }

    int addLight(const std::string& type, const glm::dvec3& color, double intensity) {
        tinygltf::Light light;
        light.name = type + "_light";
        light.type = type;
        light.color = {color.r, color.g, color.b};
        light.intensity = intensity;
        model_.lights.push_back(light);
        const int n = addNode(light.name);
        tinygltf::Value::Object ext;
        ext["light"] = tinygltf::Value(static_cast<int>(model_.lights.size() - 1));
        node(n).extensions["KHR_lights_punctual"] = tinygltf::Value(ext);
        setLightIndex(node(n), static_cast<int>(model_.lights.size() - 1), 0);
        return n;
    }

    // tinygltf 2.8 and later keep a node's light in Node::light and write the extension from it
    // alone (dropping one set by hand); before, only the extension exists. Both give one file.
    template <typename Node>
    static auto setLightIndex(Node& node, int index, int) -> decltype(node.light = index, void()) {
        node.light = index;
    }
    template <typename Node>
    static void setLightIndex(Node&, int, long) {}

    template <typename V>
    static void putVec(unsigned char* dst, const V& v) {
        for (int i = 0; i < V::length(); ++i) {
            const float f = static_cast<float>(v[i]);
            std::memcpy(dst + 4 * i, &f, 4);
        }
    }

    static void pad(std::vector<unsigned char>* data) {
        while (data->size() % 4 != 0) data->push_back(0);
    }

    int addView(const std::vector<unsigned char>& bytes, int target, std::size_t stride = 0) {
        auto& data = model_.buffers[0].data;
        pad(&data);  // accessors need their components aligned
        tinygltf::BufferView view;
        view.buffer = 0;
        view.byteOffset = data.size();
        view.byteLength = bytes.size();
        view.byteStride = stride;
        view.target = target;
        data.insert(data.end(), bytes.begin(), bytes.end());
        model_.bufferViews.push_back(view);
        return static_cast<int>(model_.bufferViews.size() - 1);
    }

    struct Bounds {
        std::vector<double> min, max;
    };

    // POSITION must carry min/max (spec 3.7.2.1); they are taken from the stored floats.
    static Bounds positionBounds(const Geometry& g) {
        Bounds b{std::vector<double>(3, std::numeric_limits<double>::max()),
                 std::vector<double>(3, std::numeric_limits<double>::lowest())};
        for (const Vertex& v : g.vertices) {
            for (int i = 0; i < 3; ++i) {
                const double f = static_cast<float>(v.position[i]);
                b.min[static_cast<std::size_t>(i)] = std::min(b.min[static_cast<std::size_t>(i)], f);
                b.max[static_cast<std::size_t>(i)] = std::max(b.max[static_cast<std::size_t>(i)], f);
            }
        }
        return b;
    }

    int addAccessor(int view, std::size_t offset, int type, std::size_t count, const Bounds& bounds = {}) {
        tinygltf::Accessor acc;
        acc.bufferView = view;
        acc.byteOffset = offset;
        acc.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
        acc.type = type;
        acc.count = count;
        acc.minValues = bounds.min;
        acc.maxValues = bounds.max;
        model_.accessors.push_back(acc);
        return static_cast<int>(model_.accessors.size() - 1);
    }

    int addIndices(const std::vector<std::uint32_t>& indices, int component_type, std::size_t vertex_count) {
        const std::size_t size = component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE    ? 1
                                 : component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 2
                                                                                            : 4;
        if (vertex_count > (std::uint64_t{1} << (8 * size))) {
            std::fprintf(stderr, "shaderlab_make_scenes: %zu vertices do not fit %zu-byte indices\n",
                         vertex_count, size);
            std::exit(1);
        }
        std::vector<unsigned char> bytes(indices.size() * size);
        for (std::size_t i = 0; i < indices.size(); ++i) {
            // Little-endian, as glTF requires; the value fits (checked above).
            for (std::size_t b = 0; b < size; ++b) {
                bytes[i * size + b] = static_cast<unsigned char>((indices[i] >> (8 * b)) & 0xffu);
            }
        }
        tinygltf::Accessor acc;
        acc.bufferView = addView(bytes, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
        acc.componentType = component_type;
        acc.type = TINYGLTF_TYPE_SCALAR;
        acc.count = indices.size();
        model_.accessors.push_back(acc);
        return static_cast<int>(model_.accessors.size() - 1);
    }

    tinygltf::Model model_;
};

constexpr int kUByte = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
constexpr int kUShort = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
constexpr int kUInt = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;

}  // namespace shaderlab::scenegen
