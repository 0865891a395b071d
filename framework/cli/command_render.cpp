// `shaderlab render` and `shaderlab info`.
#include <filesystem>
#include <iostream>

#include "commands.h"
#include "grader/reports/report.h"
#include "shaderlab/base/paths.h"
#include "shaderlab/gl/gl_context.h"
#include "shaderlab/grading/grading.h"
#include "shaderlab/lab/lab_catalog.h"
#include "shaderlab/lab/lab_spec.h"
#include "shaderlab/render/debug_view.h"
#include "shaderlab/render/renderer.h"

namespace fs = std::filesystem;

namespace shaderlab::cli {

namespace {

void printDiagnostics(const LabRender& r, const std::string& lab_id) {
    for (const Diagnostic& d : r.diagnostics)
        std::cerr << grader::formatDiagnostic(toReportDiagnostic(d), lab_id + "/") << "\n";
}

// `render --debug VIEW`: <out>/<lab>/<scene>.debug-<view>.png for every scene, and what the view
// could not show (a mesh without tangents, say) on stdout.
int writeDebugViews(const LabSpec& spec, DebugView view, const fs::path& lab_out) {
    RenderOptions options;
    options.debug_view = view;
    const LabRender r = renderLab(spec, "", options);
    for (const Diagnostic& d : r.diagnostics) {
        if (d.severity == "note")
            std::cout << spec.id << ": debug view: " << d.message << "\n";
        else
            std::cerr << grader::formatDiagnostic(toReportDiagnostic(d), spec.id + "/") << "\n";
    }
    if (r.status != RenderStatus::Ok) {
        std::cerr << spec.id << ": " << renderStatusName(r.status) << ": " << r.message << "\n";
        return 1;
    }
    std::error_code ec;
    fs::create_directories(lab_out, ec);
    int exit_code = 0;
    for (const SceneRender& scene : r.scenes) {
        if (scene.passes.empty()) {
            std::cerr << spec.id << ": scene " << scene.scene << " was not rendered: " << scene.error << "\n";
            exit_code = 1;
            continue;
        }
        const fs::path file = lab_out / (scene.scene + ".debug-" + debugViewName(view) + ".png");
        std::string err;
        if (!grader::writePng(scene.passes.front().color, file.string(), &err)) {
            std::cerr << "shaderlab: " << err << "\n";
            return 2;
        }
        std::cout << file.string() << "  (" << scene.render_ms << " ms)\n";
    }
    return exit_code;
}

}  // namespace

Backend chooseBackend(const std::string& name) {
    Backend backend = Backend::OSMesa;
    std::string note;
    if (!parseBackend(name, &backend, &note)) return Backend::OSMesa;  // CLI11 let through only known names
    static bool said = false;
    if (!note.empty() && !said) {
        std::cerr << "shaderlab: " << note << "\n";
        said = true;
    }
    return backend;
}

int runInfo(const std::string& backend_name) {
    const Backend backend = chooseBackend(backend_name);
    ContextResult ctx = createHeadlessContext(backend);
    if (!ctx.context) {
        std::cerr << "shaderlab: " << ctx.error << "\n";
        return 2;
    }
    const GlInfo& info = ctx.context->info();
    std::cout << "backend:  " << ctx.context->backend() << "\n"
              << "vendor:   " << info.vendor << "\n"
              << "renderer: " << info.renderer << "\n"
              << "version:  " << info.version << "\n";
    return 0;
}

int runRender(const RenderArgs& args) {
    std::string labs_root;
    if (!resolveLabsRoot(args.common, &labs_root)) return 2;
    std::vector<std::string> ids = args.common.labs.empty() ? listLabIds(labs_root) : args.common.labs;
    if (ids.empty()) {
        std::cerr << "shaderlab: no labs found in " << labs_root << "\n";
        return 2;
    }
    DebugView debug = DebugView::Off;
    parseDebugView(args.debug.empty() ? "off" : args.debug, &debug);  // CLI11 let through only known names
    std::error_code ec;
    if (args.submission.empty() && debug == DebugView::Off) {
        std::cerr << "shaderlab: render needs a submission folder (or --debug VIEW, which reads none)\n";
        return 2;
    }
    if (debug == DebugView::Off && !fs::is_directory(args.submission, ec)) {
        std::cerr << "shaderlab: " << args.submission << ": submission folder not found\n";
        return 2;
    }
    const Backend backend = chooseBackend(args.common.backend);
    ContextResult ctx = createHeadlessContext(backend);
    if (!ctx.context) {
        std::cerr << "shaderlab: " << ctx.error << "\n";
        return 2;
    }

    int exit_code = 0;
    for (const std::string& id : ids) {
        const LabSpecResult parsed = parseLabSpec((fs::path(labs_root) / id).string());
        if (!parsed.ok) {
            for (const std::string& e : parsed.errors) std::cerr << e << "\n";
            exit_code = 2;
            continue;
        }
        if (debug != DebugView::Off) {
            exit_code = std::max(exit_code, writeDebugViews(parsed.spec, debug, fs::path(args.out_dir) / id));
            continue;
        }
        RenderOptions options;
        options.keep_all_passes = args.all_passes;
        options.containment_root = args.submission;
        const LabRender r = renderLab(parsed.spec, (fs::path(args.submission) / id).string(), options);
        printDiagnostics(r, id);
        if (r.status != RenderStatus::Ok) {
            std::cerr << id << ": " << renderStatusName(r.status) << ": " << r.message << "\n";
            exit_code = std::max(exit_code, 1);
            continue;
        }
        const fs::path lab_out = fs::path(args.out_dir) / id;
        fs::create_directories(lab_out, ec);
        for (const SceneRender& scene : r.scenes) {
            // A scene whose file was refused (an unsupported extension, a broken glTF) renders
            // nothing: the work ran and failed (docs: exit code 1), whatever the other scenes did.
            if (!scene.error.empty()) {
                std::cerr << id << ": scene " << scene.scene << " was not rendered: " << scene.error << "\n";
                exit_code = std::max(exit_code, 1);
                continue;
            }
            // The lab's result is the last graded image; every other one is named after its pass
            // (and attachment, when the target has several or it is the depth).
            std::size_t final_index = 0;
            for (std::size_t i = 0; i < scene.passes.size(); ++i)
                if (scene.passes[i].graded) final_index = i;
            for (std::size_t i = 0; i < scene.passes.size(); ++i) {
                const PassImage& p = scene.passes[i];
                const bool final_image = i == final_index;
                const TargetSpec* t = parsed.spec.findTarget(p.target);
                const bool named = p.attachment == "depth" || (t && t->attachments.size() > 1);
                const std::string id_name = p.pass + (named ? "." + p.attachment : "");
                const fs::path file =
                    lab_out / (final_image ? scene.scene + ".png" : scene.scene + "." + id_name + ".png");
                std::string err;
                if (!grader::writePng(p.color, file.string(), &err)) {
                    std::cerr << "shaderlab: " << err << "\n";
                    exit_code = 2;
                    continue;
                }
                if (final_image) std::cout << file.string() << "  (" << scene.render_ms << " ms)\n";
            }
        }
    }
    return exit_code;
}

}  // namespace shaderlab::cli
