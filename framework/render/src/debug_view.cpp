// The debug view of a scene's vertex data; see debug_view.h. The scene is loaded and its meshes
// uploaded as the lab runner does it (gltf_loader.h, scene_upload.cpp), then drawn once with the
// framework's program into a float target of this file's own and read back.
#include "shaderlab/render/debug_view.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <memory>
#include <set>

#include "lab_runner.h"
#include "shaderlab/gl/gl.h"
#include "shaderlab/scene/camera.h"
#include "shaderlab/scene/gltf_loader.h"

namespace shaderlab {

// shaders/debug_view.vert and .frag, compiled in (CMakeLists.txt).
extern const char* const kDebugViewVert;
extern const char* const kDebugViewFrag;

namespace {

const std::vector<DebugViewInfo> kViews = {
    {DebugView::Normals, "normals", "world-space normal as n * 0.5 + 0.5 (x red, y green, z blue)"},
    {DebugView::Tangents, "tangents",
     "world-space tangent (TANGENT xyz) as t * 0.5 + 0.5; grey: the file has no TANGENT"},
    {DebugView::Bitangents, "bitangents",
     "world-space bitangent cross(n, t.xyz) * t.w as b * 0.5 + 0.5; grey: the file has no TANGENT"},
    {DebugView::Handedness, "handedness",
     "TANGENT w: green +1, red -1, dark where it changes across a triangle; grey: no TANGENT"},
    {DebugView::Uv, "uv",
     "texture coordinates (s, t, 0) as shaders read a_texcoord (t = 1 - glTF v); grey: no TEXCOORD_0"},
    {DebugView::UvChecker, "uv-checker",
     "8 checker cells per unit over (fract(s), fract(t), 0): wrapped and mirrored coordinates show; "
     "grey: no TEXCOORD_0"},
};

bool showsTangents(DebugView v) {
    return v == DebugView::Tangents || v == DebugView::Bitangents || v == DebugView::Handedness;
}

// The fragment stage of `view` (Off: the grey of a mesh without the data): the framework's text
// with the view and the grey defined after its #version line.
std::string fragmentFor(DebugView view) {
    std::string text = kDebugViewFrag;
    char defines[96];
    std::snprintf(defines, sizeof defines, "#define SL_DEBUG_VIEW %d\n#define SL_DEBUG_NEUTRAL %.9g\n",
                  static_cast<int>(view), static_cast<double>(kDebugNeutral));
    return text.insert(text.find('\n') + 1, defines);
}

// The size of the lab's final graded image, so the view lines up with the lab's picture.
void outputSize(const LabSpec& spec, int* width, int* height) {
    *width = *height = 512;
    for (const PassSpec& p : spec.passes)
        if (!p.graded.empty())
            if (const TargetSpec* t = spec.findTarget(p.target)) {
                *width = std::clamp(t->width, 1, 4096);
                *height = std::clamp(t->height, 1, 4096);
            }
}

// A float colour texture and a depth buffer, drawn into once per scene.
struct DebugTarget {
    GLuint fbo = 0, color = 0, depth = 0;
    int width = 0, height = 0;
    DebugTarget() = default;
    DebugTarget(const DebugTarget&) = delete;
    DebugTarget& operator=(const DebugTarget&) = delete;
    ~DebugTarget() {
        if (fbo) glDeleteFramebuffers(1, &fbo);
        if (color) glDeleteTextures(1, &color);
        if (depth) glDeleteRenderbuffers(1, &depth);
    }
    bool create(int w, int h) {
        width = w;
        height = h;
        glGenTextures(1, &color);
        glBindTexture(GL_TEXTURE_2D, color);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, w, h, 0, GL_RGBA, GL_FLOAT, nullptr);
        glBindTexture(GL_TEXTURE_2D, 0);
        glGenRenderbuffers(1, &depth);
        glBindRenderbuffer(GL_RENDERBUFFER, depth);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, w, h);
        glBindRenderbuffer(GL_RENDERBUFFER, 0);
        glGenFramebuffers(1, &fbo);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, color, 0);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
        const GLenum buffer = GL_COLOR_ATTACHMENT0;
        glDrawBuffers(1, &buffer);
        return glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    }
};

