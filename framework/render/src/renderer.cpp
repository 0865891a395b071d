// Executes a lab's passes on the current context; see renderer.h.
//
// LabRunner owns every GL object of one lab: programs (one per shader pair and attachment
// layout), targets (two copies of those a pass reads while drawing into them, swapped after each
// run), input textures (made per sampler type on first use), sampler objects, meshes. Each pass
// run starts from a known state: the program's uniforms back at their linked defaults, every
// sampler of the program on its own texture unit, every other unit empty (glTF material textures
// excepted: units of their own, bound per draw, material_textures.h), the pass's render state
// applied in full. Nothing here knows a lab by name.
#include "shaderlab/render/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <map>
#include <set>

#include "gl_types.h"
#include "input_textures.h"
#include "shaderlab/base/json_messages.h"
#include "material_textures.h"
#include "shaderlab/scene/camera.h"
#include "shaderlab/gl/gl.h"
#include "shaderlab/scene/gltf_loader.h"
#include "shaderlab/base/paths.h"
#include "shaderlab/base/timings.h"
#include "uniform_values.h"

namespace shaderlab {

namespace {

constexpr std::size_t kMaxShaderBytes = 256 * 1024;
constexpr int kMaxLights = 4;
constexpr int kMaxTextureUnits = 16;

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

GLenum internalFormat(TargetFormat f) {
    switch (f) {
        case TargetFormat::RGBA8:
            return GL_RGBA8;
        case TargetFormat::SRGB8:
            return GL_SRGB8_ALPHA8;
        case TargetFormat::RGBA16F:
            return GL_RGBA16F;
        default:
            return GL_RGBA32F;
    }
}

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

bool createTarget(TargetGl* t, std::string* error) {
    const TargetSpec& s = *t->spec;
    glActiveTexture(GL_TEXTURE0 + kScratchTextureUnit);
    const GLenum format = internalFormat(s.format);
    const GLenum tex_target = t->textureTarget();
    for (int b = 0; b < t->buffers; ++b) {
        t->color[b].resize(s.attachments.size());
        glGenTextures(static_cast<GLsizei>(s.attachments.size()), t->color[b].data());
        for (GLuint tex : t->color[b]) {
            glBindTexture(tex_target, tex);
            for (int f = 0; f < t->faces(); ++f) {
                const GLenum image =
                    t->cube() ? GL_TEXTURE_CUBE_MAP_POSITIVE_X + static_cast<GLenum>(f) : GL_TEXTURE_2D;
                glTexImage2D(image, 0, static_cast<GLint>(format), s.width, s.height, 0, GL_RGBA, GL_FLOAT,
                             nullptr);
            }
            if (t->mipmapped) glGenerateMipmap(tex_target);
        }
    }
    if (t->depth == DepthMode::Texture) {
        glGenTextures(1, &t->depth_texture);
        glBindTexture(GL_TEXTURE_2D, t->depth_texture);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT32F, s.width, s.height, 0, GL_DEPTH_COMPONENT,
                     GL_FLOAT, nullptr);
    } else if (t->depth == DepthMode::Buffer) {
        glGenRenderbuffers(1, &t->depth_renderbuffer);
        glBindRenderbuffer(GL_RENDERBUFFER, t->depth_renderbuffer);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, s.width, s.height);
    }
    glBindTexture(tex_target, 0);
    glActiveTexture(GL_TEXTURE0);
    std::vector<GLenum> draw_buffers;
    for (std::size_t i = 0; i < s.attachments.size(); ++i)
        draw_buffers.push_back(GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i));
    for (int b = 0; b < t->buffers; ++b) {
        for (int f = 0; f < t->faces(); ++f) {
            GLuint fbo = 0;
            glGenFramebuffers(1, &fbo);
            t->fbos[{b, f}] = fbo;
            glBindFramebuffer(GL_FRAMEBUFFER, fbo);
            const GLenum image =
                t->cube() ? GL_TEXTURE_CUBE_MAP_POSITIVE_X + static_cast<GLenum>(f) : GL_TEXTURE_2D;
            for (std::size_t i = 0; i < s.attachments.size(); ++i)
                glFramebufferTexture2D(GL_FRAMEBUFFER, draw_buffers[i], image, t->color[b][i], 0);
            if (t->depth_texture)
                glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, t->depth_texture,
                                       0);
            if (t->depth_renderbuffer)
                glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER,
                                          t->depth_renderbuffer);
            glDrawBuffers(static_cast<GLsizei>(draw_buffers.size()), draw_buffers.data());
            const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
            if (status != GL_FRAMEBUFFER_COMPLETE) {
                char buf[32];
                std::snprintf(buf, sizeof buf, "0x%04X", status);
                *error = "target '" + s.name + "' is incomplete on this driver (status " + buf + ")";
                return false;
            }
        }
    }
    return true;
}

GLint glFilterMin(TextureFilter f) {
    return f == TextureFilter::Nearest  ? GL_NEAREST
           : f == TextureFilter::Mipmap ? GL_LINEAR_MIPMAP_LINEAR
                                        : GL_LINEAR;
}

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

GLenum glDepthFuncOf(DepthFunc f) {
    switch (f) {
        case DepthFunc::Never:
            return GL_NEVER;
        case DepthFunc::Equal:
            return GL_EQUAL;
        case DepthFunc::LessEqual:
            return GL_LEQUAL;
        case DepthFunc::Greater:
            return GL_GREATER;
        case DepthFunc::NotEqual:
            return GL_NOTEQUAL;
        case DepthFunc::GreaterEqual:
            return GL_GEQUAL;
        case DepthFunc::Always:
            return GL_ALWAYS;
        default:
            return GL_LESS;
    }
}

GLenum glPrimitive(Primitive p) {
    switch (p) {
        case Primitive::Points:
            return GL_POINTS;
        case Primitive::Lines:
            return GL_LINES;
        case Primitive::LineStrip:
            return GL_LINE_STRIP;
        case Primitive::TriangleStrip:
            return GL_TRIANGLE_STRIP;
        default:
            return GL_TRIANGLES;
    }
}

