// The glTF loader's mesh primitives: one primitive of one mesh becomes one shaderlab Mesh,
// converted once however many nodes draw it. Its attributes (POSITION, NORMAL, TEXCOORD_0,
// TEXCOORD_1, COLOR_0, TANGENT) come from accessors or from the Draco decoder's output; strips and
// fans become triangle lists; without NORMAL it gets flat normals (its vertices un-shared), and
// without TANGENT but with texcoords, MikkTSpace tangents (tangent_space.cpp).
// What it does not: read or check bytes (gltf_accessors.cpp does, for every read here), skip
// points and lines or check the material (gltf_nodes.cpp, before it asks for a primitive), or
// apply skins and morph targets (warned about once per mesh; drawn in the base pose).
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "gltf_converter.h"
#include "tangent_space.h"

namespace shaderlab::gltf_detail {

// What the steps of convertPrimitive share about the primitive being converted.
struct PrimitiveInput {
    const tinygltf::Primitive& prim;
    std::string label;  // "mesh 'torus'", or "mesh 3" when it has no name
    std::string where;  // the label, then " primitive N" when the mesh has several
    // Filled by decodeDraco for a compressed primitive.
    std::map<std::string, std::pair<std::vector<float>, std::size_t>> draco_attributes;
    std::vector<std::uint32_t> draco_indices;
    bool draco = false;
};

namespace {

glm::vec3 faceNormal(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
    const glm::vec3 n = glm::cross(b - a, c - a);
    const float len = glm::length(n);
    // A degenerate triangle has no normal; any unit vector keeps the shader's normalize() finite.
    return len > 0.0f && std::isfinite(len) ? n / len : glm::vec3(0.0f, 0.0f, 1.0f);
}

// Triangle-list indices for a primitive's mode; strips and fans as the glTF 2.0 specification
// (3.7.2.1) numbers their triangles, so the winding of every triangle matches the first's.
std::vector<std::uint32_t> triangleList(int mode, const std::vector<std::uint32_t>& in) {
    if (mode == TINYGLTF_MODE_TRIANGLE_STRIP || mode == TINYGLTF_MODE_TRIANGLE_FAN) {
        std::vector<std::uint32_t> out;
        if (in.size() < 3) return out;
        out.reserve((in.size() - 2) * 3);
        for (std::size_t i = 0; i + 2 < in.size(); ++i) {
            if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
                out.insert(out.end(), {in[i], in[i + 1 + i % 2], in[i + 2 - i % 2]});
            } else {
                out.insert(out.end(), {in[i + 1], in[i + 2], in[0]});
            }
        }
        return out;
    }
    return in;
}

}  // namespace

std::string Converter::meshLabel(std::size_t mesh_index) const {
    const std::string& name = model_.meshes[mesh_index].name;
    return name.empty() ? "mesh " + std::to_string(mesh_index) : "mesh " + inQuotes(name);
}

int Converter::convertPrimitive(std::size_t mesh_index, std::size_t prim_index) {
    const auto key = std::make_pair(mesh_index, prim_index);
    if (const auto it = converted_.find(key); it != converted_.end()) return it->second;

    const tinygltf::Mesh& src = model_.meshes[mesh_index];
    const tinygltf::Primitive& prim = src.primitives[prim_index];
    const std::string label = meshLabel(mesh_index);
    const std::string where =
        label + (src.primitives.size() > 1 ? " primitive " + std::to_string(prim_index) : "");

    Mesh mesh;
    mesh.name = src.name.empty() ? "mesh" + std::to_string(mesh_index) : src.name;
    if (src.primitives.size() > 1) mesh.name += "#" + std::to_string(prim_index);

    if (prim.attributes.count("POSITION") == 0) fail(where + " has no POSITION attribute");
    if (!prim.targets.empty() && warned_.insert("morph " + label).second) {
        warnings_.push_back(where + ": " + std::to_string(prim.targets.size()) +
                            " morph targets ignored; drawn in its base shape");
    }

    // Draco-compressed primitives bring their attributes and indices decoded.
    PrimitiveInput in{prim, label, where, {}, {}, false};
    if (prim.extensions.count(kDraco) != 0)
        decodeDraco(prim, where, &in.draco_attributes, &in.draco_indices, &in.draco);

    const std::size_t vertex_count = readAttributes(in, &mesh);
    mesh.indices = triangleIndices(&in, vertex_count);
    if (mesh.normals.empty()) makeFlatNormals(where, &mesh);
    if (mesh.tangents.empty() && mesh.had_texcoords) {
        mesh.tangents = generateTangents(mesh.positions, mesh.normals, mesh.texcoords, mesh.indices);
        mesh.tangents_generated = true;
    }

    total_vertices_ += mesh.positions.size();
    total_indices_ += mesh.indices.size();
    if (total_vertices_ > kMaxVertices || total_indices_ > kMaxIndices) {
        fail("the scene has more than " + std::to_string(kMaxVertices) + " vertices or " +
             std::to_string(kMaxIndices) + " indices");
    }

    scene_.meshes.push_back(std::move(mesh));
    const int id = static_cast<int>(scene_.meshes.size() - 1);
    converted_[key] = id;
    return id;
}

