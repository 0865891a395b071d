// One run of a pass (lab_runner.h): the ping-pong copy, the program with its inputs and
// uniforms, a draw per cube face (the full-screen triangle, a mesh-less procedural draw, or the
// scene's meshes with their materials), then the GL error check, mipmaps and read-back; and the
// loop guard, read after each run. The state a pass draws with is pass_state.cpp's, its textures
// pass_inputs.cpp's, its uniforms pass_uniforms.cpp's.
#include <algorithm>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <vector>

#include "lab_runner.h"
#include "loop_probe.h"

namespace shaderlab::render_detail {

namespace {

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

}  // namespace

// The counters guarded programs write when a loop runs past kLoopGuardLimit, one for each
// stage, file and line (shader_program.h).
void LabRunner::createLoopGuard() {
    if (!GLAD_GL_VERSION_4_3) return;
    const std::vector<GLuint> zero(kLoopGuardWords, 0);
    glGenBuffers(1, &loop_guard_);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, loop_guard_);
    glBufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(zero.size() * sizeof(GLuint)), zero.data(),
                 GL_DYNAMIC_READ);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLoopGuardBinding, loop_guard_);
}

// After a pass: did a loop of its program run past the guard? Then the render stops here, at the
// line of the loop most invocations were in when they ran past it.
bool LabRunner::checkLoopGuard(const PassSpec& pass, const std::string& scene) {
    if (!loop_guard_) return true;
    std::vector<GLuint> counts(kLoopGuardWords, 0);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, loop_guard_);
    glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, static_cast<GLsizeiptr>(counts.size() * sizeof(GLuint)),
                       counts.data());
    const std::size_t per_stage = counts.size() / 2;
    std::size_t total[2] = {0, 0}, worst[2] = {0, 0};  // worst: the counter's place within its stage's
    for (std::size_t k = 0; k < 2; ++k)
        for (std::size_t i = 0; i < per_stage; ++i) {
            const GLuint c = counts[k * per_stage + i];
            total[k] += c;
            if (c > counts[k * per_stage + worst[k]]) worst[k] = i;
        }
    if (total[0] == 0 && total[1] == 0) return true;
    const int stage = total[0] > 0 ? 0 : 1;
    const std::size_t at = worst[stage];
    const LoopSite site = programOf(pass).loopSite(stage, static_cast<int>(at / kLoopGuardLines),
                                                   static_cast<int>(at % kLoopGuardLines));
    const bool vertex = stage == 0;
    const std::string& file =
        site.file.empty() ? (vertex ? pass.program.vertex : pass.program.fragment) : site.file;
    const std::string which = site.line > 0 ? "the loop at line " + std::to_string(site.line) : "a loop";
    const std::string message =
        "endless loop: in pass '" + pass.name + "' of scene '" + scene + "', " + which + " ran more than " +
        std::to_string(kLoopGuardLimit) + " times for one " + (vertex ? "vertex" : "pixel") + " (" +
        std::to_string(total[stage]) + (vertex ? " vertices" : " pixels") +
        "); the grader stops it there, as a GPU would hang on it. Check that every loop's condition "
        "becomes false: its counter must change, and towards the end";
    out_.endless_loop = true;
    out_.diagnostics.push_back({file, site.line, site.column, "error", message, "", site.source_line});
    return fail(RenderStatus::RenderError,
                file + (site.line > 0 ? ":" + std::to_string(site.line) : "") + ": " + message);
}

bool LabRunner::runPass(std::size_t index, int iteration, bool last_iteration, SceneContext& ctx) {
    const PassSpec& pass = spec_.passes[index];
    const ShaderProgram& prog = programOf(pass);
    const std::string& file = pass.program.fragment;
    TargetGl& target = *targets_.at(pass.target);
    const PassCamera& pc = ctx.cameras[index];
    if (iteration == 0) report("pass " + ctx.spec->name + " " + pass.name);
    const int write = target.buffers == 2 ? 1 - target.front : 0;
    const bool clears_all = std::all_of(pass.state.clear_colors.begin(), pass.state.clear_colors.end(),
                                        [](const auto& c) { return c.has_value(); });
    if (target.buffers == 2 && !clears_all) copyFrontToBack(target);

    glUseProgram(prog.id());
    prog.restoreDefaults();
    if (!bindInputs(index, prog, ctx.spec->name)) return false;
    if (!setLabUniforms(pass, prog, ctx)) return false;
    glUseProgram(prog.id());

    const PassRun run{pass, prog, file, target, pc, ctx};
    setFrameUniforms(run, iteration);
    setLightUniforms(run);
    drawFaces(run, write);
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
    readBack(run);
    return true;
}