void applyState(const RenderState& s, bool srgb_target, bool program_point_size) {
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDisable(GL_SCISSOR_TEST);
    if (s.depth_test) {
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(glDepthFuncOf(s.depth_func));
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
    glPolygonMode(GL_FRONT_AND_BACK, s.polygon_mode == PolygonMode::Line    ? GL_LINE
                                     : s.polygon_mode == PolygonMode::Point ? GL_POINT
                                                                            : GL_FILL);
    glLineWidth(s.line_width);
    glPointSize(s.point_size);
    if (program_point_size)
        glEnable(GL_PROGRAM_POINT_SIZE);
    else
        glDisable(GL_PROGRAM_POINT_SIZE);
    if (srgb_target)
        glEnable(GL_FRAMEBUFFER_SRGB);
    else
        glDisable(GL_FRAMEBUFFER_SRGB);
    switch (s.blend) {
        case BlendMode::None:
            glDisable(GL_BLEND);
            break;
        case BlendMode::Alpha:
            glEnable(GL_BLEND);
            glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
            break;
        case BlendMode::Premultiplied:
            glEnable(GL_BLEND);
            glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
            break;
        case BlendMode::Additive:
            glEnable(GL_BLEND);
            glBlendFunc(GL_ONE, GL_ONE);
            break;
    }
}

void clearTarget(const RenderState& s, bool has_depth) {
    for (std::size_t i = 0; i < s.clear_colors.size(); ++i) {
        if (!s.clear_colors[i]) continue;
        glClearBufferfv(GL_COLOR, static_cast<GLint>(i), glm::value_ptr(*s.clear_colors[i]));
    }
    if (s.clear_depth && has_depth) {
        glDepthMask(GL_TRUE);  // a disabled depth mask would also mask the clear
        const GLfloat one = 1.0f;
        glClearBufferfv(GL_DEPTH, 0, &one);
        glDepthMask(s.depth_write ? GL_TRUE : GL_FALSE);
    }
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

// Reads one attachment ("depth" included) of the front set into a top-row-first image; a cube
// target's faces side by side.
grader::Image readAttachment(const TargetGl& t, const std::string& attachment) {
    const TargetSpec& s = *t.spec;
    const int w = s.width, h = s.height, faces = t.faces();
    grader::Image img(w * faces, h, 4);
    std::vector<float> buf(static_cast<std::size_t>(w) * h * 4);
    const bool depth = attachment == "depth";
    const auto at = std::find(s.attachments.begin(), s.attachments.end(), attachment);
    const GLenum read_buffer = GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(at - s.attachments.begin());
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    for (int f = 0; f < faces; ++f) {
        glBindFramebuffer(GL_READ_FRAMEBUFFER, t.fbos.at({t.front, f}));
        if (depth) {
            std::vector<float> d(static_cast<std::size_t>(w) * h);
            glReadPixels(0, 0, w, h, GL_DEPTH_COMPONENT, GL_FLOAT, d.data());
            for (std::size_t i = 0; i < d.size(); ++i) {
                buf[i * 4 + 0] = buf[i * 4 + 1] = buf[i * 4 + 2] = d[i];
                buf[i * 4 + 3] = 1.0f;
            }
        } else {
            glReadBuffer(read_buffer);
            glReadPixels(0, 0, w, h, GL_RGBA, GL_FLOAT, buf.data());
        }
        // GL's first row is the bottom one. Cube faces keep GL's row order, as face images are
        // stored (their first row is t = 0).
        for (int y = 0; y < h; ++y) {
            const int src_y = t.cube() ? y : h - 1 - y;
            std::copy_n(buf.data() + static_cast<std::size_t>(src_y) * w * 4, static_cast<std::size_t>(w) * 4,
                        img.pixels.data() +
                            (static_cast<std::size_t>(y) * w * faces + static_cast<std::size_t>(f) * w) * 4);
        }
    }
    return img;
}

std::vector<std::uint8_t> readCoverage(const TargetGl& t) {
    const TargetSpec& s = *t.spec;
    const std::size_t n = static_cast<std::size_t>(s.width) * t.faces() * s.height;
    std::vector<std::uint8_t> coverage(n, 1);
    if (t.fullscreen_drawn || t.depth == DepthMode::None || t.cube()) return coverage;
    const int w = s.width, h = s.height;
    std::vector<float> depth(static_cast<std::size_t>(w) * h);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, t.fbos.at({t.front, 0}));
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, w, h, GL_DEPTH_COMPONENT, GL_FLOAT, depth.data());
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            coverage[static_cast<std::size_t>(y) * w + x] =
                depth[static_cast<std::size_t>(h - 1 - y) * w + x] < 1.0f;
    return coverage;
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

class LabRunner {
  public:
    LabRunner(const LabSpec& spec, const std::string& shader_dir, const RenderOptions& options,
              LabRender* out)
        : spec_(spec),
          shader_dir_(shader_dir),
          options_(options),
          out_(*out),
          origin_((std::filesystem::path(spec.lab_dir) / "lab.json").string()) {}

    ~LabRunner() {
        // Let the driver finish what was queued (a lab that failed half-way leaves clears and
        // uploads in flight) before the objects they use go; llvmpipe crashes later otherwise.
        glFinish();
        for (const auto& [unit, target] : bound_units_) {
            glActiveTexture(GL_TEXTURE0 + unit);
            glBindTexture(target, 0);
            glBindSampler(unit, 0);
        }
        glActiveTexture(GL_TEXTURE0);
        glBindVertexArray(0);
        for (auto& [key, tex] : input_textures_) glDeleteTextures(1, &tex.id);
        for (auto& [key, sampler] : samplers_) glDeleteSamplers(1, &sampler);
        if (empty_vao_) glDeleteVertexArrays(1, &empty_vao_);
        if (loop_guard_) glDeleteBuffers(1, &loop_guard_);
        glUseProgram(0);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
    }

    bool prepare() {
        // Filtered cube-map lookups blend across face edges instead of clamping at them.
        glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
        if (!readSources()) return false;
        ScopedTiming compile_timing("compile", spec_.id);
        if (!buildPrograms()) return false;
        compile_timing.stop();
        if (!createTargets()) return false;
        createLoopGuard();
        findNeededPasses();
        return true;
    }
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
    // The counters guarded programs write when a loop runs past kLoopGuardLimit (shader_program.h).
    void createLoopGuard() {
        if (!GLAD_GL_VERSION_4_3) return;
        const GLuint zero[2] = {0, 0};
        glGenBuffers(1, &loop_guard_);
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, loop_guard_);
        glBufferData(GL_SHADER_STORAGE_BUFFER, sizeof zero, zero, GL_DYNAMIC_READ);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLoopGuardBinding, loop_guard_);
    }
    // After a pass: did a loop of its program run past the guard? Then the render stops here.
    bool checkLoopGuard(const PassSpec& pass, const std::string& scene) {
        if (!loop_guard_) return true;
        GLuint counts[2] = {0, 0};
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, loop_guard_);
        glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof counts, counts);
        if (counts[0] == 0 && counts[1] == 0) return true;
        const bool vertex = counts[0] > 0;
        const std::string& file = vertex ? pass.program.vertex : pass.program.fragment;
        const std::string message =
            "endless loop: in pass '" + pass.name + "' of scene '" + scene + "', a loop ran more than " +
            std::to_string(kLoopGuardLimit) + " times for one " + (vertex ? "vertex" : "pixel") + " (" +
            std::to_string(vertex ? counts[0] : counts[1]) + (vertex ? " vertices" : " pixels") +
            "); the grader stops it there, as a GPU would hang on it. Check that every loop's condition "
            "becomes false: its counter must change, and towards the end";
        out_.endless_loop = true;
        out_.diagnostics.push_back({file, 0, 0, "error", message});
        return fail(RenderStatus::RenderError, file + ": " + message);
    }
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
    FileText readProgramFile(const std::string& file) const;
    std::string programKey(const PassSpec& pass) const;
    const ShaderProgram& programOf(const PassSpec& pass) const { return programs_.at(programKey(pass)); }

    bool readSources();
    bool buildPrograms();
    void checkOutputs(const ShaderProgram& prog, const PassSpec& pass, const TargetSpec& target);
    bool createTargets();
    void findNeededPasses();
    const LoadedScene* loadScene(const SceneSpec& scene_spec);
    GLuint sampler(TextureFilter filter, TextureWrap wrap, bool shadow);
    bool bindInputs(const PassSpec& pass, const ShaderProgram& prog);
    bool setLabUniforms(const PassSpec& pass, const ShaderProgram& prog, const SceneContext& ctx);
    bool runPass(std::size_t index, int iteration, bool last_iteration, SceneContext& ctx);
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
    MaterialTextures material_textures_;                  // glTF material textures, bound per draw
};