// Reads attribute `name` as floats into `values`; returns its element count, 0 when the primitive
// has none (`values` is then left as it was).
std::size_t Converter::readAttribute(const PrimitiveInput& in, const char* name, Use use,
                                     std::vector<float>* values, std::size_t* components) const {
    const auto it = in.prim.attributes.find(name);
    if (it == in.prim.attributes.end()) return 0;
    const std::string role = std::string(name) + " of " + in.label;
    if (in.draco) {
        const auto d = in.draco_attributes.find(name);
        if (d != in.draco_attributes.end()) {
            *values = d->second.first;
            *components = d->second.second;
            const std::size_t want = use == Use::Texcoord  ? 2
                                     : use == Use::Color   ? *components
                                     : use == Use::Tangent ? 4
                                                           : 3;
            if (*components != want || (use == Use::Color && want < 3))
                fail(in.where + ": Draco attribute " + name + " has " + std::to_string(*components) +
                     " components");
            return values->size() / *components;
        }
    }
    return readAccessor(it->second, role, use, values, components);
}

// Reads the vertex attributes into `mesh_out` and returns the vertex count (POSITION's); every
// other attribute must have as many elements.
std::size_t Converter::readAttributes(const PrimitiveInput& in, Mesh* mesh_out) {
    Mesh& mesh = *mesh_out;
    const std::string& label = in.label;
    const std::string& where = in.where;
    std::vector<float> values;
    const auto read = [&](const char* name, Use use, std::size_t* components) {
        return readAttribute(in, name, use, &values, components);
    };
    std::size_t components = 0;
    const std::size_t vertex_count = read("POSITION", Use::Position, &components);
    if (!std::all_of(values.begin(), values.end(), [](float v) { return std::isfinite(v); })) {
        fail(where + ": POSITION contains non-finite values");
    }
    mesh.positions.resize(vertex_count);
    for (std::size_t i = 0; i < vertex_count; ++i) {
        mesh.positions[i] = glm::vec3(values[3 * i], values[3 * i + 1], values[3 * i + 2]);
    }
    const auto sameCount = [&](const char* name, std::size_t n) {
        if (n != vertex_count) {
            fail(where + ": " + name + " has " + std::to_string(n) + " elements but POSITION has " +
                 std::to_string(vertex_count));
        }
    };

    if (const std::size_t n = read("NORMAL", Use::Normal, &components)) {
        sameCount("NORMAL", n);
        mesh.normals.resize(n);
        for (std::size_t i = 0; i < n; ++i) {
            const glm::vec3 v(values[3 * i], values[3 * i + 1], values[3 * i + 2]);
            const float len = glm::length(v);
            // The spec requires unit normals; exporters are sloppy, and a shader that forgets to
            // normalize should not be graded on someone else's rounding.
            mesh.normals[i] = len > 0.0f && std::isfinite(len) ? v / len : glm::vec3(0.0f, 0.0f, 1.0f);
        }
    }

    // glTF puts (0, 0) at an image's top-left, OpenGL texture coordinates at the row uploaded
    // first, which the framework makes the image's bottom row: t = 1 - v keeps an image upright on
    // a mesh as in a fullscreen pass.
    const auto texcoords = [&](const char* name, std::vector<glm::vec2>* out) {
        const std::size_t n = read(name, Use::Texcoord, &components);
        if (n == 0) return false;
        sameCount(name, n);
        out->resize(n);
        for (std::size_t i = 0; i < n; ++i) {
            const glm::vec2 uv(values[2 * i], 1.0f - values[2 * i + 1]);
            (*out)[i] = std::isfinite(uv.x) && std::isfinite(uv.y) ? uv : glm::vec2(0.0f);
        }
        return true;
    };
    mesh.had_texcoords = texcoords("TEXCOORD_0", &mesh.texcoords);
    if (!mesh.had_texcoords) mesh.texcoords.assign(vertex_count, glm::vec2(0.0f));
    texcoords("TEXCOORD_1", &mesh.texcoords1);

    if (const std::size_t n = read("COLOR_0", Use::Color, &components)) {
        sameCount("COLOR_0", n);
        mesh.colors.resize(n);
        for (std::size_t i = 0; i < n; ++i) {
            glm::vec4 c(1.0f);
            for (std::size_t k = 0; k < components; ++k) c[static_cast<int>(k)] = values[i * components + k];
            mesh.colors[i] = std::isfinite(c.r + c.g + c.b + c.a) ? c : glm::vec4(1.0f);
        }
    }
    if (const std::size_t n = read("TANGENT", Use::Tangent, &components)) {
        sameCount("TANGENT", n);
        mesh.tangents.resize(n);
        for (std::size_t i = 0; i < n; ++i) {
            const glm::vec3 t(values[4 * i], values[4 * i + 1], values[4 * i + 2]);
            const float len = glm::length(t);
            mesh.tangents[i] =
                glm::vec4(len > 0.0f && std::isfinite(len) ? t / len : glm::vec3(1.0f, 0.0f, 0.0f),
                          values[4 * i + 3] < 0.0f ? -1.0f : 1.0f);
        }
    }
    for (const auto& [name, accessor] : in.prim.attributes) {
        (void)accessor;
        if ((name.rfind("JOINTS_", 0) == 0 || name.rfind("WEIGHTS_", 0) == 0) &&
            warned_.insert("skin " + label).second)
            warnings_.push_back(where + ": skinning attributes ignored; drawn in its bind pose");
    }
    return vertex_count;
}

