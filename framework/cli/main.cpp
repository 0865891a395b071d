// shaderlab: render, grade and check GLSL lab submissions. Argument parsing only; the work is
// in the command functions (commands.h) and the libraries.
#include "commands.h"

#include <CLI/CLI.hpp>

int main(int argc, char** argv) {
    using namespace shaderlab::cli;
    CLI::App app{"shaderlab: render and grade GLSL shading labs"};
    app.require_subcommand(1);

    auto add_common = [](CLI::App* cmd, CommonOptions* common) {
        cmd->add_option("--backend", common->backend, "OpenGL context backend")
            ->check(CLI::IsMember({"osmesa", "egl"}))
            ->capture_default_str();
        cmd->add_option("--labs", common->labs_root, "folder holding the labs (default: the bundled labs/)");
        cmd->add_option("--lab", common->labs, "lab id, e.g. 01-phong (repeatable; default: all labs)");
    };

    RenderArgs render;
    CLI::App* render_cmd = app.add_subcommand("render", "render a submission's labs to PNG, one per graded scene");
    render_cmd->add_option("submission", render.submission, "folder mirroring labs/ (e.g. reference_solutions)")
        ->required();
    render_cmd->add_option("--out", render.out_dir, "output folder")->required();
    render_cmd->add_flag("--all-passes", render.all_passes, "also write the ungraded passes of multi-pass labs");
    add_common(render_cmd, &render.common);

    std::string info_backend = "osmesa";
    CLI::App* info_cmd = app.add_subcommand("info", "print the OpenGL context a backend gives");
    info_cmd->add_option("--backend", info_backend)->check(CLI::IsMember({"osmesa", "egl"}));

    CLI11_PARSE(app, argc, argv);

    if (render_cmd->parsed()) return runRender(render);
    if (info_cmd->parsed()) return runInfo(info_backend);
    return 2;
}