// Student files come from the submission, every other program file from the lab folder (or the
// course's shared folder): a submission can neither omit nor replace the instructor's shaders.
FileText LabRunner::readProgramFile(const std::string& file) const {
    if (isStudentFile(file)) {
        const std::string& root = options_.containment_root.empty() ? shader_dir_ : options_.containment_root;
        const std::string prefix = options_.containment_root.empty()
                                       ? std::string()
                                       : std::filesystem::path(shader_dir_)
                                                 .lexically_relative(options_.containment_root)
                                                 .generic_string() +
                                             "/";
        return readFileInside(root, prefix + file, kMaxShaderBytes);
    }
    const bool shared = file.rfind("shared/", 0) == 0;
    return readFileInside(shared ? spec_.labs_root : spec_.lab_dir, file, kMaxShaderBytes);
}

bool LabRunner::readSources() {
    for (const PassSpec& pass : spec_.passes) {
        for (const std::string* file : {&pass.program.vertex, &pass.program.fragment}) {
            if (sources_.count(*file)) continue;
            FileText t = readProgramFile(*file);
            if (!t.ok) {
                // Absent (or a link out of the submission): missing. Present but refused (too
                // large, a folder): it cannot be compiled, which is a compile error naming why.
                out_.diagnostics.push_back({*file, 0, 0, "error", t.error});
                return fail(t.missing ? RenderStatus::Missing : RenderStatus::CompileError, t.error);
            }
            sources_[*file] = std::move(t.text);
        }
    }
    return true;
}

std::string LabRunner::programKey(const PassSpec& pass) const {
    std::string key = pass.program.vertex + '\n' + pass.program.fragment;
    if (const TargetSpec* t = spec_.findTarget(pass.target))
        for (const std::string& a : t->attachments) key += '\n' + a;
    return key;
}

