// Executes a lab's passes on the current context; see renderer.h.
#include "shaderlab/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <map>
#include <set>
#include <variant>

#include "shaderlab/gl.h"
#include "shaderlab/gltf_loader.h"
#include "shaderlab/paths.h"

namespace shaderlab {

namespace {

constexpr std::size_t kMaxShaderBytes = 256 * 1024;
constexpr int kMaxLights = 4;

struct GpuMesh {
    GLuint vao = 0, vbo[3] = {0, 0, 0}, ebo = 0;
    GLsizei index_count = 0;
    GpuMesh() = default;
    GpuMesh(const GpuMesh&) = delete;
    GpuMesh& operator=(const GpuMesh&) = delete;
    ~GpuMesh() {
        if (ebo) glDeleteBuffers(1, &ebo);
        glDeleteBuffers(3, vbo);
        if (vao) glDeleteVertexArrays(1, &vao);
    }
};

template <typename T>
void uploadAttribute(GLuint buffer, GLuint location, int components, const std::vector<T>& data) {
    glBindBuffer(GL_ARRAY_BUFFER, buffer);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(data.size() * sizeof(T)), data.data(),
                 GL_STATIC_DRAW);
    glEnableVertexAttribArray(location);
    glVertexAttribPointer(location, components, GL_FLOAT, GL_FALSE, 0, nullptr);
}

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

// One triangle that covers the viewport; texcoords run 0..1 across the visible part.
std::unique_ptr<GpuMesh> fullscreenTriangle() {
    Mesh m;
    m.positions = {{-1.0f, -1.0f, 0.0f}, {3.0f, -1.0f, 0.0f}, {-1.0f, 3.0f, 0.0f}};
    m.normals = {{0.0f, 0.0f, 1.0f}, {0.0f, 0.0f, 1.0f}, {0.0f, 0.0f, 1.0f}};
    m.texcoords = {{0.0f, 0.0f}, {2.0f, 0.0f}, {0.0f, 2.0f}};
    m.indices = {0, 1, 2};
    return uploadMesh(m);
}

struct Target {
    GLuint fbo = 0, color = 0, depth = 0;
    int width = 0, height = 0;
    Target() = default;
    Target(const Target&) = delete;
    Target& operator=(const Target&) = delete;
    ~Target() {
        if (fbo) glDeleteFramebuffers(1, &fbo);
        if (color) glDeleteTextures(1, &color);
        if (depth) glDeleteRenderbuffers(1, &depth);
    }
};

GLint glFilter(TextureFilter f) { return f == TextureFilter::Nearest ? GL_NEAREST : GL_LINEAR; }

GLint glWrap(TextureWrap w) {
    switch (w) {
        case TextureWrap::Repeat:
            return GL_REPEAT;
        case TextureWrap::MirroredRepeat:
            return GL_MIRRORED_REPEAT;
        default:
            return GL_CLAMP_TO_EDGE;
    }
}

void setSampling(GLuint texture, TextureFilter filter, TextureWrap wrap) {
    glBindTexture(GL_TEXTURE_2D, texture);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, glFilter(filter));
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, glFilter(filter));
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, glWrap(wrap));
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, glWrap(wrap));
}

bool createTarget(const TargetSpec& spec, int lab_w, int lab_h, Target* t, std::string* error) {
    t->width = spec.width > 0 ? spec.width : std::max(1, static_cast<int>(std::lround(lab_w * spec.scale)));
    t->height =
        spec.height > 0 ? spec.height : std::max(1, static_cast<int>(std::lround(lab_h * spec.scale)));
    GLenum internal = GL_RGBA32F;
    if (spec.format == TargetFormat::RGBA8) internal = GL_RGBA8;
    if (spec.format == TargetFormat::RGBA16F) internal = GL_RGBA16F;
    glGenTextures(1, &t->color);
    glBindTexture(GL_TEXTURE_2D, t->color);
    glTexImage2D(GL_TEXTURE_2D, 0, static_cast<GLint>(internal), t->width, t->height, 0, GL_RGBA, GL_FLOAT,
                 nullptr);
    setSampling(t->color, spec.filter, spec.wrap);
    glGenRenderbuffers(1, &t->depth);
    glBindRenderbuffer(GL_RENDERBUFFER, t->depth);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, t->width, t->height);
    glGenFramebuffers(1, &t->fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, t->fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, t->color, 0);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, t->depth);
    const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        *error = "target '" + spec.name + "' is incomplete (status 0x" + std::to_string(status) + ")";
        return false;
    }
    return true;
}