// The primitive's triangles as a list, every index checked against the vertex count.
std::vector<std::uint32_t> Converter::triangleIndices(PrimitiveInput* in, std::size_t vertex_count) const {
    const tinygltf::Primitive& prim = in->prim;
    const std::string& label = in->label;
    const std::string& where = in->where;
    std::vector<std::uint32_t> indices;
    if (in->draco) {
        indices = std::move(in->draco_indices);
    } else if (prim.indices != -1) {
        readAccessor(prim.indices, std::string("indices of ") + label, Use::Indices, &indices);
    } else {
        indices.resize(vertex_count);
        for (std::size_t i = 0; i < vertex_count; ++i) indices[i] = static_cast<std::uint32_t>(i);
    }
    for (std::size_t i = 0; i < indices.size(); ++i) {
        if (indices[i] >= vertex_count) {
            fail((in->draco ? where + " (" + kDraco + ")"
                            : "accessor " + std::to_string(prim.indices) + " (indices of " + label + ")") +
                 ": index " + std::to_string(indices[i]) + " at position " + std::to_string(i) +
                 " is out of range: the primitive has " + std::to_string(vertex_count) + " vertices");
        }
    }
    const int mode = prim.mode == -1 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
    if (mode == TINYGLTF_MODE_TRIANGLES && indices.size() % 3 != 0) {
        fail(where + ": " + std::to_string(indices.size()) + " indices is not a whole number of triangles");
    }
    std::vector<std::uint32_t> triangles = triangleList(mode, indices);
    if (triangles.empty()) fail(where + ": fewer than 3 vertices, so no triangle to draw");
    return triangles;
}

// Flat normals need one vertex per triangle corner: un-share every vertex.
void Converter::makeFlatNormals(const std::string& where, Mesh* mesh_out) {
    Mesh& mesh = *mesh_out;
    const std::size_t corners = mesh.indices.size();
    if (corners > kMaxVertices) fail(where + ": too many triangles to generate flat normals");
    const auto unshare = [&](auto* attribute) {
        if (attribute->empty()) return;
        std::remove_reference_t<decltype(*attribute)> out(corners);
        for (std::size_t i = 0; i < corners; ++i) out[i] = (*attribute)[mesh.indices[i]];
        *attribute = std::move(out);
    };
    unshare(&mesh.positions);
    unshare(&mesh.texcoords);
    unshare(&mesh.texcoords1);
    unshare(&mesh.colors);
    unshare(&mesh.tangents);
    mesh.normals.resize(corners);
    for (std::size_t t = 0; t < corners; t += 3) {
        const glm::vec3 n = faceNormal(mesh.positions[t], mesh.positions[t + 1], mesh.positions[t + 2]);
        mesh.normals[t] = mesh.normals[t + 1] = mesh.normals[t + 2] = n;
    }
    for (std::size_t i = 0; i < corners; ++i) mesh.indices[i] = static_cast<std::uint32_t>(i);
    mesh.had_normals = false;
    warnings_.push_back("normals generated flat for " + where);
}

}  // namespace shaderlab::gltf_detail
