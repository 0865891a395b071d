// What the glTF loader's files share: the caps on what a file may ask for, the error it unwinds
// with, and the Converter that turns a parsed tinygltf::Model into a Scene. Its members are
// defined by stage: gltf_accessors.cpp (buffer views, accessors, sparse data, Draco and meshopt),
// gltf_primitives.cpp (a mesh primitive's attributes and triangles), gltf_materials.cpp (images,
// textures, samplers, materials), gltf_nodes.cpp (the node tree, instancing, lights, bounds, the
// camera) and gltf_loader.cpp (the order they run in).
// What it does not: read the file, check its GLB layout, JSON or required extensions, or guard
// the file system; gltf_loader.cpp does all of that before tinygltf runs, and nothing here reads
// outside the Model it is given.
#pragma once

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "shaderlab/scene/scene.h"

namespace shaderlab::gltf_detail {

// Caps that keep a hostile file from making us allocate or loop without bound. The bundled
// scenes are tens of thousands of vertices; a lab never needs anything near these. Data read
// from a bufferView is already bounded by the file size; the caps matter where a few bytes of
// JSON can ask for a lot: accessors without a bufferView (all zeros), flat-normal expansion,
// and one big mesh instanced by many nodes.
constexpr std::size_t kMaxFileBytes = std::size_t{256} << 20;
constexpr std::size_t kMaxVertices = 10'000'000;     // per accessor and per scene (~320 MB of Mesh)
constexpr std::size_t kMaxIndices = 30'000'000;      // per accessor and per scene
constexpr std::size_t kMaxUnbackedCount = 1u << 20;  // accessors without a bufferView
constexpr std::size_t kMaxDrawItems = 100'000;
constexpr std::size_t kExactBoundsBudget = 20'000'000;  // vertex transforms for exact bounds

// Thrown by the conversion code and caught in loadGltfScene: the checks sit deep in helpers, and
// unwinding to one place keeps each check a single line.
struct LoadError {
    std::string message;
};

[[noreturn]] inline void fail(const std::string& message) { throw LoadError{message}; }

inline std::string inQuotes(const std::string& s) { return "'" + s + "'"; }

// The extensions the loader implements (gltf_loader.cpp checks the file's lists against them).
constexpr const char* kDraco = "KHR_draco_mesh_compression";
constexpr const char* kMeshopt = "EXT_meshopt_compression";
constexpr const char* kQuantization = "KHR_mesh_quantization";
constexpr const char* kInstancing = "EXT_mesh_gpu_instancing";
constexpr const char* kLights = "KHR_lights_punctual";

// Images are kept encoded, never decoded here (the renderer decodes the ones a program samples,
// with its own checks: material_textures.cpp); this keeps tinygltf from running its image
// decoder on untrusted bytes. tinygltf hands over the bytes of a data: URI or an external file;
// an image in a bufferView is read later through the Converter's checked bufferView().
struct ImageBytes {
    std::map<int, std::vector<unsigned char>> by_image;
    std::size_t total = 0;
    std::vector<int> dropped;  // images past the kMaxFileBytes budget
};

// What an accessor is used for decides which layouts are accepted (glTF 2.0 spec, 3.7.2.1;
// KHR_mesh_quantization widens the integer layouts of positions, normals, tangents, texcoords and
// instance transforms).
enum class Use { Position, Normal, Tangent, Texcoord, Color, Indices, Translation, Rotation, Scale };

struct Bytes {
    const unsigned char* data = nullptr;
    std::size_t size = 0;
};

inline bool finite(const std::vector<double>& values) {
    return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
}

// One primitive's input while it is converted (gltf_primitives.cpp).
struct PrimitiveInput;

class Converter {
  public:
    Converter(const tinygltf::Model& model, Scene* scene, std::vector<std::string>* warnings,
              std::set<int> fallback_buffers, ImageBytes* images)
        : model_(model),
          scene_(*scene),
          warnings_(*warnings),
          fallback_buffers_(std::move(fallback_buffers)),
          images_(*images) {}

    void run();

  private:
    // gltf_accessors.cpp
    Bytes bufferView(int index, const std::string& who) const;
    template <typename T>
    std::size_t readAccessor(int index, const std::string& role, Use use, std::vector<T>* out,
                             std::size_t* components_out = nullptr) const;
    std::size_t viewStride(int index) const;
    template <typename T>
    void applySparse(const tinygltf::Accessor& acc, const std::string& who, std::size_t components,
                     std::size_t comp_size, std::vector<T>* out) const;
    void decodeMeshoptViews();
    void decodeDraco(const tinygltf::Primitive& prim, const std::string& where,
                     std::map<std::string, std::pair<std::vector<float>, std::size_t>>* attributes,
                     std::vector<std::uint32_t>* indices, bool* has_indices) const;

    // gltf_primitives.cpp
    std::string meshLabel(std::size_t mesh_index) const;
    int convertPrimitive(std::size_t mesh_index, std::size_t prim_index);
    std::size_t readAttribute(const PrimitiveInput& in, const char* name, Use use, std::vector<float>* values,
                              std::size_t* components) const;
    std::size_t readAttributes(const PrimitiveInput& in, Mesh* mesh);
    std::vector<std::uint32_t> triangleIndices(PrimitiveInput* in, std::size_t vertex_count) const;
    void makeFlatNormals(const std::string& where, Mesh* mesh);

    // gltf_materials.cpp
    void convertImages();
    void convertTextures();
    void convertMaterials();

    // gltf_nodes.cpp
    std::vector<glm::mat4> instanceTransforms(std::size_t node_index) const;
    glm::mat4 localMatrix(std::size_t node_index) const;
    glm::mat4 localMatrixUnchecked(std::size_t node_index) const;
    std::vector<int> rootNodes() const;
    void walkNodes();
    void visitNode(std::size_t node_index, const glm::mat4& world);
    void addLight(std::size_t node_index, const glm::mat4& world);
    void computeBounds();
    void placeCamera();
    void checkCamera() const;

    const tinygltf::Model& model_;
    Scene& scene_;
    std::vector<std::string>& warnings_;
    std::set<int> fallback_buffers_;
    ImageBytes& images_;
    bool quantized_ = false;                                   // KHR_mesh_quantization is used
    std::map<int, std::vector<unsigned char>> decoded_views_;  // meshopt view -> its bytes
    std::map<int, std::size_t> meshopt_strides_;
    std::set<std::string> warned_;                                  // one warning per kind and mesh
    std::map<std::pair<std::size_t, std::size_t>, int> converted_;  // (mesh, primitive) -> Scene mesh
    std::size_t total_vertices_ = 0;
    std::size_t total_indices_ = 0;
    int camera_node_ = -1;
    glm::mat4 camera_world_{1.0f};
};

}  // namespace shaderlab::gltf_detail