void applyState(const RenderState& s) {
    if (s.depth_test) {
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(s.depth_func == DepthFunc::Less        ? GL_LESS
                    : s.depth_func == DepthFunc::LessEqual ? GL_LEQUAL
                                                           : GL_ALWAYS);
    } else {
        glDisable(GL_DEPTH_TEST);
    }
    glDepthMask(s.depth_write ? GL_TRUE : GL_FALSE);
    if (s.cull == CullMode::None) {
        glDisable(GL_CULL_FACE);
    } else {
        glEnable(GL_CULL_FACE);
        glCullFace(s.cull == CullMode::Back ? GL_BACK : GL_FRONT);
    }
    glFrontFace(GL_CCW);
    glPolygonMode(GL_FRONT_AND_BACK, s.polygon_mode == PolygonMode::Line ? GL_LINE : GL_FILL);
    glLineWidth(s.line_width);
    if (s.blend == BlendMode::None) {
        glDisable(GL_BLEND);
    } else {
        glEnable(GL_BLEND);
        if (s.blend == BlendMode::Alpha)
            glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
        else
            glBlendFunc(GL_ONE, GL_ONE);
    }
    GLbitfield clear = 0;
    if (s.clear_color) {
        glClearColor(s.clear_color->r, s.clear_color->g, s.clear_color->b, s.clear_color->a);
        clear |= GL_COLOR_BUFFER_BIT;
    }
    if (s.clear_depth) {
        glClearDepth(1.0);
        clear |= GL_DEPTH_BUFFER_BIT;
    }
    if (clear) {
        glDepthMask(GL_TRUE);  // a disabled depth mask would also mask the clear
        glClear(clear);
        glDepthMask(s.depth_write ? GL_TRUE : GL_FALSE);
    }
}

PassImage readBack(const Target& t, bool with_depth) {
    PassImage img;
    const int w = t.width, h = t.height;
    std::vector<float> rgba(static_cast<std::size_t>(w) * h * 4);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, t.fbo);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_FLOAT, rgba.data());
    img.color = grader::Image(w, h, 4);
    // GL's first row is the bottom one; images are stored top row first.
    for (int y = 0; y < h; ++y) {
        std::copy_n(rgba.data() + static_cast<std::size_t>(h - 1 - y) * w * 4,
                    static_cast<std::size_t>(w) * 4,
                    img.color.pixels.data() + static_cast<std::size_t>(y) * w * 4);
    }
    img.coverage.assign(static_cast<std::size_t>(w) * h, 1);
    if (with_depth) {
        std::vector<float> depth(static_cast<std::size_t>(w) * h);
        glReadPixels(0, 0, w, h, GL_DEPTH_COMPONENT, GL_FLOAT, depth.data());
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                img.coverage[static_cast<std::size_t>(y) * w + x] =
                    depth[static_cast<std::size_t>(h - 1 - y) * w + x] < 1.0f ? 1 : 0;
    }
    return img;
}

std::string glErrorName(GLenum e) {
    switch (e) {
        case GL_INVALID_ENUM:
            return "GL_INVALID_ENUM";
        case GL_INVALID_VALUE:
            return "GL_INVALID_VALUE";
        case GL_INVALID_OPERATION:
            return "GL_INVALID_OPERATION";
        case GL_OUT_OF_MEMORY:
            return "GL_OUT_OF_MEMORY";
        case GL_INVALID_FRAMEBUFFER_OPERATION:
            return "GL_INVALID_FRAMEBUFFER_OPERATION";
        default:
            return "GL error " + std::to_string(e);
    }
}

// The scene's camera with the lab's overrides applied.
Camera resolveCamera(const Scene& scene, const CameraOverride& o) {
    Camera c = scene.camera;
    if (o.position) c.position = *o.position;
    if (o.target) c.target = *o.target;
    if (o.up) c.up = *o.up;
    if (o.fov_y_deg) c.fov_y_deg = *o.fov_y_deg;
    if (o.z_near) c.z_near = *o.z_near;
    if (o.z_far) c.z_far = *o.z_far;
    return c;
}

