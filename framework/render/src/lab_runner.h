// The lab runner behind renderLab() (renderer.h), declared once for the files that define its
// parts: renderer.cpp (sources, programs, the passes a lab needs, the scene loop), lab_targets.cpp
// (framebuffers, attachments, depth, ping-pong copies, read-back), pass_state.cpp (a pass's GL
// state), pass_inputs.cpp (textures and samplers), pass_uniforms.cpp (lab.json and framework
// uniforms), pass_draw.cpp (one run of a pass, the loop guard) and scene_upload.cpp (meshes on the
// GPU). Private to the render library.
//
// LabRunner owns every GL object of one lab: programs (one per shader pair and attachment
// layout), targets (two copies of those a pass reads while drawing into them, swapped after each
// run), input textures (made per sampler type on first use), sampler objects, meshes. Each pass
// run starts from a known state: the program's uniforms back at their linked defaults, every
// sampler of the program on its own texture unit, every other unit empty (glTF material textures
// excepted: units of their own, bound per draw, material_textures.h), the pass's render state
// applied in full. Nothing here knows a lab by name.
#pragma once

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "input_textures.h"
#include "material_textures.h"
#include "shaderlab/gl/gl.h"
#include "shaderlab/render/renderer.h"
#include "shaderlab/scene/camera.h"
#include "uniform_values.h"

namespace shaderlab::render_detail {

// How many optional vertex attributes a mesh may carry (a_tangent, a_color, a_texcoord1;
// scene_upload.cpp).
constexpr int kOptionalCount = 3;

struct GpuMesh {
    GLuint vao = 0, vbo[3] = {0, 0, 0}, ebo = 0;
    GLsizei index_count = 0;
    const Mesh* source = nullptr;                     // for the optional attributes; null: none
    GLuint optional_vbo[kOptionalCount] = {0, 0, 0};  // 0 until first used
    GpuMesh() = default;
    GpuMesh(const GpuMesh&) = delete;
    GpuMesh& operator=(const GpuMesh&) = delete;
    ~GpuMesh() {
        if (ebo) glDeleteBuffers(1, &ebo);
        glDeleteBuffers(3, vbo);
        glDeleteBuffers(kOptionalCount, optional_vbo);
        if (vao) glDeleteVertexArrays(1, &vao);
    }
};

// Points the optional attributes `program` declares at `mesh`'s data (uploading it on first use)
// or at a constant; returns the locations enabled, to disable after the draw.
std::vector<GLuint> bindOptionalAttributes(GpuMesh& mesh, GLuint program);

// A mesh's positions, normals, texcoords (locations 0, 1, 2) and indices on the GPU; `source`
// is left for the caller to set.
std::unique_ptr<GpuMesh> uploadMesh(const Mesh& mesh);

// One triangle that covers the viewport; texcoords run 0..1 across the visible part.
std::unique_ptr<GpuMesh> fullscreenTriangle();

// A target's GL objects: colour textures per attachment (two sets when ping-ponged), depth, and a
// framebuffer per (set, cube face).
struct TargetGl {
    const TargetSpec* spec = nullptr;
    DepthMode depth = DepthMode::None;  // what was allocated: the spec's, or none when unused
    int buffers = 1;
    int front = 0;  // the set holding the latest result
    std::vector<GLuint> color[2];
    GLuint depth_renderbuffer = 0, depth_texture = 0;
    std::map<std::pair<int, int>, GLuint> fbos;
    bool mipmapped = false;
    bool fullscreen_drawn = false;  // this scene: coverage is the whole frame

    TargetGl() = default;
    TargetGl(const TargetGl&) = delete;
    TargetGl& operator=(const TargetGl&) = delete;
    ~TargetGl() {
        for (auto& [key, fbo] : fbos) glDeleteFramebuffers(1, &fbo);
        for (auto& set : color)
            if (!set.empty()) glDeleteTextures(static_cast<GLsizei>(set.size()), set.data());
        if (depth_renderbuffer) glDeleteRenderbuffers(1, &depth_renderbuffer);
        if (depth_texture) glDeleteTextures(1, &depth_texture);
    }
    bool cube() const { return spec->type == TargetType::Cube; }
    int faces() const { return cube() ? 6 : 1; }
    GLenum textureTarget() const { return cube() ? GL_TEXTURE_CUBE_MAP : GL_TEXTURE_2D; }
};

// The GL internal format of a target's colour textures (lab_targets.cpp).
GLenum targetInternalFormat(TargetFormat f);

// A pass's render state, applied in full (pass_state.cpp), and its clears.
void applyState(const RenderState& s, bool srgb_target, bool program_point_size);
void clearTarget(const RenderState& s, bool has_depth);

class LabRunner {
  public:
    LabRunner(const LabSpec& spec, const std::string& shader_dir, const RenderOptions& options,
              LabRender* out)
        : spec_(spec),
          shader_dir_(shader_dir),
          options_(options),
          out_(*out),
          origin_((std::filesystem::path(spec.lab_dir) / "lab.json").string()) {}

