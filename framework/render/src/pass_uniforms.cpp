// The uniforms of a pass (lab_runner.h): lab.json's values (the pass's, then the scene's, which
// win) and the framework's, set by name when the program declares them: camera matrices, time,
// iteration, resolution and lights once per run. The per-draw ones (model matrices, material) are
// set where the draw is (pass_draw.cpp); how a lab.json value becomes a uniform is
// uniform_values.h's.
#include <algorithm>
#include <glm/gtc/type_ptr.hpp>

#include "gl_types.h"
#include "lab_runner.h"
#include "shaderlab/base/json_messages.h"

namespace shaderlab::render_detail {

namespace {

constexpr int kMaxLights = 4;

}  // namespace

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

// Camera, time, iteration and resolution: one value per pass run.
void LabRunner::setFrameUniforms(const PassRun& run, int iteration) {
    const ShaderProgram& prog = run.prog;
    const std::string& file = run.file;
    const TargetSpec& tspec = *run.target.spec;
    const PassCamera& pc = run.pc;
    const SceneContext& ctx = run.ctx;
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
}

// The scene's first kMaxLights lights.
void LabRunner::setLightUniforms(const PassRun& run) {
    const ShaderProgram& prog = run.prog;
    const std::string& file = run.file;
    const SceneContext& ctx = run.ctx;
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
}

}  // namespace shaderlab::render_detail