struct LightUniforms {
    int count = 0;
    glm::vec4 position[kMaxLights] = {};  // w = 1: point at xyz; w = 0: xyz points toward the light
    glm::vec3 color[kMaxLights] = {};     // colour times intensity
};

LightUniforms resolveLights(const Scene& scene, const SceneSpec& spec, const Camera& camera) {
    LightUniforms out;
    auto add = [&out](bool directional, glm::vec3 pos, glm::vec3 dir, glm::vec3 color) {
        if (out.count >= kMaxLights) return;
        out.position[out.count] = directional ? glm::vec4(-glm::normalize(dir), 0.0f) : glm::vec4(pos, 1.0f);
        out.color[out.count] = color;
        ++out.count;
    };
    if (spec.lights) {
        for (const LightSpec& l : *spec.lights)
            add(l.type == "directional", l.position, l.direction, l.color * l.intensity);
    } else {
        for (const Light& l : scene.lights)
            add(l.type == LightType::Directional, l.position, l.direction, l.color * l.intensity);
    }
    if (out.count == 0) {
        // A scene without lights is still lit: a white point light above the camera.
        add(false, camera.position + glm::vec3(0.0f, 2.0f, 0.0f), {}, glm::vec3(1.0f));
    }
    return out;
}

}  // namespace

const char* renderStatusName(RenderStatus status) {
    switch (status) {
        case RenderStatus::Ok:
            return "ok";
        case RenderStatus::Missing:
            return "missing";
        case RenderStatus::CompileError:
            return "compile_error";
        case RenderStatus::LinkError:
            return "link_error";
        default:
            return "render_error";
    }
}

namespace {

// The zero of a lab uniform's type: what a scene-only uniform is reset to in the scenes that do
// not set it, so no value leaks from one scene into the next.
UniformValue zeroLike(const UniformValue& v) {
    return std::visit(
        [](const auto& x) -> UniformValue {
            using T = std::decay_t<decltype(x)>;
            if constexpr (std::is_same_v<T, glm::mat3> || std::is_same_v<T, glm::mat4>)
                return T(0.0f);
            else if constexpr (std::is_same_v<T, bool>)
                return false;
            else
                return T(0);
        },
        v);
}

bool isSampler2D(unsigned type) { return type == GL_SAMPLER_2D; }

// One lab on the current context: the steps of renderLab, each in its own method. Owns every GL
// object it makes and deletes them when it goes.
class LabRunner {
  public:
    LabRunner(const LabSpec& spec, const std::string& shader_dir, const RenderOptions& options,
              LabRender* out)
        : spec_(spec), shader_dir_(shader_dir), options_(options), out_(*out) {}

    ~LabRunner() {
        for (auto& [name, tex] : file_textures_) glDeleteTextures(1, &tex);
        for (auto& [key, sampler] : samplers_) glDeleteSamplers(1, &sampler);
        glUseProgram(0);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
    }

    bool prepare() { return readSources() && buildPrograms() && loadTextures() && createTargets(); }

    bool renderScene(const SceneSpec& scene_spec);

  private:
    struct LoadedScene {
        Scene scene;
        std::vector<std::unique_ptr<GpuMesh>> meshes;
    };

    bool fail(RenderStatus status, const std::string& message) {
        out_.status = status;
        out_.message = message;
        return false;
    }
    void warnOnce(const std::string& file, const std::string& message) {
        if (warned_.insert(file + '\n' + message).second)
            out_.diagnostics.push_back({file, 0, 0, "warning", message});
    }

    bool readSources();
    bool buildPrograms();
    bool loadTextures();
    bool createTargets();
    const LoadedScene* loadScene(const SceneSpec& scene_spec);
    GLuint sampler(TextureFilter filter, TextureWrap wrap);
    bool runPass(std::size_t index, const SceneSpec& scene_spec, const LoadedScene* scene,
                 const Camera& camera, const LightUniforms& lights, SceneRender* scene_out);
    void setFramework(const ShaderProgram& prog, const std::string& file, const char* name, GLenum type,
                      const std::function<void(GLint)>& set);

    const LabSpec& spec_;
    const std::string& shader_dir_;
    const RenderOptions& options_;
    LabRender& out_;