// The pass's draws into each face of its target (one for a 2D target), with the pass's state.
void LabRunner::drawFaces(const PassRun& run, int write) {
    const PassSpec& pass = run.pass;
    const ShaderProgram& prog = run.prog;
    const std::string& file = run.file;
    const TargetGl& target = run.target;
    const TargetSpec& tspec = *target.spec;
    const SceneContext& ctx = run.ctx;
    const bool program_point_size =
        pass.draw == DrawKind::Procedural && mentionsIdentifier(prog.preparedText(0), "gl_PointSize");
    const MaterialWarning scene_warning = [&](const std::string& message) {
        warnOnce("../" + ctx.spec->file, message);
    };
    // An attachment no output of the program writes is left as it was (its draw buffer is
    // GL_NONE while the pass draws): GL leaves it undefined otherwise, and drivers differ (Mesa
    // 22's llvmpipe writes garbage, Mesa 25's keeps the old values), which would make a grade
    // depend on the machine. The framework's warning says which attachment it is.
    std::vector<GLenum> all_buffers, drawn_buffers;
    for (std::size_t i = 0; i < tspec.attachments.size(); ++i) {
        const GLenum a = GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i);
        const bool written = !prog.outputsKnown() || std::any_of(prog.outputs().begin(), prog.outputs().end(),
                                                                 [&](const FragmentOutput& o) {
                                                                     return o.location == static_cast<int>(i);
                                                                 });
        all_buffers.push_back(a);
        drawn_buffers.push_back(written ? a : GL_NONE);
    }
    const bool masked = drawn_buffers != all_buffers;
    // A program's first draw of the lab goes in strips, so that an endless loop costs one strip
    // (loop_probe.h); a program with no loop needs none.
    const bool probe =
        prog.loopGuarded() && hasLoop(prog) && probed_programs_.insert(programKey(pass)).second;
    for (int face = 0; face < target.faces(); ++face) {
        glBindFramebuffer(GL_FRAMEBUFFER, target.fbos.at({write, face}));
        glViewport(0, 0, tspec.width, tspec.height);
        applyState(pass.state, tspec.format == TargetFormat::SRGB8, program_point_size);
        clearTarget(pass.state, target.depth != DepthMode::None);
        if (masked) glDrawBuffers(static_cast<GLsizei>(drawn_buffers.size()), drawn_buffers.data());
        setFramework(prog, file, "u_cube_face", GL_INT, [&](GLint l) { glUniform1i(l, face); });
        const auto draw = [&]() { drawItems(run, scene_warning); };
        const bool clean =
            probe ? drawProbingLoops(loop_guard_, tspec.width, tspec.height, draw) : (draw(), true);
        if (masked) glDrawBuffers(static_cast<GLsizei>(all_buffers.size()), all_buffers.data());
        if (!clean) return;  // the guard check after the pass says where
    }
}

// Every draw of one face of the pass: the fullscreen triangle, the procedural draw, or the
// scene's meshes.
void LabRunner::drawItems(const PassRun& run, const MaterialWarning& scene_warning) {
    static const Material kDefaultMaterial;
    const PassSpec& pass = run.pass;
    const SceneContext& ctx = run.ctx;
    if (pass.draw == DrawKind::Fullscreen) {
        drawMesh(run, scene_warning, fullscreen_.get(), glm::mat4(1.0f), kDefaultMaterial);
        return;
    }
    if (pass.draw == DrawKind::Procedural) {
        drawMesh(run, scene_warning, nullptr, glm::mat4(1.0f), kDefaultMaterial);
        return;
    }
    for (const DrawItem& item : ctx.scene->scene.draw_items) {
        const Material& material = item.material >= 0
                                       ? ctx.scene->scene.materials[static_cast<std::size_t>(item.material)]
                                       : kDefaultMaterial;
        // A mirroring transform turns the winding over; a double-sided material is not back-face
        // culled (glTF 2.0, 3.9.6). Front-face culling, a lab's own technique (inverted-hull
        // outlines), stays.
        const bool unculled = material.double_sided && pass.state.cull == CullMode::Back;
        if (item.mirrored) glFrontFace(GL_CW);
        if (unculled) glDisable(GL_CULL_FACE);
        drawMesh(run, scene_warning, ctx.scene->meshes[static_cast<std::size_t>(item.mesh)].get(), item.world,
                 material);
        if (item.mirrored) glFrontFace(GL_CCW);
        if (unculled) glEnable(GL_CULL_FACE);
    }
}

// One draw: the model and material uniforms, the material's textures, then the mesh (none: a
// procedural draw of the pass's vertex count).
void LabRunner::drawMesh(const PassRun& run, const MaterialWarning& scene_warning, GpuMesh* mesh,
                         const glm::mat4& model, const Material& material) {
    const PassSpec& pass = run.pass;
    const ShaderProgram& prog = run.prog;
    const std::string& file = run.file;
    const glm::mat4& view = run.pc.values.view;
    const glm::mat4& projection = run.pc.values.projection;
    const SceneContext& ctx = run.ctx;
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
    setFramework(prog, file, "u_roughness", GL_FLOAT, [&](GLint l) { glUniform1f(l, material.roughness); });
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
}

}  // namespace shaderlab::render_detail
