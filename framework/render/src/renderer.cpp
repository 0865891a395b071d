// Executes a lab's passes on the current context; see renderer.h.
//
// This file holds renderLab() and the lab runner's outline (lab_runner.h): reading the program
// files, building the programs, finding the passes a graded image needs, and each scene's pass
// sequence with its repeat loops. Targets, state, inputs, uniforms, draws and meshes are defined
// in the files lab_runner.h names.
#include "shaderlab/render/renderer.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <set>

#include "lab_runner.h"
#include "shaderlab/base/paths.h"
#include "shaderlab/base/student_files.h"
#include "shaderlab/base/timings.h"
#include "shaderlab/render/debug_view.h"

namespace shaderlab {

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

namespace render_detail {

namespace {

constexpr std::size_t kMaxShaderBytes = 256 * 1024;

}  // namespace

LabRunner::~LabRunner() {
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
    dropStandIns();
    for (auto& [key, sampler] : samplers_) glDeleteSamplers(1, &sampler);
    if (empty_vao_) glDeleteVertexArrays(1, &empty_vao_);
    if (loop_guard_) glDeleteBuffers(1, &loop_guard_);
    glUseProgram(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

bool LabRunner::prepare() {
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

// Student files come from the submission, every other program file from the lab folder (or the
// course's shared folder): a submission can neither omit nor replace the instructor's shaders.
FileText LabRunner::readProgramFile(const std::string& file, std::string* case_note) const {
    if (isStudentFile(file)) {
        const auto given = options_.source_overrides.find(file);
        if (given != options_.source_overrides.end()) {
            FileText t;
            t.ok = true;
            t.path = file;
            t.text = given->second;
            return t;
        }
        const std::string& root = options_.containment_root.empty() ? shader_dir_ : options_.containment_root;
        const std::string prefix = options_.containment_root.empty()
                                       ? std::string()
                                       : std::filesystem::path(shader_dir_)
                                                 .lexically_relative(options_.containment_root)
                                                 .generic_string() +
                                             "/";
        return readStudentFile(root, prefix + file, file, kMaxShaderBytes, case_note);
    }
    const bool shared = file.rfind("shared/", 0) == 0;
    return readFileInside(shared ? spec_.labs_root : spec_.lab_dir, file, kMaxShaderBytes);
}

bool LabRunner::readSources() {
    for (const PassSpec& pass : spec_.passes) {
        for (const std::string* file : {&pass.program.vertex, &pass.program.fragment}) {
            if (sources_.count(*file)) continue;
            std::string case_note;  // a file found by its case is graded, with a note (student_files.h)
            FileText t = readProgramFile(*file, &case_note);
            if (!case_note.empty()) warnOnce(*file, case_note);
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
        std::string case_note;
        FileText t = readProgramFile(name, &case_note);
        if (!case_note.empty()) warnOnce(name, case_note);
        return t;
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
// lost without a word from OpenGL, and an attachment no output writes would be undefined (drawFaces leaves it
// as it was).
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
                               target.name + "', so it keeps what it held (name it o_" +
                               target.attachments[i] + ")");
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
    blankTargets();
    dropStandIns();
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

}  // namespace render_detail

LabRender renderLab(const LabSpec& spec, const std::string& shader_dir, const RenderOptions& options) {
    if (options.debug_view != DebugView::Off) return renderDebugView(spec, options.debug_view, options);
    LabRender result;
    render_detail::LabRunner runner(spec, shader_dir, options, &result);
    if (!runner.prepare()) return result;
    const auto asked = [&](const SceneSpec& s) {
        return options.only_scenes.empty() ||
               std::find(options.only_scenes.begin(), options.only_scenes.end(), s.name) !=
                   options.only_scenes.end();
    };
    const std::size_t wanted =
        static_cast<std::size_t>(std::count_if(spec.scenes.begin(), spec.scenes.end(), asked));
    std::size_t drawn = 0;
    for (const SceneSpec& scene_spec : spec.scenes) {
        if (!asked(scene_spec)) continue;
        if (!runner.renderScene(scene_spec)) break;
        ++drawn;
    }
    // An endless loop would cost every other scene as much again (loop_probe.h): they are left.
    if (result.endless_loop && wanted > drawn + 1)
        result.message += "; the lab's " + std::to_string(wanted - drawn - 1) +
                          " other scenes were not drawn with this shader";
    return result;
}

}  // namespace shaderlab