    std::map<std::string, std::string> sources_;
    std::map<std::pair<std::string, std::string>, ShaderProgram> programs_;
    std::map<std::string, GLuint> file_textures_;
    std::map<std::pair<int, int>, GLuint> samplers_;
    std::map<std::string, std::unique_ptr<Target>> targets_;  // by target name
    std::map<std::string, const TargetSpec*> target_specs_;
    std::vector<std::string> pass_target_;
    std::map<std::string, LoadedScene> scenes_;  // by file, meshes uploaded once
    std::unique_ptr<GpuMesh> fullscreen_;
    std::map<std::string, UniformValue> scene_uniform_zeros_;
    std::set<std::string> warned_;
};

// Student files come from the submission, every other program file from the lab folder: a
// submission can neither omit nor replace the instructor's shared shaders.
bool LabRunner::readSources() {
    const std::string& student_root =
        options_.containment_root.empty() ? shader_dir_ : options_.containment_root;
    const std::string prefix = options_.containment_root.empty()
                                   ? std::string()
                                   : std::filesystem::path(shader_dir_)
                                             .lexically_relative(options_.containment_root)
                                             .generic_string() +
                                         "/";
    for (const PassSpec& pass : spec_.passes) {
        for (const std::string* file : {&pass.program.vertex, &pass.program.fragment}) {
            if (sources_.count(*file)) continue;
            const bool student = std::find(spec_.student_files.begin(), spec_.student_files.end(), *file) !=
                                 spec_.student_files.end();
            // Resolved against the submission root, so a lab folder that is itself a symlink out
            // of the submission is refused like a symlinked file.
            FileText t = student ? readFileInside(student_root, prefix + *file, kMaxShaderBytes)
                                 : readFileInside(spec_.lab_dir, *file, kMaxShaderBytes);
            if (!t.ok) {
                out_.diagnostics.push_back({*file, 0, 0, "error", t.error});
                return fail(RenderStatus::Missing, t.error);
            }
            sources_[*file] = std::move(t.text);
        }
    }
    return true;
}

bool LabRunner::buildPrograms() {
    for (const PassSpec& pass : spec_.passes) {
        const auto key = std::make_pair(pass.program.vertex, pass.program.fragment);
        if (programs_.count(key)) continue;
        ShaderProgram& prog = programs_[key];
        prog.build(key.first, sources_[key.first], key.second, sources_[key.second]);
        for (const Diagnostic& d : prog.diagnostics()) out_.diagnostics.push_back(d);
        if (!prog.compiled()) {
            out_.status = RenderStatus::CompileError;
        } else if (!prog.linked() && out_.status == RenderStatus::Ok) {
            out_.status = RenderStatus::LinkError;
        }
    }
    if (out_.status == RenderStatus::Ok) return true;
    for (const Diagnostic& d : out_.diagnostics) {
        if (d.severity != "error") continue;
        out_.message = d.file + (d.line ? ":" + std::to_string(d.line) : "") + ": " + d.message;
        break;
    }
    if (out_.message.empty()) out_.message = renderStatusName(out_.status);
    return false;
}

bool LabRunner::loadTextures() {
    for (const PassSpec& pass : spec_.passes) {
        for (const PassInput& in : pass.inputs) {
            if (in.texture_file.empty() || file_textures_.count(in.texture_file)) continue;
            const PathResult p = resolveInside(spec_.lab_dir, in.texture_file);
            grader::Image img;
            std::string err;
            if (!p.ok || !grader::readPng(p.path, &img, &err))
                return fail(RenderStatus::RenderError, p.ok ? err : p.error);
            // RGBA floats with the top row last: GL's row 0 is the bottom one. Grey fills RGB.
            std::vector<float> rgba(static_cast<std::size_t>(img.width) * img.height * 4, 1.0f);
            for (int y = 0; y < img.height; ++y) {
                for (int x = 0; x < img.width; ++x) {
                    float* dst = &rgba[(static_cast<std::size_t>(img.height - 1 - y) * img.width + x) * 4];
                    for (int c = 0; c < 4; ++c) {
                        if (img.channels == 1 && c < 3)
                            dst[c] = img.at(x, y, 0);
                        else if (img.channels > 1 && c < img.channels)
                            dst[c] = img.at(x, y, c);
                    }
                }
            }
            GLuint tex = 0;
            glGenTextures(1, &tex);
            glBindTexture(GL_TEXTURE_2D, tex);
            glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, img.width, img.height, 0, GL_RGBA, GL_FLOAT,
                         rgba.data());
            file_textures_[in.texture_file] = tex;
        }
    }
    return true;
}