class DebugRenderer {
  public:
    DebugRenderer(const LabSpec& spec, DebugView view, const RenderOptions& options, LabRender* out)
        : spec_(spec), view_(view), options_(options), out_(*out) {}
    ~DebugRenderer() {
        glUseProgram(0);
        glBindVertexArray(0);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
    }
    bool prepare();
    bool renderScene(const SceneSpec& scene_spec);

  private:
    void report(const std::string& event) const {
        if (options_.progress) options_.progress(event);
    }
    bool fail(const std::string& message) {
        out_.status = RenderStatus::RenderError;
        out_.message = "debug view: " + message;
        return false;
    }
    void diagnose(const std::string& file, const std::string& severity, const std::string& message) {
        if (said_.insert(file + '\n' + message).second)
            out_.diagnostics.push_back({file, 0, 0, severity, message});
    }
    bool build(ShaderProgram* program, DebugView view);
    bool hasData(const Mesh& m) const;
    void noteMissing(const SceneSpec& scene_spec, const Mesh& m);
    void drawItem(const ShaderProgram& program, const glm::mat4& view_projection, const DrawItem& item,
                  render_detail::GpuMesh& mesh);
    bool draw(const SceneSpec& scene_spec, const Scene& scene, const Camera& camera);
    PassImage readBack() const;

    const LabSpec& spec_;
    const DebugView view_;
    const RenderOptions& options_;
    LabRender& out_;
    ShaderProgram program_;  // the view
    ShaderProgram neutral_;  // grey, for a mesh without what the view shows
    DebugTarget target_;
    std::set<std::string> said_;
};

bool DebugRenderer::build(ShaderProgram* program, DebugView view) {
    program->build("debug_view.vert", kDebugViewVert, "debug_view.frag", fragmentFor(view));
    if (program->linked()) return true;
    std::string why = "the program did not build";
    for (const Diagnostic& d : program->diagnostics())
        if (d.severity == "error") {
            why += ": " + d.file + ":" + std::to_string(d.line) + ": " + d.message;
            break;
        }
    return fail(why);
}

bool DebugRenderer::prepare() {
    report("compile debug_view.vert debug_view.frag");
    if (!build(&program_, view_) || !build(&neutral_, DebugView::Off)) return false;
    int width = 0, height = 0;
    outputSize(spec_, &width, &height);
    if (!target_.create(width, height)) return fail("its framebuffer is not complete on this driver");
    return true;
}

bool DebugRenderer::hasData(const Mesh& m) const {
    if (showsTangents(view_)) return m.tangents.size() == m.positions.size() && !m.tangents_generated;
    if (view_ == DebugView::Uv || view_ == DebugView::UvChecker) return m.had_texcoords;
    return true;
}

// What the picture cannot show of mesh `m`, said once per file and mesh.
void DebugRenderer::noteMissing(const SceneSpec& scene_spec, const Mesh& m) {
    const std::string where = " in " + scene_spec.file + ", mesh " + m.name;
    const std::string file = "../" + scene_spec.file;
    if (showsTangents(view_) && !hasData(m))
        diagnose(file, "note",
                 "no tangents" + where + ": drawn grey; lab shaders read " +
                     (m.tangents_generated ? "the MikkTSpace tangents the loader generates for it"
                                           : "a_tangent = (1, 0, 0, 1)"));
    else if (!hasData(m))
        diagnose(file, "note",
                 "no texture coordinates" + where + ": drawn grey; lab shaders read a_texcoord = (0, 0)");
    else if (view_ == DebugView::Normals && !m.had_normals)
        diagnose(file, "note",
                 "no normals" + where +
                     ": the flat normals the loader made are shown (lab shaders read them too)");
}

