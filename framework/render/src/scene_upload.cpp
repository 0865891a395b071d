// Meshes on the GPU for the lab runner (lab_runner.h): a scene's meshes, uploaded once per scene
// file, the full-screen triangle, and the optional vertex attributes fed per program at draw
// time. Reading the glTF file is the scene library's (gltf_loader.h).
#include <filesystem>
#include <glm/gtc/type_ptr.hpp>

#include "lab_runner.h"
#include "shaderlab/base/timings.h"
#include "shaderlab/scene/gltf_loader.h"

namespace shaderlab::render_detail {

namespace {

// Optional vertex attributes (docs/scenes.md): uploaded the first time a program that declares
// them draws the mesh, and fed as a constant when the mesh lacks them.
struct OptionalAttribute {
    const char* name;
    int components;
    glm::vec4 absent;  // the constant a shader reads when the mesh has no such data
};
constexpr OptionalAttribute kOptionalAttributes[] = {{"a_tangent", 4, {1.0f, 0.0f, 0.0f, 1.0f}},
                                                     {"a_color", 4, {1.0f, 1.0f, 1.0f, 1.0f}},
                                                     {"a_texcoord1", 2, {0.0f, 0.0f, 0.0f, 1.0f}}};

template <typename T>
void uploadAttribute(GLuint buffer, GLuint location, int components, const std::vector<T>& data) {
    glBindBuffer(GL_ARRAY_BUFFER, buffer);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(data.size() * sizeof(T)), data.data(),
                 GL_STATIC_DRAW);
    glEnableVertexAttribArray(location);
    glVertexAttribPointer(location, components, GL_FLOAT, GL_FALSE, 0, nullptr);
}

}  // namespace

std::unique_ptr<GpuMesh> uploadMesh(const Mesh& mesh) {
    auto gpu = std::make_unique<GpuMesh>();
    glGenVertexArrays(1, &gpu->vao);
    glBindVertexArray(gpu->vao);
    glGenBuffers(3, gpu->vbo);
    uploadAttribute(gpu->vbo[0], 0, 3, mesh.positions);
    uploadAttribute(gpu->vbo[1], 1, 3, mesh.normals);
    std::vector<glm::vec2> uv = mesh.texcoords;
    uv.resize(mesh.positions.size(), glm::vec2(0.0f));
    uploadAttribute(gpu->vbo[2], 2, 2, uv);
    glGenBuffers(1, &gpu->ebo);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, gpu->ebo);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER,
                 static_cast<GLsizeiptr>(mesh.indices.size() * sizeof(std::uint32_t)), mesh.indices.data(),
                 GL_STATIC_DRAW);
    gpu->index_count = static_cast<GLsizei>(mesh.indices.size());
    glBindVertexArray(0);
    return gpu;
}

// Points the optional attributes `program` declares at `mesh`'s data (uploading it on first use)
// or at a constant; returns the locations enabled, to disable after the draw.
std::vector<GLuint> bindOptionalAttributes(GpuMesh& mesh, GLuint program) {
    std::vector<GLuint> enabled;
    for (int k = 0; k < kOptionalCount; ++k) {
        const OptionalAttribute& a = kOptionalAttributes[k];
        const GLint location = glGetAttribLocation(program, a.name);
        if (location < 0) continue;
        const auto loc = static_cast<GLuint>(location);
        const Mesh* m = mesh.source;
        const void* data = nullptr;
        std::size_t bytes = 0;
        if (m && k == 0 && m->tangents.size() == m->positions.size()) {
            data = m->tangents.data();
            bytes = m->tangents.size() * sizeof(glm::vec4);
        } else if (m && k == 1 && m->colors.size() == m->positions.size()) {
            data = m->colors.data();
            bytes = m->colors.size() * sizeof(glm::vec4);
        } else if (m && k == 2 && m->texcoords1.size() == m->positions.size()) {
            data = m->texcoords1.data();
            bytes = m->texcoords1.size() * sizeof(glm::vec2);
        }
        if (!data) {
            glDisableVertexAttribArray(loc);
            glVertexAttrib4fv(loc, glm::value_ptr(a.absent));
            continue;
        }
        if (!mesh.optional_vbo[k]) {
            glGenBuffers(1, &mesh.optional_vbo[k]);
            glBindBuffer(GL_ARRAY_BUFFER, mesh.optional_vbo[k]);
            glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(bytes), data, GL_STATIC_DRAW);
        }
        glBindBuffer(GL_ARRAY_BUFFER, mesh.optional_vbo[k]);
        glEnableVertexAttribArray(loc);
        glVertexAttribPointer(loc, a.components, GL_FLOAT, GL_FALSE, 0, nullptr);
        enabled.push_back(loc);
    }
    return enabled;
}

// One triangle that covers the viewport; texcoords run 0..1 across the visible part.
std::unique_ptr<GpuMesh> fullscreenTriangle() {
    Mesh m;
    m.positions = {{-1.0f, -1.0f, 0.0f}, {3.0f, -1.0f, 0.0f}, {-1.0f, 3.0f, 0.0f}};
    m.normals = {{0.0f, 0.0f, 1.0f}, {0.0f, 0.0f, 1.0f}, {0.0f, 0.0f, 1.0f}};
    m.texcoords = {{0.0f, 0.0f}, {2.0f, 0.0f}, {0.0f, 2.0f}};
    m.indices = {0, 1, 2};
    return uploadMesh(m);
}

const LabRunner::LoadedScene* LabRunner::loadScene(const SceneSpec& scene_spec) {
    static const LoadedScene kEmpty;
    if (scene_spec.file.empty()) return &kEmpty;
    const std::string path = (std::filesystem::path(spec_.labs_root) / scene_spec.file).string();
    auto it = scenes_.find(path);
    if (it != scenes_.end()) return &it->second;
    ScopedTiming timing("scene_load", spec_.id, scene_spec.file);
    LoadedScene loaded;
    const SceneLoadResult r = loadGltfScene(path, &loaded.scene);
    // The loader's warnings are the lab author's to read (a skipped primitive, an ignored
    // extension), never dropped; a file that does not load fails this scene only.
    // Named from the lab folder, as every diagnostic file is: scene files sit beside the labs.
    for (const std::string& w : r.warnings) warnOnce("../" + scene_spec.file, w);
    if (!r.ok) {
        loaded.error = r.error;
        return &scenes_.emplace(path, std::move(loaded)).first->second;
    }
    for (const Mesh& m : loaded.scene.meshes) loaded.meshes.push_back(uploadMesh(m));
    LoadedScene& stored = scenes_.emplace(path, std::move(loaded)).first->second;
    for (std::size_t i = 0; i < stored.meshes.size(); ++i) stored.meshes[i]->source = &stored.scene.meshes[i];
    return &stored;
}

}  // namespace shaderlab::render_detail