bool LabRunner::createTargets() {
    pass_target_.resize(spec_.passes.size());
    for (std::size_t i = 0; i < spec_.passes.size(); ++i) {
        const PassSpec& pass = spec_.passes[i];
        if (!pass.draw_into.empty()) {
            for (std::size_t j = 0; j < i; ++j)
                if (spec_.passes[j].name == pass.draw_into) pass_target_[i] = pass_target_[j];
            continue;
        }
        auto t = std::make_unique<Target>();
        std::string err;
        if (!createTarget(pass.target, spec_.width, spec_.height, t.get(), &err))
            return fail(RenderStatus::RenderError, err);
        pass_target_[i] = pass.target.name;
        target_specs_[pass.target.name] = &pass.target;
        targets_[pass.target.name] = std::move(t);
    }
    for (const SceneSpec& s : spec_.scenes)
        for (const auto& [name, value] : s.uniforms) scene_uniform_zeros_.emplace(name, zeroLike(value));
    fullscreen_ = fullscreenTriangle();
    return true;
}

const LabRunner::LoadedScene* LabRunner::loadScene(const SceneSpec& scene_spec) {
    static const LoadedScene kEmpty;
    if (scene_spec.file.empty()) return &kEmpty;
    const std::string path = (std::filesystem::path(spec_.labs_root) / scene_spec.file).string();
    auto it = scenes_.find(path);
    if (it != scenes_.end()) return &it->second;
    LoadedScene loaded;
    const SceneLoadResult r = loadGltfScene(path, &loaded.scene);
    if (!r.ok) {
        fail(RenderStatus::RenderError, r.error);
        return nullptr;
    }
    for (const Mesh& m : loaded.scene.meshes) loaded.meshes.push_back(uploadMesh(m));
    return &scenes_.emplace(path, std::move(loaded)).first->second;
}

GLuint LabRunner::sampler(TextureFilter filter, TextureWrap wrap) {
    const auto key = std::make_pair(static_cast<int>(filter), static_cast<int>(wrap));
    auto it = samplers_.find(key);
    if (it != samplers_.end()) return it->second;
    GLuint s = 0;
    glGenSamplers(1, &s);
    glSamplerParameteri(s, GL_TEXTURE_MIN_FILTER, glFilter(filter));
    glSamplerParameteri(s, GL_TEXTURE_MAG_FILTER, glFilter(filter));
    glSamplerParameteri(s, GL_TEXTURE_WRAP_S, glWrap(wrap));
    glSamplerParameteri(s, GL_TEXTURE_WRAP_T, glWrap(wrap));
    samplers_[key] = s;
    return s;
}

// Sets a framework uniform when the shader declares it; one declared with another type is
// skipped with a warning, since the value would be meaningless.
void LabRunner::setFramework(const ShaderProgram& prog, const std::string& file, const char* name,
                             GLenum type, const std::function<void(GLint)>& set) {
    const UniformSlot* s = prog.uniform(name);
    if (!s) return;
    if (s->type != type) {
        warnOnce(file, std::string(name) +
                           " is provided by the framework with another type: see docs/student-contract.md");
        return;
    }
    set(s->location);
}

bool LabRunner::renderScene(const SceneSpec& scene_spec) {
    const auto t0 = std::chrono::steady_clock::now();
    const LoadedScene* scene = loadScene(scene_spec);
    if (!scene) return false;
    // Every target starts each scene blank, so nothing of the previous scene survives in a pass
    // that draws without clearing.
    for (auto& [name, t] : targets_) {
        glBindFramebuffer(GL_FRAMEBUFFER, t->fbo);
        glDepthMask(GL_TRUE);
        glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
        glClearDepth(1.0);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    }
    const Camera camera = resolveCamera(scene->scene, scene_spec.camera);
    const LightUniforms lights = resolveLights(scene->scene, scene_spec, camera);
    SceneRender scene_out;
    scene_out.scene = scene_spec.name;
    for (std::size_t i = 0; i < spec_.passes.size(); ++i)
        if (!runPass(i, scene_spec, scene, camera, lights, &scene_out)) return false;
    glFinish();
    scene_out.render_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    out_.scenes.push_back(std::move(scene_out));
    return true;
}