void DebugRenderer::drawItem(const ShaderProgram& program, const glm::mat4& view_projection,
                             const DrawItem& item, render_detail::GpuMesh& mesh) {
    glUseProgram(program.id());
    // The framework's names and meanings (docs/student-contract.md), set here for this program only.
    glUniformMatrix4fv(glGetUniformLocation(program.id(), "u_view_projection"), 1, GL_FALSE,
                       glm::value_ptr(view_projection));
    glUniformMatrix4fv(glGetUniformLocation(program.id(), "u_model"), 1, GL_FALSE,
                       glm::value_ptr(item.world));
    const glm::mat3 normal_matrix = glm::inverseTranspose(glm::mat3(item.world));
    glUniformMatrix3fv(glGetUniformLocation(program.id(), "u_normal_matrix"), 1, GL_FALSE,
                       glm::value_ptr(normal_matrix));
    glBindVertexArray(mesh.vao);
    const std::vector<GLuint> enabled = render_detail::bindOptionalAttributes(mesh, program.id());
    glDrawElements(GL_TRIANGLES, mesh.index_count, GL_UNSIGNED_INT, nullptr);
    for (GLuint location : enabled) glDisableVertexAttribArray(location);
}

bool DebugRenderer::draw(const SceneSpec& scene_spec, const Scene& scene, const Camera& camera) {
    std::vector<std::unique_ptr<render_detail::GpuMesh>> meshes;
    for (const Mesh& m : scene.meshes) {
        meshes.push_back(render_detail::uploadMesh(m));
        meshes.back()->source = &m;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, target_.fbo);
    glViewport(0, 0, target_.width, target_.height);
    for (GLenum cap : {GL_BLEND, GL_CULL_FACE, GL_SCISSOR_TEST, GL_STENCIL_TEST, GL_DEPTH_CLAMP,
                       GL_POLYGON_OFFSET_FILL, GL_FRAMEBUFFER_SRGB, GL_RASTERIZER_DISCARD})
        glDisable(cap);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glClearColor(kDebugBackground[0], kDebugBackground[1], kDebugBackground[2], 0.0f);
    glClearDepth(1.0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    const float aspect = static_cast<float>(target_.width) / static_cast<float>(target_.height);
    const glm::mat4 view_projection = projectionMatrix(camera, aspect) * viewMatrix(camera);
    for (const DrawItem& item : scene.draw_items) {
        if (item.mesh < 0 || item.mesh >= static_cast<int>(meshes.size())) continue;
        const Mesh& m = scene.meshes[static_cast<std::size_t>(item.mesh)];
        noteMissing(scene_spec, m);
        drawItem(hasData(m) ? program_ : neutral_, view_projection, item,
                 *meshes[static_cast<std::size_t>(item.mesh)]);
    }
    glBindVertexArray(0);
    glFinish();
    const GLenum error = glGetError();
    if (error != GL_NO_ERROR)
        return fail("scene '" + scene_spec.name + "': GL error " + std::to_string(error) + " while drawing");
    return true;
}

// The target as an opaque RGBA image (alpha 1, as every PassImage is RGBA), top row first;
// coverage where a mesh was drawn (the target's alpha, cleared to 0).
PassImage DebugRenderer::readBack() const {
    const int w = target_.width, h = target_.height;
    std::vector<float> rgba(static_cast<std::size_t>(w) * h * 4);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, target_.fbo);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_FLOAT, rgba.data());
    PassImage img;
    img.pass = "debug";
    img.target = "debug";
    img.attachment = debugViewName(view_);
    img.color = grader::Image(w, h, 4);
    img.coverage.assign(static_cast<std::size_t>(w) * h, 0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float* p = &rgba[(static_cast<std::size_t>(h - 1 - y) * w + x) * 4];
            for (int c = 0; c < 3; ++c) img.color.at(x, y, c) = p[c];
            img.color.at(x, y, 3) = 1.0f;
            img.coverage[static_cast<std::size_t>(y) * w + x] = p[3] > 0.5f ? 1 : 0;
        }
    return img;
}

