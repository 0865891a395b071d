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
    glm::vec4 position[kMaxLights];  // w = 1: point at xyz; w = 0: xyz points toward the light
    glm::vec3 color[kMaxLights];     // colour times intensity
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

// Sets a framework uniform when the shader declares it with the right type; framework
// uniforms the shader does not use are simply skipped.
void setIfActive(const ShaderProgram& p, const char* name, GLenum type,
                 const std::function<void(GLint)>& fn) {
    const UniformSlot* s = p.uniform(name);
    if (s && s->type == type) fn(s->location);
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

LabRender renderLab(const LabSpec& spec, const std::string& shader_dir, const RenderOptions& options) {
    LabRender result;

    // 1. Read every student file first: a missing file is reported before any GL work.
    std::map<std::string, std::string> sources;
    for (const PassSpec& pass : spec.passes) {
        for (const std::string* file : {&pass.program.vertex, &pass.program.fragment}) {
            if (sources.count(*file)) continue;
            FileText t = readFileInside(shader_dir, *file, kMaxShaderBytes);
            if (!t.ok) {
                result.status = RenderStatus::Missing;
                result.message = t.error;
                result.diagnostics.push_back({*file, 0, 0, "error", t.error});
                return result;
            }
            sources[*file] = std::move(t.text);
        }
    }

    // 2. Build one program per distinct (vertex, fragment) pair.
    std::map<std::pair<std::string, std::string>, ShaderProgram> programs;
    for (const PassSpec& pass : spec.passes) {
        const auto key = std::make_pair(pass.program.vertex, pass.program.fragment);
        if (programs.count(key)) continue;
        ShaderProgram& prog = programs[key];
        prog.build(key.first, sources[key.first], key.second, sources[key.second]);
        for (const Diagnostic& d : prog.diagnostics()) result.diagnostics.push_back(d);
        if (!prog.compiled()) {
            result.status = RenderStatus::CompileError;
        } else if (!prog.linked() && result.status == RenderStatus::Ok) {
            result.status = RenderStatus::LinkError;
        }
    }
    if (result.status != RenderStatus::Ok) {
        for (const Diagnostic& d : result.diagnostics) {
            if (d.severity != "error") continue;
            result.message = d.file + (d.line ? ":" + std::to_string(d.line) : "") + ": " + d.message;
            break;
        }
        if (result.message.empty()) result.message = renderStatusName(result.status);
        return result;
    }

    // 3. Textures the lab ships, shared by all scenes.
    std::map<std::string, GLuint> file_textures;
    auto cleanup_textures = [&file_textures]() {
        for (auto& [name, tex] : file_textures) glDeleteTextures(1, &tex);
    };
    for (const PassSpec& pass : spec.passes) {
        for (const PassInput& in : pass.inputs) {
            if (in.texture_file.empty() || file_textures.count(in.texture_file)) continue;
            const PathResult p = resolveInside(spec.lab_dir, in.texture_file);
            grader::Image img;
            std::string err;
            if (!p.ok || !grader::readPng(p.path, &img, &err)) {
                result.status = RenderStatus::RenderError;
                result.message = p.ok ? err : p.error;
                cleanup_textures();
                return result;
            }
            // Upload as RGBA float with the top row last, as GL expects row 0 at the bottom.
            std::vector<float> rgba(static_cast<std::size_t>(img.width) * img.height * 4, 1.0f);
            for (int y = 0; y < img.height; ++y)
                for (int x = 0; x < img.width; ++x)
                    for (int c = 0; c < 4; ++c) {
                        const int src_c = img.channels == 1 ? 0 : c;
                        if (c < img.channels || (img.channels == 1 && c < 3))
                            rgba[(static_cast<std::size_t>(img.height - 1 - y) * img.width + x) * 4 + c] =
                                img.at(x, y, src_c);
                    }
            GLuint tex = 0;
            glGenTextures(1, &tex);
            glBindTexture(GL_TEXTURE_2D, tex);
            glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, img.width, img.height, 0, GL_RGBA, GL_FLOAT,
                         rgba.data());
            file_textures[in.texture_file] = tex;
        }
    }

    // 4. Targets, one per pass that owns one; created once and reused for every scene.
    std::map<std::string, std::unique_ptr<Target>> targets;  // by target name
    std::map<std::string, const TargetSpec*> target_specs;
    std::vector<std::string> pass_target(spec.passes.size());
    std::vector<bool> pass_draws_depth(spec.passes.size(), false);
    for (std::size_t i = 0; i < spec.passes.size(); ++i) {
        const PassSpec& pass = spec.passes[i];
        if (!pass.draw_into.empty()) {
            for (std::size_t j = 0; j < i; ++j)
                if (spec.passes[j].name == pass.draw_into) pass_target[i] = pass_target[j];
            continue;
        }
        auto t = std::make_unique<Target>();
        std::string err;
        if (!createTarget(pass.target, spec.width, spec.height, t.get(), &err)) {
            result.status = RenderStatus::RenderError;
            result.message = err;
            cleanup_textures();
            return result;
        }
        pass_target[i] = pass.target.name;
        target_specs[pass.target.name] = &pass.target;
        targets[pass.target.name] = std::move(t);
    }
    for (std::size_t i = 0; i < spec.passes.size(); ++i)
        if (spec.passes[i].draw == DrawKind::Scene) pass_draws_depth[i] = true;

    const auto fullscreen = fullscreenTriangle();
    std::map<std::string, Scene> scene_cache;

    for (const SceneSpec& scene_spec : spec.scenes) {
        if (!options.only_scenes.empty() && std::find(options.only_scenes.begin(), options.only_scenes.end(),
                                                      scene_spec.name) == options.only_scenes.end())
            continue;
        const auto t0 = std::chrono::steady_clock::now();
        SceneRender scene_out;
        scene_out.scene = scene_spec.name;

        const Scene* scene = nullptr;
        static const Scene kEmptyScene;
        std::vector<std::unique_ptr<GpuMesh>> gpu_meshes;
        if (!scene_spec.file.empty()) {
            const std::string path = (std::filesystem::path(spec.labs_root) / scene_spec.file).string();
            auto it = scene_cache.find(path);
            if (it == scene_cache.end()) {
                Scene loaded;
                const SceneLoadResult r = loadGltfScene(path, &loaded);
                if (!r.ok) {
                    result.status = RenderStatus::RenderError;
                    result.message = r.error;
                    cleanup_textures();
                    return result;
                }
                it = scene_cache.emplace(path, std::move(loaded)).first;
            }
            scene = &it->second;
            for (const Mesh& m : scene->meshes) gpu_meshes.push_back(uploadMesh(m));
        } else {
            scene = &kEmptyScene;
        }

        const Camera camera = resolveCamera(*scene, scene_spec.camera);
        const LightUniforms lights = resolveLights(*scene, scene_spec, camera);
        const glm::mat4 view = glm::lookAt(camera.position, camera.target, camera.up);

        for (std::size_t pi = 0; pi < spec.passes.size(); ++pi) {
            const PassSpec& pass = spec.passes[pi];
            const ShaderProgram& prog = programs.at({pass.program.vertex, pass.program.fragment});
            Target& target = *targets.at(pass_target[pi]);
            glBindFramebuffer(GL_FRAMEBUFFER, target.fbo);
            glViewport(0, 0, target.width, target.height);
            applyState(pass.state);
            glUseProgram(prog.id());

            // Inputs: earlier targets and lab textures on consecutive texture units.
            int unit = 0;
            for (const PassInput& in : pass.inputs) {
                GLuint tex = 0;
                TextureFilter filter = TextureFilter::Linear;
                TextureWrap wrap = TextureWrap::ClampToEdge;
                if (!in.from_pass.empty()) {
                    tex = targets.at(in.from_pass)->color;
                    filter = target_specs.at(in.from_pass)->filter;
                    wrap = target_specs.at(in.from_pass)->wrap;
                } else {
                    tex = file_textures.at(in.texture_file);
                }
                if (in.filter) filter = *in.filter;
                if (in.wrap) wrap = *in.wrap;
                glActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(unit));
                setSampling(tex, filter, wrap);
                if (const UniformSlot* s = prog.uniform(in.sampler)) glUniform1i(s->location, unit);
                ++unit;
            }
            glActiveTexture(GL_TEXTURE0);

            const float aspect = static_cast<float>(target.width) / static_cast<float>(target.height);
            const glm::mat4 projection =
                glm::perspective(glm::radians(camera.fov_y_deg), aspect, camera.z_near, camera.z_far);
            setIfActive(prog, "u_view", GL_FLOAT_MAT4,
                        [&](GLint l) { glUniformMatrix4fv(l, 1, GL_FALSE, glm::value_ptr(view)); });
            setIfActive(prog, "u_projection", GL_FLOAT_MAT4,
                        [&](GLint l) { glUniformMatrix4fv(l, 1, GL_FALSE, glm::value_ptr(projection)); });
            setIfActive(prog, "u_camera_position", GL_FLOAT_VEC3,
                        [&](GLint l) { glUniform3fv(l, 1, glm::value_ptr(camera.position)); });
            setIfActive(prog, "u_time", GL_FLOAT, [&](GLint l) { glUniform1f(l, scene_spec.time); });
            setIfActive(prog, "u_resolution", GL_FLOAT_VEC2, [&](GLint l) {
                glUniform2f(l, static_cast<float>(target.width), static_cast<float>(target.height));
            });
            setIfActive(prog, "u_light_count", GL_INT, [&](GLint l) { glUniform1i(l, lights.count); });
            if (const UniformSlot* s = prog.uniform("u_light_position"); s && s->type == GL_FLOAT_VEC4)
                glUniform4fv(s->location, std::min(s->size, lights.count),
                             glm::value_ptr(lights.position[0]));
            if (const UniformSlot* s = prog.uniform("u_light_color"); s && s->type == GL_FLOAT_VEC3)
                glUniform3fv(s->location, std::min(s->size, lights.count), glm::value_ptr(lights.color[0]));

            // Lab values: the pass's, then the scene's overrides.
            for (const UniformMap* map : {&pass.uniforms, &scene_spec.uniforms}) {
                for (const auto& [name, value] : *map) {
                    const std::string warning = prog.set(name, value);
                    if (!warning.empty() && scene_out.scene == spec.scenes.front().name)
                        result.diagnostics.push_back({pass.program.fragment, 0, 0, "warning", warning});
                }
            }
            glUseProgram(prog.id());

            auto draw = [&](const GpuMesh& mesh, const glm::mat4& model, const glm::vec4& base_color) {
                const glm::mat4 model_view = view * model;
                const glm::mat4 mvp = projection * model_view;
                const glm::mat3 normal_matrix = glm::inverseTranspose(glm::mat3(model));
                setIfActive(prog, "u_model", GL_FLOAT_MAT4,
                            [&](GLint l) { glUniformMatrix4fv(l, 1, GL_FALSE, glm::value_ptr(model)); });
                setIfActive(prog, "u_model_view", GL_FLOAT_MAT4,
                            [&](GLint l) { glUniformMatrix4fv(l, 1, GL_FALSE, glm::value_ptr(model_view)); });
                setIfActive(prog, "u_model_view_projection", GL_FLOAT_MAT4,
                            [&](GLint l) { glUniformMatrix4fv(l, 1, GL_FALSE, glm::value_ptr(mvp)); });
                setIfActive(prog, "u_normal_matrix", GL_FLOAT_MAT3, [&](GLint l) {
                    glUniformMatrix3fv(l, 1, GL_FALSE, glm::value_ptr(normal_matrix));
                });
                setIfActive(prog, "u_base_color", GL_FLOAT_VEC4,
                            [&](GLint l) { glUniform4fv(l, 1, glm::value_ptr(base_color)); });
                glBindVertexArray(mesh.vao);
                glDrawElements(GL_TRIANGLES, mesh.index_count, GL_UNSIGNED_INT, nullptr);
            };

            if (pass.draw == DrawKind::Fullscreen) {
                draw(*fullscreen, glm::mat4(1.0f), glm::vec4(1.0f));
            } else {
                for (const DrawItem& item : scene->draw_items) {
                    const glm::vec4 base =
                        item.material >= 0
                            ? scene->materials[static_cast<std::size_t>(item.material)].base_color
                            : glm::vec4(1.0f);
                    draw(*gpu_meshes[static_cast<std::size_t>(item.mesh)], item.world, base);
                }
            }
            glBindVertexArray(0);

            const GLenum err = glGetError();
            if (err != GL_NO_ERROR) {
                result.status = RenderStatus::RenderError;
                result.message =
                    "pass '" + pass.name + "', scene '" + scene_spec.name + "': " + glErrorName(err);
                cleanup_textures();
                return result;
            }
            if (pass.graded || options.keep_all_passes) {
                PassImage img = readBack(target, pass_draws_depth[pi] || !pass.draw_into.empty());
                img.pass = pass.name;
                img.target = pass_target[pi];
                img.graded = pass.graded;
                scene_out.passes.push_back(std::move(img));
            }
        }
        glFinish();
        scene_out.render_ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        result.scenes.push_back(std::move(scene_out));
    }
    cleanup_textures();
    glUseProgram(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return result;
}

}  // namespace shaderlab
