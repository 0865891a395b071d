// shaderlab_make_scenes <out_dir>: writes the glTF 2.0 scenes bundled in labs/scenes/.
//
// Every mesh is built procedurally here (positions, normals, texcoords, indices) and written
// with tinygltf's writer, so the committed scenes can be regenerated and diffed
// (scripts/regenerate_scenes.sh; tests/scenes_fresh_test.cpp fails when they are stale). The
// output is deterministic: no timestamps, geometry computed in double and rounded once to float,
// JSON keys sorted by the writer.
// Each scene has a perspective camera node and a KHR_lights_punctual point light. The scenes
// exercise the loader on purpose: all three index component types, an interleaved bufferView
// with byteStride (torus), a .glb (torus_knot), a mesh without NORMAL (cube_no_normals), a
// non-uniform node scale (nonuniform_scale).
// It does not write textures, animations or anything the labs do not draw.
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

namespace fs = std::filesystem;

namespace shaderlab {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Computed in double: the float rounding happens once, when vertices are stored, so libm
// differences in the last double bit almost never change a stored byte.
struct Vertex {
    glm::dvec3 position;
    glm::dvec3 normal;
    glm::dvec2 uv;
};

struct Geometry {
    std::vector<Vertex> vertices;
    std::vector<std::uint32_t> indices;
    bool write_normals = true;
};

// Makes every triangle wind counter-clockwise seen from the side its vertex normals point to,
// which is what back-face culling in the labs expects. Building each surface with the right
// winding by hand is easy to get wrong per parameterization; checking it here is not.
void orientTriangles(Geometry* g) {
    for (std::size_t t = 0; t + 2 < g->indices.size(); t += 3) {
        const Vertex& a = g->vertices[g->indices[t]];
        const Vertex& b = g->vertices[g->indices[t + 1]];
        const Vertex& c = g->vertices[g->indices[t + 2]];
        const glm::dvec3 face = glm::cross(b.position - a.position, c.position - a.position);
        if (glm::dot(face, a.normal + b.normal + c.normal) < 0.0)
            std::swap(g->indices[t + 1], g->indices[t + 2]);
    }
}

// Two triangles per cell of a (rows + 1) x (cols + 1) vertex grid stored row by row, then wound
// counter-clockwise. A UV sphere's first and last rows collapse to the poles, so there one
// triangle of each cell would be degenerate and is left out.
void addGridTriangles(Geometry* g, int rows, int cols, bool skip_pole_triangles) {
    const auto at = [cols](int i, int j) { return static_cast<std::uint32_t>(i * (cols + 1) + j); };
    for (int i = 0; i < rows; ++i) {
        for (int j = 0; j < cols; ++j) {
            if (!skip_pole_triangles || i != rows - 1)
                g->indices.insert(g->indices.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            if (!skip_pole_triangles || i != 0)
                g->indices.insert(g->indices.end(), {at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    }
    orientTriangles(g);
}

// UV sphere, +Y up, seam at -Z; the poles get one triangle per segment, not a degenerate pair.
Geometry uvSphere(double radius, int segments, int rings) {
    Geometry g;
    for (int i = 0; i <= rings; ++i) {
        const double theta = kPi * i / rings;
        for (int j = 0; j <= segments; ++j) {
            const double phi = 2.0 * kPi * j / segments;
            const glm::dvec3 n(std::sin(theta) * std::sin(phi), std::cos(theta),
                               std::sin(theta) * std::cos(phi));
            g.vertices.push_back({radius * n, n, glm::dvec2(double(j) / segments, double(i) / rings)});
        }
    }
    addGridTriangles(&g, rings, segments, true);
    return g;
}

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
        return n;
    }

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

}  // namespace
}  // namespace shaderlab

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: shaderlab_make_scenes <out_dir>\n");
        return 2;
    }
    const fs::path dir = argv[1];
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec || !fs::is_directory(dir)) {
        std::fprintf(stderr, "shaderlab_make_scenes: cannot create %s\n", dir.string().c_str());
        return 1;
    }
    using namespace shaderlab;
    const bool ok =
        writeSphere(dir, "sphere", 64, 32, kUShort) && writeSphere(dir, "sphere_low_poly", 12, 6, kUByte) &&
        writeTorus(dir) && writeTorusKnot(dir) && writeCube(dir, "cube_flat", true) &&
        writeCube(dir, "cube_no_normals", false) && writeNonuniformScale(dir) && writeGroundPlane(dir);
    return ok ? 0 : 1;
}