bool LabRunner::runPass(std::size_t index, const SceneSpec& scene_spec, const LoadedScene* scene,
                        const Camera& camera, const LightUniforms& lights, SceneRender* scene_out) {
    const PassSpec& pass = spec_.passes[index];
    const ShaderProgram& prog = programs_.at({pass.program.vertex, pass.program.fragment});
    const std::string& file = pass.program.fragment;
    Target& target = *targets_.at(pass_target_[index]);
    glBindFramebuffer(GL_FRAMEBUFFER, target.fbo);
    glViewport(0, 0, target.width, target.height);
    applyState(pass.state);
    glUseProgram(prog.id());

    // Inputs on consecutive units; every other unit is left empty, so a sampler the lab does not
    // feed reads the incomplete texture 0 (black) rather than whatever was bound last.
    for (GLuint unit = 0; unit < 16; ++unit) {
        glActiveTexture(GL_TEXTURE0 + unit);
        glBindTexture(GL_TEXTURE_2D, 0);
        glBindSampler(unit, 0);
    }
    GLuint unit = 0;
    for (const PassInput& in : pass.inputs) {
        GLuint tex = 0;
        TextureFilter filter = TextureFilter::Linear;
        TextureWrap wrap = TextureWrap::ClampToEdge;
        if (!in.from_pass.empty()) {
            tex = targets_.at(in.from_pass)->color;
            filter = target_specs_.at(in.from_pass)->filter;
            wrap = target_specs_.at(in.from_pass)->wrap;
        } else {
            tex = file_textures_.at(in.texture_file);
        }
        if (in.filter) filter = *in.filter;
        if (in.wrap) wrap = *in.wrap;
        glActiveTexture(GL_TEXTURE0 + unit);
        glBindTexture(GL_TEXTURE_2D, tex);
        glBindSampler(unit, sampler(filter, wrap));
        if (const UniformSlot* s = prog.uniform(in.sampler)) {
            if (isSampler2D(s->type))
                glUniform1i(s->location, static_cast<GLint>(unit));
            else
                warnOnce(file, in.sampler + " receives a texture from the lab; declare it as sampler2D");
        }
        ++unit;
    }
    glActiveTexture(GL_TEXTURE0);

    const float aspect = static_cast<float>(target.width) / static_cast<float>(target.height);
    const glm::mat4 view = glm::lookAt(camera.position, camera.target, camera.up);
    const glm::mat4 projection =
        glm::perspective(glm::radians(camera.fov_y_deg), aspect, camera.z_near, camera.z_far);
    setFramework(prog, file, "u_view", GL_FLOAT_MAT4,
                 [&](GLint l) { glUniformMatrix4fv(l, 1, GL_FALSE, glm::value_ptr(view)); });
    setFramework(prog, file, "u_projection", GL_FLOAT_MAT4,
                 [&](GLint l) { glUniformMatrix4fv(l, 1, GL_FALSE, glm::value_ptr(projection)); });
    setFramework(prog, file, "u_camera_position", GL_FLOAT_VEC3,
                 [&](GLint l) { glUniform3fv(l, 1, glm::value_ptr(camera.position)); });
    setFramework(prog, file, "u_time", GL_FLOAT, [&](GLint l) { glUniform1f(l, scene_spec.time); });
    setFramework(prog, file, "u_resolution", GL_FLOAT_VEC2, [&](GLint l) {
        glUniform2f(l, static_cast<float>(target.width), static_cast<float>(target.height));
    });
    setFramework(prog, file, "u_light_count", GL_INT, [&](GLint l) { glUniform1i(l, lights.count); });
    // All declared entries are written (unused ones zero), so no light of another scene lingers.
    if (const UniformSlot* s = prog.uniform("u_light_position")) {
        if (s->type == GL_FLOAT_VEC4)
            glUniform4fv(s->location, std::min(s->size, kMaxLights), glm::value_ptr(lights.position[0]));
        else
            warnOnce(file, "u_light_position is provided by the framework as vec4");
    }
    if (const UniformSlot* s = prog.uniform("u_light_color")) {
        if (s->type == GL_FLOAT_VEC3)
            glUniform3fv(s->location, std::min(s->size, kMaxLights), glm::value_ptr(lights.color[0]));
        else
            warnOnce(file, "u_light_color is provided by the framework as vec3");
    }

    // Lab values: scene-only names reset, then the pass's values, then the scene's overrides.
    for (const auto& [name, zero] : scene_uniform_zeros_)
        if (!pass.uniforms.count(name) && !scene_spec.uniforms.count(name)) prog.set(name, zero);
    for (const UniformMap* map : {&pass.uniforms, &scene_spec.uniforms}) {
        for (const auto& [name, value] : *map) {
            const std::string warning = prog.set(name, value);
            if (!warning.empty()) warnOnce(file, warning);
        }
    }
    glUseProgram(prog.id());

    auto draw = [&](const GpuMesh& mesh, const glm::mat4& model, const glm::vec4& base_color) {
        const glm::mat4 model_view = view * model;
        const glm::mat4 mvp = projection * model_view;
        const glm::mat3 normal_matrix = glm::inverseTranspose(glm::mat3(model));
        setFramework(prog, file, "u_model", GL_FLOAT_MAT4,
                     [&](GLint l) { glUniformMatrix4fv(l, 1, GL_FALSE, glm::value_ptr(model)); });
        setFramework(prog, file, "u_model_view", GL_FLOAT_MAT4,
                     [&](GLint l) { glUniformMatrix4fv(l, 1, GL_FALSE, glm::value_ptr(model_view)); });
        setFramework(prog, file, "u_model_view_projection", GL_FLOAT_MAT4,
                     [&](GLint l) { glUniformMatrix4fv(l, 1, GL_FALSE, glm::value_ptr(mvp)); });
        setFramework(prog, file, "u_normal_matrix", GL_FLOAT_MAT3,
                     [&](GLint l) { glUniformMatrix3fv(l, 1, GL_FALSE, glm::value_ptr(normal_matrix)); });
        setFramework(prog, file, "u_base_color", GL_FLOAT_VEC4,
                     [&](GLint l) { glUniform4fv(l, 1, glm::value_ptr(base_color)); });
        glBindVertexArray(mesh.vao);
        glDrawElements(GL_TRIANGLES, mesh.index_count, GL_UNSIGNED_INT, nullptr);
    };
    if (pass.draw == DrawKind::Fullscreen) {
        draw(*fullscreen_, glm::mat4(1.0f), glm::vec4(1.0f));
    } else {
        for (const DrawItem& item : scene->scene.draw_items) {
            const glm::vec4 base =
                item.material >= 0
                    ? scene->scene.materials[static_cast<std::size_t>(item.material)].base_color
                    : glm::vec4(1.0f);
            draw(*scene->meshes[static_cast<std::size_t>(item.mesh)], item.world, base);
        }
    }
    glBindVertexArray(0);

    const GLenum err = glGetError();
    if (err != GL_NO_ERROR)
        return fail(RenderStatus::RenderError,
                    "pass '" + pass.name + "', scene '" + scene_spec.name + "': " + glErrorName(err));
    if (pass.graded || options_.keep_all_passes) {
        // Coverage comes from depth: scene passes and passes drawing into another target.
        PassImage img = readBack(target, pass.draw == DrawKind::Scene || !pass.draw_into.empty());
        img.pass = pass.name;
        img.target = pass_target_[index];
        img.graded = pass.graded;
        scene_out->passes.push_back(std::move(img));
    }
    return true;
}

}  // namespace

LabRender renderLab(const LabSpec& spec, const std::string& shader_dir, const RenderOptions& options) {
    LabRender result;
    LabRunner runner(spec, shader_dir, options, &result);
    if (!runner.prepare()) return result;
    for (const SceneSpec& scene_spec : spec.scenes) {
        if (!options.only_scenes.empty() && std::find(options.only_scenes.begin(), options.only_scenes.end(),
                                                      scene_spec.name) == options.only_scenes.end())
            continue;
        if (!runner.renderScene(scene_spec)) break;
    }
    return result;
}

}  // namespace shaderlab