    ~LabRunner();

    bool prepare();
    bool renderScene(const SceneSpec& scene_spec);

  private:
    struct LoadedScene {
        Scene scene;
        std::vector<std::unique_ptr<GpuMesh>> meshes;
        std::string error;  // the file did not load: "<path>: <problem>"
    };
    struct PassCamera {
        Camera camera;
        PassCameraValues values;
    };
    struct SceneContext {
        const SceneSpec* spec;
        const LoadedScene* scene;
        std::vector<ResolvedLight> lights;
        std::vector<PassCamera> cameras;  // by pass index
        SceneRender* out;
    };
    // What the steps of one pass run share (runPass).
    struct PassRun {
        const PassSpec& pass;
        const ShaderProgram& prog;
        const std::string& file;  // the fragment stage: where a framework uniform's warning goes
        const TargetGl& target;
        const PassCamera& pc;
        const SceneContext& ctx;
    };

    void report(const std::string& event) const {
        if (options_.progress) options_.progress(event);
    }
    bool fail(RenderStatus status, const std::string& message) {
        if (out_.status == RenderStatus::Ok) {
            out_.status = status;
            out_.message = message;
        }
        return false;
    }
    void createLoopGuard();
    bool checkLoopGuard(const PassSpec& pass, const std::string& scene);
    // A problem with a lab.json key: the lab's file is named, so it reads like a parser message.
    bool failAt(RenderStatus status, const std::string& path_and_problem) {
        out_.diagnostics.push_back({"lab.json", 0, 0, "error", path_and_problem});
        return fail(status, origin_ + ": " + path_and_problem);
    }
    void warnOnce(const std::string& file, const std::string& message) {
        if (warned_.insert(file + '\n' + message).second)
            out_.diagnostics.push_back({file, 0, 0, "warning", message});
    }
    bool isStudentFile(const std::string& f) const {
        return std::find(spec_.student_files.begin(), spec_.student_files.end(), f) !=
               spec_.student_files.end();
    }
    FileText readProgramFile(const std::string& file, std::string* case_note = nullptr) const;
    std::string programKey(const PassSpec& pass) const;
    const ShaderProgram& programOf(const PassSpec& pass) const { return programs_.at(programKey(pass)); }

    bool readSources();
    bool buildPrograms();
    void checkOutputs(const ShaderProgram& prog, const PassSpec& pass, const TargetSpec& target);
    bool createTargets();
    void findNeededPasses();
    const LoadedScene* loadScene(const SceneSpec& scene_spec);
    void blankTargets();
    GLuint sampler(TextureFilter filter, TextureWrap wrap, bool shadow);
    bool bindInputs(std::size_t pass_index, const ShaderProgram& prog, const std::string& scene);
    GLuint standInTexture(const StandIn& stand_in, const TargetGl& target);
    void dropStandIns();
    bool setLabUniforms(const PassSpec& pass, const ShaderProgram& prog, const SceneContext& ctx);
    bool runPass(std::size_t index, int iteration, bool last_iteration, SceneContext& ctx);
    void setFrameUniforms(const PassRun& run, int iteration);
    void setLightUniforms(const PassRun& run);
    void drawFaces(const PassRun& run, int write);
    void drawItems(const PassRun& run, const MaterialWarning& scene_warning);
    void drawMesh(const PassRun& run, const MaterialWarning& scene_warning, GpuMesh* mesh,
                  const glm::mat4& model, const Material& material);
    void readBack(const PassRun& run);
    void setFramework(const ShaderProgram& prog, const std::string& file, const char* name, GLenum type,
                      const std::function<void(GLint)>& set);
    void copyFrontToBack(TargetGl& t);

    const LabSpec& spec_;
    const std::string& shader_dir_;
    const RenderOptions& options_;
    LabRender& out_;
    std::string origin_;

    std::map<std::string, std::string> sources_;  // program file -> text
    std::map<std::string, ShaderProgram> programs_;
    std::map<std::string, std::unique_ptr<TargetGl>> targets_;
    std::vector<bool> needed_;  // per pass: whether a graded image depends on it (see findNeededPasses)
    std::map<std::string, InputTexture> input_textures_;
    std::map<std::tuple<int, int, bool>, GLuint> samplers_;
    std::map<std::string, LoadedScene> scenes_;
    std::unique_ptr<GpuMesh> fullscreen_;
    GLuint empty_vao_ = 0;
    std::set<std::string> warned_;
    std::vector<std::pair<GLuint, GLenum>> bound_units_;  // (unit, texture target) of the last pass
    std::string all_program_text_;                        // every program's prepared sources
    GLuint loop_guard_ = 0;                               // see createLoopGuard()
    std::set<std::string> probed_programs_;               // drawn once in strips (loop_probe.h)
    MaterialTextures material_textures_;                  // glTF material textures, bound per draw
    std::map<const StandIn*, GLuint> stand_in_textures_;  // this scene's (RenderOptions::stand_ins)
};

}  // namespace shaderlab::render_detail