bool DebugRenderer::renderScene(const SceneSpec& scene_spec) {
    const auto t0 = std::chrono::steady_clock::now();
    report("scene " + scene_spec.name);
    SceneRender scene_out;
    scene_out.scene = scene_spec.name;
    Scene scene;
    if (!scene_spec.file.empty()) {
        const std::string path = (std::filesystem::path(spec_.labs_root) / scene_spec.file).string();
        const SceneLoadResult loaded = loadGltfScene(path, &scene);
        for (const std::string& w : loaded.warnings) diagnose("../" + scene_spec.file, "warning", w);
        if (!loaded.ok) {
            scene_out.error = loaded.error;
            diagnose("../" + scene_spec.file, "error", loaded.error);
        }
    } else {
        diagnose("lab.json", "note",
                 "scene " + scene_spec.name + " has no scene file: no vertex data to show");
    }
    if (scene_out.error.empty()) {
        Camera camera = scene.camera;
        const std::vector<ResolvedLight> lights = resolveLights(scene, scene_spec, camera);
        const std::string problem = applyCameraOverride(scene, lights, scene_spec.camera, &camera);
        if (!problem.empty()) {
            scene_out.error = scene_spec.path + ".camera: " + problem;
            diagnose("lab.json", "error", scene_out.error);
        } else {
            orbitCamera(scene, options_.orbit, &camera);
            if (!draw(scene_spec, scene, camera)) return false;
            scene_out.passes.push_back(readBack());
        }
    }
    scene_out.render_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    char ms[32];
    std::snprintf(ms, sizeof ms, "%.1f", scene_out.render_ms);
    report("done " + scene_spec.name + " " + ms);
    out_.scenes.push_back(std::move(scene_out));
    return true;
}

}  // namespace

const std::vector<DebugViewInfo>& debugViews() { return kViews; }

const DebugViewInfo* debugViewInfo(DebugView view) {
    for (const DebugViewInfo& v : kViews)
        if (v.view == view) return &v;
    return nullptr;
}

const char* debugViewName(DebugView view) {
    const DebugViewInfo* info = debugViewInfo(view);
    return info ? info->name : "off";
}

bool parseDebugView(const std::string& name, DebugView* out) {
    if (name == "off") {
        *out = DebugView::Off;
        return true;
    }
    for (const DebugViewInfo& v : kViews)
        if (name == v.name) {
            *out = v.view;
            return true;
        }
    return false;
}

std::string debugViewNames(const std::string& separator) {
    std::string names = "off";
    for (const DebugViewInfo& v : kViews) names += separator + v.name;
    return names;
}

std::string describeDebugPixel(DebugView view, float r, float g, float b, bool covered) {
    if (!covered) return "no mesh here";
    char text[160];
    if (r == kDebugNeutral && g == kDebugNeutral && b == kDebugNeutral) {
        std::snprintf(text, sizeof text, "grey: this mesh has no data for the %s view", debugViewName(view));
    } else if (view == DebugView::Handedness) {
        std::snprintf(text, sizeof text, "handedness w = %+.3f", g - r);
    } else if (view == DebugView::Uv) {
        std::snprintf(text, sizeof text, "texture coordinates s = %.4f, t = %.4f", r, g);
    } else if (view == DebugView::UvChecker) {
        std::snprintf(text, sizeof text, "checker colour: the uv view reads the coordinates themselves");
    } else {
        const char* what = view == DebugView::Normals    ? "normal"
                           : view == DebugView::Tangents ? "tangent"
                                                         : "bitangent";
        std::snprintf(text, sizeof text, "%s (%+.3f, %+.3f, %+.3f)", what, 2.0f * r - 1.0f, 2.0f * g - 1.0f,
                      2.0f * b - 1.0f);
    }
    return text;
}

LabRender renderDebugView(const LabSpec& spec, DebugView view, const RenderOptions& options) {
    LabRender result;
    if (view == DebugView::Off) {
        result.status = RenderStatus::RenderError;
        result.message = "debug view: no view chosen";
        return result;
    }
    DebugRenderer renderer(spec, view, options, &result);
    if (!renderer.prepare()) return result;
    for (const SceneSpec& scene_spec : spec.scenes) {
        if (!options.only_scenes.empty() && std::find(options.only_scenes.begin(), options.only_scenes.end(),
                                                      scene_spec.name) == options.only_scenes.end())
            continue;
        if (!renderer.renderScene(scene_spec)) break;
    }
    return result;
}

}  // namespace shaderlab