bool LabRunner::buildPrograms() {
    // `#include "name"`: from the submission when `name` is a student file, else from the lab
    // folder or the shared folder; an include's own includes follow the same rule.
    const IncludeReader includes = [this](const std::string&, const std::string& name) {
        if (name.empty() || name[0] == '/' || name.find("..") != std::string::npos) {
            FileText t;
            t.error = "include paths are relative to the lab folder (or shared/...) and have no '..'";
            return t;
        }
        return readProgramFile(name);
    };
    for (const PassSpec& pass : spec_.passes) {
        const std::string key = programKey(pass);
        if (programs_.count(key)) continue;
        const TargetSpec& target = *spec_.findTarget(pass.target);
        report("compile " + pass.program.vertex + " " + pass.program.fragment);
        ShaderProgram& prog = programs_[key];
        prog.build(StageSource{pass.program.vertex, sources_[pass.program.vertex], includes},
                   StageSource{pass.program.fragment, sources_[pass.program.fragment], includes},
                   target.attachments, /*guard_loops=*/true);
        all_program_text_ += prog.preparedText(0) + prog.preparedText(1);
        // A file in two programs (03-cel-outline's outline.frag, with two vertex stages) would
        // report each of its problems twice.
        for (const Diagnostic& d : prog.diagnostics()) {
            const bool repeated =
                std::any_of(out_.diagnostics.begin(), out_.diagnostics.end(), [&](const Diagnostic& e) {
                    return e.file == d.file && e.line == d.line && e.column == d.column &&
                           e.severity == d.severity && e.message == d.message;
                });
            if (!repeated) out_.diagnostics.push_back(d);
        }
        if (!prog.compiled()) {
            out_.status = RenderStatus::CompileError;
        } else if (!prog.linked() && out_.status == RenderStatus::Ok) {
            out_.status = RenderStatus::LinkError;
        } else if (prog.linked()) {
            checkOutputs(prog, pass, target);
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

// Fragment outputs and the target's attachments must meet: an output no attachment receives is
// lost without a word from OpenGL, and an attachment no output writes keeps garbage.
void LabRunner::checkOutputs(const ShaderProgram& prog, const PassSpec& pass, const TargetSpec& target) {
    if (!prog.outputsKnown()) return;
    const std::string& file = pass.program.fragment;
    std::set<int> written;
    for (const FragmentOutput& o : prog.outputs()) {
        if (o.location >= 0 && static_cast<std::size_t>(o.location) < target.attachments.size()) {
            written.insert(o.location);
            continue;
        }
        std::string list;
        for (const std::string& a : target.attachments) list += (list.empty() ? "" : ", ") + a;
        warnOnce(file, "output `" + o.name + "` (location " + std::to_string(o.location) +
                           ") reaches no attachment of target '" + target.name + "' (" + list +
                           "): nothing it writes is seen. Name outputs o_<attachment>.");
    }
    for (std::size_t i = 0; i < target.attachments.size(); ++i)
        if (!written.count(static_cast<int>(i)))
            warnOnce(file, "no output writes attachment '" + target.attachments[i] + "' of target '" +
                               target.name + "' (name it o_" + target.attachments[i] + ")");
}

// A pass runs only when an image the caller keeps depends on it: the graded passes, what they
// read (the passes drawing into those targets), and the earlier passes drawing into the same
// target (a pass that does not clear adds to them), followed back to the first pass. A loop
// (`repeat`) runs whole or not at all. With keep_all_passes (`render --all-passes`, the
// viewer) every pass runs, since every pass is shown.
void LabRunner::findNeededPasses() {
    const std::size_t n = spec_.passes.size();
    needed_.assign(n, options_.keep_all_passes);
    if (options_.keep_all_passes) return;
    std::vector<std::size_t> work;
    auto need = [&](std::size_t i) {
        if (needed_[i]) return;
        needed_[i] = true;
        work.push_back(i);
        const int loop = spec_.passes[i].loop;
        if (loop < 0) return;
        const LoopSpec& l = spec_.loops[static_cast<std::size_t>(loop)];
        for (std::size_t j = l.first; j <= l.last; ++j)
            if (!needed_[j]) {
                needed_[j] = true;
                work.push_back(j);
            }
    };
    for (std::size_t i = 0; i < n; ++i)
        if (!spec_.passes[i].graded.empty()) need(i);
    while (!work.empty()) {
        const std::size_t i = work.back();
        work.pop_back();
        const PassSpec& pass = spec_.passes[i];
        for (std::size_t j = 0; j < n; ++j) {
            const std::string& written = spec_.passes[j].target;
            const bool read = std::any_of(pass.inputs.begin(), pass.inputs.end(), [&](const PassInput& in) {
                return in.source == InputSource::Target && in.target == written;
            });
            if (read || (j < i && written == pass.target)) need(j);
        }
    }
    for (std::size_t i = 0; i < n; ++i)
        if (!needed_[i] && timingsEnabled())
            recordTiming("pass_skipped", spec_.id, spec_.passes[i].name, 0.0);
}

bool LabRunner::createTargets() {
    std::set<std::string> self_read, mipmapped;
    for (const PassSpec& pass : spec_.passes) {
        for (const PassInput& in : pass.inputs) {
            if (in.source != InputSource::Target) continue;
            if (in.target == pass.target && in.attachment != "depth") self_read.insert(in.target);
            const TargetSpec* t = spec_.findTarget(in.target);
            if (in.filter.value_or(t ? t->filter : TextureFilter::Linear) == TextureFilter::Mipmap)
                mipmapped.insert(in.target);
        }
    }
    // A depth buffer (not a depth texture, which later passes read) is allocated only when a
    // pass drawing into the target tests or writes depth, or grades it: a target that only
    // full-screen passes draw (post-processing, unless its lab.json says "depth": "none") would
    // otherwise be cleared and carried for nothing.
    std::set<std::string> depth_used;
    for (const PassSpec& pass : spec_.passes) {
        const bool grades_depth =
            std::find(pass.graded.begin(), pass.graded.end(), "depth") != pass.graded.end();
        if (pass.state.depth_test || pass.state.depth_write || grades_depth) depth_used.insert(pass.target);
    }
    for (const TargetSpec& spec : spec_.targets) {
        auto t = std::make_unique<TargetGl>();
        t->spec = &spec;
        t->depth =
            spec.depth == DepthMode::Buffer && !depth_used.count(spec.name) ? DepthMode::None : spec.depth;
        t->buffers = self_read.count(spec.name) ? 2 : 1;
        t->mipmapped = mipmapped.count(spec.name) > 0;
        std::string err;
        if (!createTarget(t.get(), &err)) return fail(RenderStatus::RenderError, err);
        targets_[spec.name] = std::move(t);
    }
    fullscreen_ = fullscreenTriangle();
    glGenVertexArrays(1, &empty_vao_);
    return true;
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

GLuint LabRunner::sampler(TextureFilter filter, TextureWrap wrap, bool shadow) {
    const auto key = std::make_tuple(static_cast<int>(filter), static_cast<int>(wrap), shadow);
    auto it = samplers_.find(key);
    if (it != samplers_.end()) return it->second;
    GLuint s = 0;
    glGenSamplers(1, &s);
    glSamplerParameteri(s, GL_TEXTURE_MIN_FILTER, glFilterMin(filter));
    glSamplerParameteri(s, GL_TEXTURE_MAG_FILTER, filter == TextureFilter::Nearest ? GL_NEAREST : GL_LINEAR);
    for (GLenum p : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
        glSamplerParameteri(s, p, glWrap(wrap));
    if (shadow) {
        glSamplerParameteri(s, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
        glSamplerParameteri(s, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    }
    samplers_[key] = s;
    return s;
}

// Every sampler the program declares gets its own unit, so samplers of different types never
// share one (a GL_INVALID_OPERATION at draw time). The lab's inputs are bound by the sampler type
// the program declares; a sampler the lab does not feed reads an empty unit (black).
bool LabRunner::bindInputs(const PassSpec& pass, const ShaderProgram& prog) {
    for (const auto& [unit, target] : bound_units_) {
        glActiveTexture(GL_TEXTURE0 + unit);
        glBindTexture(target, 0);
        glBindSampler(unit, 0);
    }
    bound_units_.clear();
    const std::string& file = pass.program.fragment;
    GLuint unit = 0;
    std::set<std::string> fed;
    const auto fedByLab = [&](const std::string& name) {
        return std::any_of(pass.inputs.begin(), pass.inputs.end(),
                           [&](const PassInput& in) { return in.sampler == name; });
    };
    for (const UniformSlot& slot : prog.uniforms()) {
        if (glTypeInfo(slot.type).kind != ScalarKind::Sampler) continue;
        // Material textures have units of their own (material_textures.h), unless the lab feeds
        // the name itself.
        if (isMaterialSampler(slot.name) && !fedByLab(slot.name)) continue;
        if (slot.size > 1)
            return failAt(RenderStatus::LinkError,
                          "the program declares `" + std::string(glslTypeName(slot.type)) + " " + slot.name +
                              "[" + std::to_string(slot.size) +
                              "]`: arrays of samplers are not supported; declare one per input");
        if (static_cast<int>(unit) >= kMaxTextureUnits)
            return failAt(RenderStatus::LinkError, "the program declares more than 16 samplers");
        const PassInput* in = nullptr;
        for (const PassInput& candidate : pass.inputs)
            if (candidate.sampler == slot.name) in = &candidate;
        const GLenum tex_target = samplerTextureTarget(slot.type);
        const std::string declared = "`" + std::string(glslTypeName(slot.type)) + " " + slot.name + "`";
        glUniform1i(slot.location, static_cast<GLint>(unit));
        if (!in) {
            warnOnce(file, "sampler " + slot.name + " gets no texture from the lab (" + pass.path +
                               ".inputs has none by that name); it reads black");
            ++unit;
            continue;
        }
        fed.insert(in->sampler);
        if (tex_target == 0)
            return failAt(RenderStatus::LinkError,
                          in->path + ": the program declares " + declared +
                              "; inputs feed sampler1D, sampler2D, sampler3D, samplerCube "
                              "and sampler2DShadow");
        GLuint texture = 0;
        TextureFilter filter = in->filter.value_or(TextureFilter::Linear);
        TextureWrap wrap = in->wrap.value_or(TextureWrap::ClampToEdge);
        if (in->source == InputSource::Target) {
            TargetGl& t = *targets_.at(in->target);
            filter = in->filter.value_or(t.spec->filter);
            wrap = in->wrap.value_or(t.spec->wrap);
            const bool depth = in->attachment == "depth";
            if (depth) {
                if (tex_target != GL_TEXTURE_2D)
                    return failAt(RenderStatus::LinkError, in->path +
                                                               ": a depth texture is read with sampler2D or "
                                                               "sampler2DShadow; the program declares " +
                                                               declared);
                texture = t.depth_texture;
            } else {
                if (isShadowSampler(slot.type))
                    return failAt(RenderStatus::LinkError,
                                  in->path + ": the program declares " + declared +
                                      ", which compares depths: feed it a depth attachment (\"" + in->target +
                                      ".depth\")");
                if (tex_target != t.textureTarget())
                    return failAt(RenderStatus::LinkError, in->path + ": target '" + in->target + "' is " +
                                                               (t.cube() ? "a cube map (declare samplerCube)"
                                                                         : "2D (declare sampler2D)") +
                                                               "; the program declares " + declared);
                const auto at =
                    std::find(t.spec->attachments.begin(), t.spec->attachments.end(), in->attachment);
                const std::size_t index =
                    in->attachment.empty() ? 0 : static_cast<std::size_t>(at - t.spec->attachments.begin());
                texture = t.color[t.front][index];
            }
        } else {
            const bool mipmaps = filter == TextureFilter::Mipmap;
            const std::string key = in->path + '\n' + std::to_string(slot.type) + (mipmaps ? "m" : "");
            auto it = input_textures_.find(key);
            if (it == input_textures_.end()) {
                InputTexture tex;
                const std::string problem = createInputTexture(spec_, *in, slot.type, mipmaps, &tex);
                if (!problem.empty()) return failAt(RenderStatus::LinkError, in->path + ": " + problem);
                it = input_textures_.emplace(key, tex).first;
            }
            texture = it->second.id;
        }
        glActiveTexture(GL_TEXTURE0 + unit);
        glBindTexture(tex_target, texture);
        glBindSampler(unit, sampler(filter, wrap, isShadowSampler(slot.type)));
        bound_units_.emplace_back(unit, tex_target);
        ++unit;
    }
    glActiveTexture(GL_TEXTURE0);
    material_textures_.beginPass(prog, fed, [&](const std::string& message) { warnOnce(file, message); });
    for (const PassInput& in : pass.inputs) {
        if (fed.count(in.sampler)) continue;
        const std::string text = prog.preparedText(0) + prog.preparedText(1);
        if (!mentionsIdentifier(text, in.sampler))
            warnOnce(file, in.path + ": the lab gives a texture to " + in.sampler + ", which neither " +
                               pass.program.vertex + " nor " + file + " declares" +
                               didYouMean(in.sampler, declaredUniformNames(text)));
    }
    return true;
}

bool LabRunner::setLabUniforms(const PassSpec& pass, const ShaderProgram& prog, const SceneContext& ctx) {
    const PassCameraLookup cameras = [this, &ctx](const std::string& name) -> const PassCameraValues* {
        for (std::size_t i = 0; i < spec_.passes.size(); ++i)
            if (spec_.passes[i].name == name) return &ctx.cameras[i].values;
        return nullptr;
    };
    // A pass's value is for its own program: one that program never mentions is likely
    // misspelt. A scene's value goes to every pass, so it is suspicious only when no program of
    // the lab mentions it.
    auto apply = [&](const UniformSetting& u, bool from_scene) {
        const UniformApplyResult r = applyUniform(prog, u, cameras);
        if (!r.error.empty()) return failAt(RenderStatus::LinkError, r.error);
        if (r.declared) return true;
        const std::string text = prog.preparedText(0) + prog.preparedText(1);
        if (!from_scene && !mentionsIdentifier(text, u.name))
            warnOnce(pass.program.fragment, "lab.json sets " + u.name + " (" + u.path + "), but neither " +
                                                pass.program.vertex + " nor " + pass.program.fragment +
                                                " mentions it" +
                                                didYouMean(u.name, declaredUniformNames(text)));
        if (from_scene && !mentionsIdentifier(all_program_text_, u.name))
            warnOnce("lab.json", "lab.json sets " + u.name + " (" + u.path +
                                     "), but no shader of the lab mentions it" +
                                     didYouMean(u.name, declaredUniformNames(all_program_text_)));
        return true;
    };
    for (const UniformSetting& u : pass.uniforms) {
        const bool overridden = std::any_of(ctx.spec->uniforms.begin(), ctx.spec->uniforms.end(),
                                            [&](const UniformSetting& s) { return s.name == u.name; });
        if (!overridden && !apply(u, false)) return false;
    }
    for (const UniformSetting& u : ctx.spec->uniforms)
        if (!apply(u, true)) return false;
    return true;
}

// Sets a framework uniform when the shader declares it; one declared with another type is
// skipped with a warning, since the value would be meaningless.
void LabRunner::setFramework(const ShaderProgram& prog, const std::string& file, const char* name,
                             GLenum type, const std::function<void(GLint)>& set) {
    const UniformSlot* s = prog.uniform(name);
    if (!s) return;
    if (s->type != type) {
        warnOnce(file, std::string(name) + " is provided by the framework as " + glslTypeName(type) +
                           "; it is declared " + glslTypeName(s->type) + " (see docs/student-contract.md)");
        return;
    }
    set(s->location);
}

void LabRunner::copyFrontToBack(TargetGl& t) {
    const int back = 1 - t.front;
    for (int f = 0; f < t.faces(); ++f) {
        glBindFramebuffer(GL_READ_FRAMEBUFFER, t.fbos.at({t.front, f}));
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, t.fbos.at({back, f}));
        for (std::size_t i = 0; i < t.spec->attachments.size(); ++i) {
            const GLenum a = GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i);
            glReadBuffer(a);
            glDrawBuffers(1, &a);
            glBlitFramebuffer(0, 0, t.spec->width, t.spec->height, 0, 0, t.spec->width, t.spec->height,
                              GL_COLOR_BUFFER_BIT, GL_NEAREST);
        }
        std::vector<GLenum> all;
        for (std::size_t i = 0; i < t.spec->attachments.size(); ++i)
            all.push_back(GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i));
        glDrawBuffers(static_cast<GLsizei>(all.size()), all.data());
    }
}

bool LabRunner::renderScene(const SceneSpec& scene_spec) {
    const auto t0 = std::chrono::steady_clock::now();
    report("scene " + scene_spec.name);
    const LoadedScene* scene = loadScene(scene_spec);
    if (!scene->error.empty()) {
        // The other scenes still render and are graded; this one is reported with the reason.
        SceneRender failed;
        failed.scene = scene_spec.name;
        failed.error = scene->error;
        out_.diagnostics.push_back({"../" + scene_spec.file, 0, 0, "error", scene->error});
        report("done " + scene_spec.name + " 0.0");
        out_.scenes.push_back(std::move(failed));
        return true;
    }
    // Every target starts each scene blank, so nothing of the previous scene survives in a pass
    // that draws without clearing.
    for (auto& [name, t] : targets_) {
        t->front = 0;
        t->fullscreen_drawn = false;
        for (const auto& [key, fbo] : t->fbos) {
            glBindFramebuffer(GL_FRAMEBUFFER, fbo);
            glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
            glDepthMask(GL_TRUE);
            glDisable(GL_FRAMEBUFFER_SRGB);
            const GLfloat zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
            for (std::size_t i = 0; i < t->spec->attachments.size(); ++i)
                glClearBufferfv(GL_COLOR, static_cast<GLint>(i), zero);
            if (t->depth != DepthMode::None) {
                const GLfloat one = 1.0f;
                glClearBufferfv(GL_DEPTH, 0, &one);
            }
        }
    }
    SceneContext ctx;
    ctx.spec = &scene_spec;
    ctx.scene = scene;
    Camera camera = scene->scene.camera;
    ctx.lights = resolveLights(scene->scene, scene_spec, camera);
    std::string problem = applyCameraOverride(scene->scene, ctx.lights, scene_spec.camera, &camera);
    if (!problem.empty()) return failAt(RenderStatus::RenderError, scene_spec.path + ".camera: " + problem);
    orbitCamera(scene->scene, options_.orbit, &camera);
    for (const PassSpec& pass : spec_.passes) {
        PassCamera pc;
        pc.camera = camera;
        if (pass.camera.any()) {
            problem = applyCameraOverride(scene->scene, ctx.lights, pass.camera, &pc.camera);
            if (!problem.empty())
                return failAt(RenderStatus::RenderError,
                              pass.path + ": scene '" + scene_spec.name + "': " + problem);
        }
        const TargetSpec& t = *spec_.findTarget(pass.target);
        pc.values.view = viewMatrix(pc.camera);
        pc.values.projection =
            projectionMatrix(pc.camera, static_cast<float>(t.width) / static_cast<float>(t.height));
        pc.values.position = pc.camera.position;
        ctx.cameras.push_back(pc);
    }
    SceneRender scene_out;
    scene_out.scene = scene_spec.name;
    ctx.out = &scene_out;
    for (std::size_t i = 0; i < spec_.passes.size();) {
        const PassSpec& pass = spec_.passes[i];
        if (pass.loop < 0) {
            if (needed_[i] && (!runPass(i, 0, true, ctx) || !checkLoopGuard(pass, scene_spec.name)))
                return false;
            ++i;
            continue;
        }
        const LoopSpec& loop = spec_.loops[static_cast<std::size_t>(pass.loop)];
        if (!needed_[i]) {
            i = loop.last + 1;
            continue;
        }
        const auto it = scene_spec.repeats.find(loop.declared_by);
        const int count = it != scene_spec.repeats.end() ? it->second : loop.count;
        for (int k = 0; k < count; ++k)
            for (std::size_t j = loop.first; j <= loop.last; ++j)
                if (!runPass(j, k, k + 1 == count, ctx) || !checkLoopGuard(spec_.passes[j], scene_spec.name))
                    return false;
        i = loop.last + 1;
    }
    glFinish();
    scene_out.render_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (timingsEnabled()) recordTiming("scene", spec_.id, scene_spec.name, scene_out.render_ms);
    char ms[32];
    std::snprintf(ms, sizeof ms, "%.1f", scene_out.render_ms);
    report("done " + scene_spec.name + " " + ms);
    out_.scenes.push_back(std::move(scene_out));
    return true;
}

bool LabRunner::runPass(std::size_t index, int iteration, bool last_iteration, SceneContext& ctx) {
    const PassSpec& pass = spec_.passes[index];
    const ShaderProgram& prog = programOf(pass);
    const std::string& file = pass.program.fragment;
    TargetGl& target = *targets_.at(pass.target);
    const TargetSpec& tspec = *target.spec;
    const PassCamera& pc = ctx.cameras[index];
    if (iteration == 0) report("pass " + ctx.spec->name + " " + pass.name);
    const int write = target.buffers == 2 ? 1 - target.front : 0;
    const bool clears_all = std::all_of(pass.state.clear_colors.begin(), pass.state.clear_colors.end(),
                                        [](const auto& c) { return c.has_value(); });
    if (target.buffers == 2 && !clears_all) copyFrontToBack(target);

    glUseProgram(prog.id());
    prog.restoreDefaults();
    if (!bindInputs(pass, prog)) return false;
    if (!setLabUniforms(pass, prog, ctx)) return false;
    glUseProgram(prog.id());

    const glm::mat4& view = pc.values.view;
    const glm::mat4& projection = pc.values.projection;
    const glm::mat4 view_projection = projection * view;
    const glm::mat4 inverse_vp = glm::inverse(view_projection);
    setFramework(prog, file, "u_view", GL_FLOAT_MAT4,
                 [&](GLint l) { glUniformMatrix4fv(l, 1, GL_FALSE, glm::value_ptr(view)); });
    setFramework(prog, file, "u_projection", GL_FLOAT_MAT4,
                 [&](GLint l) { glUniformMatrix4fv(l, 1, GL_FALSE, glm::value_ptr(projection)); });
    setFramework(prog, file, "u_view_projection", GL_FLOAT_MAT4,
                 [&](GLint l) { glUniformMatrix4fv(l, 1, GL_FALSE, glm::value_ptr(view_projection)); });
    setFramework(prog, file, "u_inverse_view_projection", GL_FLOAT_MAT4,
                 [&](GLint l) { glUniformMatrix4fv(l, 1, GL_FALSE, glm::value_ptr(inverse_vp)); });
    setFramework(prog, file, "u_camera_position", GL_FLOAT_VEC3,
                 [&](GLint l) { glUniform3fv(l, 1, glm::value_ptr(pc.camera.position)); });
    setFramework(prog, file, "u_time", GL_FLOAT, [&](GLint l) { glUniform1f(l, ctx.spec->time); });
    setFramework(prog, file, "u_iteration", GL_INT, [&](GLint l) { glUniform1i(l, iteration); });
    setFramework(prog, file, "u_resolution", GL_FLOAT_VEC2, [&](GLint l) {
        glUniform2f(l, static_cast<float>(tspec.width), static_cast<float>(tspec.height));
    });
    const int light_count = std::min<int>(kMaxLights, static_cast<int>(ctx.lights.size()));
    glm::vec4 light_position[kMaxLights] = {};
    glm::vec3 light_color[kMaxLights] = {};
    for (int i = 0; i < light_count; ++i) {
        const ResolvedLight& l = ctx.lights[static_cast<std::size_t>(i)];
        light_position[i] = l.directional ? glm::vec4(-l.direction, 0.0f) : glm::vec4(l.position, 1.0f);
        light_color[i] = l.color;
    }
    float light_range[kMaxLights] = {};
    glm::vec3 light_direction[kMaxLights] = {};
    glm::vec2 light_cone[kMaxLights] = {};
    for (int i = 0; i < light_count; ++i) {
        const ResolvedLight& l = ctx.lights[static_cast<std::size_t>(i)];
        light_range[i] = l.range;
        light_direction[i] = l.direction;
        light_cone[i] = l.cone;
    }
    setFramework(prog, file, "u_light_count", GL_INT, [&](GLint l) { glUniform1i(l, light_count); });
    // KHR_lights_punctual range and spot cones (docs/scenes.md): arrays like u_light_position.
    const auto lightArray = [&](const char* name, GLenum type,
                                const std::function<void(GLint, GLsizei)>& set) {
        if (const UniformSlot* s = prog.uniform(name)) {
            if (s->type == type)
                set(s->location, std::min(s->size, kMaxLights));
            else
                warnOnce(file, std::string(name) + " is provided by the framework as " + glslTypeName(type));
        }
    };
    lightArray("u_light_range", GL_FLOAT, [&](GLint l, GLsizei n) { glUniform1fv(l, n, light_range); });
    lightArray("u_light_direction", GL_FLOAT_VEC3,
               [&](GLint l, GLsizei n) { glUniform3fv(l, n, glm::value_ptr(light_direction[0])); });
    lightArray("u_light_cone", GL_FLOAT_VEC2,
               [&](GLint l, GLsizei n) { glUniform2fv(l, n, glm::value_ptr(light_cone[0])); });
    // All declared entries are written (unused ones zero), so no light of another scene lingers.
    if (const UniformSlot* s = prog.uniform("u_light_position")) {
        if (s->type == GL_FLOAT_VEC4)
            glUniform4fv(s->location, std::min(s->size, kMaxLights), glm::value_ptr(light_position[0]));
        else
            warnOnce(file, "u_light_position is provided by the framework as vec4");
    }
    if (const UniformSlot* s = prog.uniform("u_light_color")) {
        if (s->type == GL_FLOAT_VEC3)
            glUniform3fv(s->location, std::min(s->size, kMaxLights), glm::value_ptr(light_color[0]));
        else
            warnOnce(file, "u_light_color is provided by the framework as vec3");
    }

    const bool program_point_size =
        pass.draw == DrawKind::Procedural && mentionsIdentifier(prog.preparedText(0), "gl_PointSize");
    static const Material kDefaultMaterial;
    const MaterialWarning scene_warning = [&](const std::string& message) {
        warnOnce("../" + ctx.spec->file, message);
    };
    auto draw = [&](GpuMesh* mesh, const glm::mat4& model, const Material& material) {
        const glm::vec4& base_color = material.base_color;
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
        setFramework(prog, file, "u_metallic", GL_FLOAT, [&](GLint l) { glUniform1f(l, material.metallic); });
        setFramework(prog, file, "u_roughness", GL_FLOAT,
                     [&](GLint l) { glUniform1f(l, material.roughness); });
        setFramework(prog, file, "u_emissive", GL_FLOAT_VEC3,
                     [&](GLint l) { glUniform3fv(l, 1, glm::value_ptr(material.emissive)); });
        material_textures_.bindMaterial(ctx.scene->scene, material, scene_warning);
        if (!mesh) {
            glBindVertexArray(empty_vao_);
            glDrawArrays(glPrimitive(pass.primitive), 0, pass.vertex_count);
        } else {
            glBindVertexArray(mesh->vao);
            const std::vector<GLuint> enabled = bindOptionalAttributes(*mesh, prog.id());
            glDrawElements(GL_TRIANGLES, mesh->index_count, GL_UNSIGNED_INT, nullptr);
            for (GLuint loc : enabled) glDisableVertexAttribArray(loc);
        }
    };
    for (int face = 0; face < target.faces(); ++face) {
        glBindFramebuffer(GL_FRAMEBUFFER, target.fbos.at({write, face}));
        glViewport(0, 0, tspec.width, tspec.height);
        applyState(pass.state, tspec.format == TargetFormat::SRGB8, program_point_size);
        clearTarget(pass.state, target.depth != DepthMode::None);
        setFramework(prog, file, "u_cube_face", GL_INT, [&](GLint l) { glUniform1i(l, face); });
        if (pass.draw == DrawKind::Fullscreen) {
            draw(fullscreen_.get(), glm::mat4(1.0f), kDefaultMaterial);
        } else if (pass.draw == DrawKind::Procedural) {
            draw(nullptr, glm::mat4(1.0f), kDefaultMaterial);
        } else {
            for (const DrawItem& item : ctx.scene->scene.draw_items) {
                const Material& material =
                    item.material >= 0 ? ctx.scene->scene.materials[static_cast<std::size_t>(item.material)]
                                       : kDefaultMaterial;
                // A mirroring transform turns the winding over; a double-sided material is not
                // back-face culled (glTF 2.0, 3.9.6). Front-face culling, a lab's own technique
                // (inverted-hull outlines), stays.
                const bool unculled = material.double_sided && pass.state.cull == CullMode::Back;
                if (item.mirrored) glFrontFace(GL_CW);
                if (unculled) glDisable(GL_CULL_FACE);
                draw(ctx.scene->meshes[static_cast<std::size_t>(item.mesh)].get(), item.world, material);
                if (item.mirrored) glFrontFace(GL_CCW);
                if (unculled) glEnable(GL_CULL_FACE);
            }
        }
    }
    glBindVertexArray(0);
    const GLenum err = glGetError();
    if (err != GL_NO_ERROR)
        return fail(RenderStatus::RenderError,
                    "pass '" + pass.name + "', scene '" + ctx.spec->name + "': " + glErrorName(err));
    target.front = write;
    if (pass.draw == DrawKind::Fullscreen) target.fullscreen_drawn = true;
    if (target.mipmapped) {
        glActiveTexture(GL_TEXTURE0 + kScratchTextureUnit);
        for (GLuint tex : target.color[target.front]) {
            glBindTexture(target.textureTarget(), tex);
            glGenerateMipmap(target.textureTarget());
        }
        glBindTexture(target.textureTarget(), 0);
        glActiveTexture(GL_TEXTURE0);
    }
    if (!last_iteration) return true;
    std::vector<std::string> read = pass.graded;
    if (options_.keep_all_passes) {
        read = tspec.attachments;
        if (target.depth != DepthMode::None && !target.cube()) read.push_back("depth");
    }
    if (read.empty()) return true;
    ScopedTiming timing("readback", spec_.id, ctx.spec->name);
    const std::vector<std::uint8_t> coverage = readCoverage(target);
    for (const std::string& attachment : read) {
        PassImage img;
        img.pass = pass.name;
        img.target = tspec.name;
        img.attachment = attachment;
        img.graded = std::find(pass.graded.begin(), pass.graded.end(), attachment) != pass.graded.end();
        img.color = readAttachment(target, attachment);
        img.coverage = coverage;
        ctx.out->passes.push_back(std::move(img));
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
