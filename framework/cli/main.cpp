// shaderlab: render, grade and check GLSL lab submissions. Argument parsing only; the work is
// in the command functions (commands.h) and the libraries. One function per command adds its
// options; main() parses and runs the one that was given.
#include <CLI/CLI.hpp>
#if defined(__GLIBC__)
#include <malloc.h>
#endif
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "commands.h"
#include "shaderlab/base/json_messages.h"
#include "shaderlab/render/debug_view.h"

namespace {

using namespace shaderlab::cli;

// The limits of each lab's render process, for grade and check (docs/grading.md, "Limits").
void addLimits(CLI::App* cmd, LimitArgs* limits, const char* draw_help) {
    cmd->add_option("--timeout", limits->timeout_s, draw_help)
        ->check(CLI::Range(0.1, 86400.0))
        ->capture_default_str();
    cmd->add_option("--compile-timeout", limits->compile_timeout_s,
                    "seconds a lab may take to start, compile and link its shaders")
        ->check(CLI::Range(0.1, 86400.0))
        ->capture_default_str();
    cmd->add_option("--memory", limits->memory_mib, "MiB of memory a lab's render process may use")
        ->check(CLI::Range(std::size_t(64), std::size_t(1) << 20))
        ->capture_default_str();
}

// The debug views' names, "off" first (shaderlab/render/debug_view.h).
std::vector<std::string> debugViewList() {
    std::vector<std::string> names{"off"};
    for (const shaderlab::DebugViewInfo& v : shaderlab::debugViews()) names.push_back(v.name);
    return names;
}

// Where the labs come from when --labs is not given (defaultLabsRoot, shaderlab/base/paths.h).
const char* const kLabsHelp =
    "folder holding the labs (default: $SHADERLAB_LABS, else the labs/ folder of the course found from the "
    "working folder upward)";

void addCommon(CLI::App* cmd, CommonOptions* common) {
    cmd->add_option("--backend", common->backend,
                    "OpenGL context backend: auto (OSMesa where it is installed, else EGL), osmesa or egl")
        ->check(CLI::IsMember({"auto", "osmesa", "egl"}))
        ->capture_default_str();
    cmd->add_option("--labs", common->labs_root, kLabsHelp);
    cmd->add_option("--lab", common->labs, "lab id, e.g. 01-phong (repeatable; default: all labs)");
}

CLI::App* addRender(CLI::App& app, RenderArgs* args) {
    CLI::App* cmd = app.add_subcommand("render", "render a submission's labs to PNG, one per graded scene");
    cmd->add_option("submission", args->submission,
                    "folder mirroring labs/ (e.g. reference_solutions); not needed with --debug");
    cmd->add_option("--out", args->out_dir, "output folder")->required();
    cmd->add_flag("--all-passes", args->all_passes, "also write the ungraded passes of multi-pass labs");
    cmd->add_option("--debug", args->debug,
                    "instead, draw each scene's vertex data as colours: <scene>.debug-VIEW.png")
        ->check(CLI::IsMember(debugViewList()));
    addCommon(cmd, &args->common);
    return cmd;
}

void addReferenceCache(CLI::App* cmd, std::string* dir, bool* off) {
    cmd->add_option("--cache", *dir,
                    "folder of what is kept between runs: reference renders and compiled shaders "
                    "(default: out/.shaderlab beside labs/)");
    cmd->add_flag("--no-cache", *off, "render the reference and compile every shader every time");
}

CLI::App* addGrade(CLI::App& app, GradeArgs* args) {
    CLI::App* cmd = app.add_subcommand("grade", "grade a submission: report.json, report.html and images");
    cmd->add_option("submission", args->submission, "folder mirroring labs/")->required();
    cmd->add_option("--out", args->out_dir, "output folder")->required();
    cmd->add_option("--format", args->formats, "extra report formats: gradescope (results.json), junit")
        ->check(CLI::IsMember({"json", "gradescope", "junit"}));
    cmd->add_option("--reference", args->reference_root,
                    "reference solutions folder (default: reference_solutions beside labs/)");
    cmd->add_flag("--no-reference", args->no_reference, "grade against the stored golden images");
    addReferenceCache(cmd, &args->cache_dir, &args->no_cache);
    addLimits(cmd, &args->limits, "seconds one lab may take to draw its scenes");
    addCommon(cmd, &args->common);
    return cmd;
}

CLI::App* addStart(CLI::App& app, StartArgs* args) {
    CLI::App* cmd =
        app.add_subcommand("start", "copy a lab's starter files into work/<lab>/, your own copy to edit");
    cmd->add_option("lab", args->lab, "lab id, e.g. 01-phong")->required();
    cmd->add_option("--into", args->into, "folder to copy into (default: work/ beside labs/)");
    cmd->add_flag("--force", args->force, "overwrite files already there with the starter code");
    cmd->add_option("--labs", args->common.labs_root, kLabsHelp);
    return cmd;
}

CLI::App* addCheck(CLI::App& app, CheckArgs* args) {
    CLI::App* cmd =
        app.add_subcommand("check", "check one lab of your work (work/<lab>/) and print a verdict");
    cmd->add_option("lab", args->lab, "lab id, e.g. 01-phong")->required();
    cmd->add_option("--submission", args->submission,
                    "folder mirroring labs/ (default: work/ beside labs/, made by `shaderlab start`)");
    cmd->add_option("--out", args->out_dir, "where images and the report go (default: out/check)");
    cmd->add_flag("--no-reference", args->no_reference, "use the stored golden images");
    addReferenceCache(cmd, &args->cache_dir, &args->no_cache);
    addLimits(cmd, &args->limits, "seconds the lab may take to draw its scenes");
    cmd->add_option("--backend", args->common.backend)->check(CLI::IsMember({"auto", "osmesa", "egl"}));
    cmd->add_option("--labs", args->common.labs_root, kLabsHelp);
    return cmd;
}

CLI::App* addView(CLI::App& app, ViewArgs* args) {
    CLI::App* cmd = app.add_subcommand(
        "view", "open a window on one lab of your work that follows every save, beside the reference");
    cmd->add_option("lab", args->lab, "lab id, e.g. 01-phong")->required();
    cmd->add_option("--submission", args->submission,
                    "folder mirroring labs/ (default: work/ beside labs/; reference_solutions works too)");
    cmd->add_option("--reference", args->reference_root,
                    "reference solutions folder (default: reference_solutions beside labs/)");
    cmd->add_flag("--no-reference", args->no_reference, "compare with the stored golden images");
    cmd->add_option("--scene", args->scene, "scene shown first");
    cmd->add_option("--image", args->image, "image shown first: PASS.ATTACHMENT, e.g. bright.color");
    cmd->add_option("--orbit", args->orbit,
                    "start turned from the graded view: YAW PITCH (degrees) ZOOM (R in the window resets)")
        ->expected(3);
    cmd->add_option("--mode", args->mode, "first view")
        ->check(CLI::IsMember({"student", "reference", "diff", "split"}))
        ->capture_default_str();
    cmd->add_option("--timeout", args->timeout_s, "seconds one scene may take to render")
        ->check(CLI::Range(0.1, 600.0))
        ->capture_default_str();
    cmd->add_option("--frames", args->frames, "exit after N frames once the first picture is shown")
        ->check(CLI::Range(1, 1000000));
    cmd->add_option("--exit-after-reloads", args->exit_after_reloads,
                    "exit once N pictures (or errors) made after a file change are shown")
        ->check(CLI::Range(1, 1000000));
    cmd->add_option("--screenshot", args->screenshot,
                    "at exit, save the picture as shown, one pixel per image pixel (PNG)");
    cmd->add_option("--screenshot-window", args->screenshot_window, "at exit, save the whole window (PNG)");
    cmd->add_option(
        "--panel-text", args->panel_text,
        "at exit, save the panel's grade, goals, hints and verdict as the window lists them (text)");
    cmd->add_option("--debug", args->debug,
                    "first picture: the lab's (off) or a view of the vertex data (V cycles)")
        ->check(CLI::IsMember(debugViewList()))
        ->capture_default_str();
    cmd->add_option("--backend", args->common.backend)->check(CLI::IsMember({"auto", "osmesa", "egl"}));
    cmd->add_option("--labs", args->common.labs_root, kLabsHelp);
    return cmd;
}

CLI::App* addServe(CLI::App& app, ServeArgs* args) {
    CLI::App* cmd = app.add_subcommand(
        "serve",
        "a page in your browser on one lab of your work: pictures, verdict and goals, on every save");
    cmd->add_option("lab", args->lab, "lab id, e.g. 01-phong")->required();
    cmd->add_option("--submission", args->submission,
                    "folder mirroring labs/ (default: work/ beside labs/; reference_solutions works too)");
    cmd->add_option("--port", args->port, "port to listen on (0: any free port)")
        ->check(CLI::Range(0, 65535))
        ->capture_default_str();
    cmd->add_option("--host", args->host,
                    "address to listen on (default 127.0.0.1, this machine only; anything else is reachable "
                    "from other machines, and serve says so)")
        ->capture_default_str();
    cmd->add_option("--reference", args->reference_root,
                    "reference solutions folder (default: reference_solutions beside labs/)");
    cmd->add_flag("--no-reference", args->no_reference, "compare with the stored golden images");
    cmd->add_option("--view-timeout", args->timeout_s, "seconds one scene may take to render for the picture")
        ->check(CLI::Range(0.1, 600.0))
        ->capture_default_str();
    addLimits(cmd, &args->limits, "seconds the lab may take to draw its scenes when graded (as `check`)");
    cmd->add_option("--backend", args->common.backend)->check(CLI::IsMember({"auto", "osmesa", "egl"}));
    cmd->add_option("--labs", args->common.labs_root, kLabsHelp);
    return cmd;
}

CLI::App* addWatch(CLI::App& app, WatchArgs* args) {
    CLI::App* cmd = app.add_subcommand(
        "watch", "check one lab of your work again on every save, without a window (like `check`)");
    cmd->add_option("lab", args->check.lab, "lab id, e.g. 01-phong")->required();
    cmd->add_option("--submission", args->check.submission,
                    "folder mirroring labs/ (default: work/ beside labs/)");
    cmd->add_option("--out", args->check.out_dir, "where images and the report go (default: out/check)");
    cmd->add_flag("--no-reference", args->check.no_reference, "use the stored golden images");
    addLimits(cmd, &args->check.limits, "seconds the lab may take to draw its scenes");
    cmd->add_option("--max-checks", args->max_checks, "stop after N checks (default: until Ctrl-C)")
        ->check(CLI::Range(1, 1000000));
    cmd->add_option("--backend", args->check.common.backend)->check(CLI::IsMember({"auto", "osmesa", "egl"}));
    cmd->add_option("--labs", args->check.common.labs_root, kLabsHelp);
    return cmd;
}

CLI::App* addCompare(CLI::App& app, CompareArgs* args) {
    CLI::App* cmd = app.add_subcommand("compare", "print PSNR, SSIM, FLIP and mismatch of two PNG images");
    cmd->add_option("reference", args->a, "reference image")->required();
    cmd->add_option("test", args->b, "test image")->required();
    cmd->add_flag("--json", args->json, "print JSON");
    cmd->add_option("--tolerance", args->tolerance, "per-channel tolerance of the mismatch count")
        ->check(CLI::Range(0.0f, 1.0f))
        ->capture_default_str();
    return cmd;
}

CLI::App* addGoldens(CLI::App& app, GoldensArgs* args) {
    CLI::App* cmd = app.add_subcommand("goldens",
                                       "render the reference solutions into labs/*/golden/ and the corpus "
                                       "mistakes into labs/*/hints/");
    cmd->add_option("--reference", args->reference_root, "reference solutions folder");
    cmd->add_option("--into", args->golden_root,
                    "write to DIR/<lab>/golden/ instead of the labs (to compare)");
    cmd->add_option("--corpus", args->corpus_root,
                    "folder of <lab>/cases.json whose mistakes become hints (default: tests/corpus)");
    cmd->add_flag("--no-hints", args->no_hints,
                  "only the goldens: do not render the corpus mistakes into labs/*/hints/");
    addCommon(cmd, &args->common);
    return cmd;
}

CLI::App* addCorpus(CLI::App& app, CorpusArgs* args) {
    CLI::App* cmd = app.add_subcommand(
        "corpus", "grade each lab's known mistakes and alternative solutions and check the verdicts");
    cmd->add_option("--corpus", args->corpus_root, "folder of <lab>/cases.json (default: tests/corpus)");
    cmd->add_option("--reference", args->reference_root, "reference solutions folder");
    cmd->add_option("--out", args->out_dir, "output folder (required, except for add-case)");
    cmd->add_flag("--render-reference", args->use_reference,
                  "render the reference for every case instead of reading the goldens");
    cmd->add_flag("--margins", args->margins,
                  "print each image's metrics against its thresholds and how far each verdict is from "
                  "turning; write <out>/<lab>/margins.json");
    cmd->add_option("--timeout", args->timeout_s, "seconds one case may take to render")
        ->check(CLI::Range(0.1, 600.0))
        ->capture_default_str();
    addCommon(cmd, &args->common);
    // `--out` is required of `corpus` itself; CLI11 would ask it of `corpus add-case` too.
    cmd->require_subcommand(0, 1);
    cmd->final_callback([cmd, args] {
        if (cmd->get_subcommands().empty() && args->out_dir.empty()) throw CLI::RequiredError("--out");
    });
    return cmd;
}

// `corpus add-case`: a subcommand of `corpus`, since it writes what `corpus` reads.
CLI::App* addCorpusAddCase(CLI::App* corpus, CorpusAddCaseArgs* args) {
    CLI::App* cmd = corpus->add_subcommand(
        "add-case",
        "add a case to a lab's corpus from a folder: only the student files that differ from "
        "the reference are stored");
    cmd->add_option("lab", args->lab, "lab id, e.g. 01-phong")->required();
    cmd->add_option("name", args->name, "the case's name and folder, e.g. light-vector-reversed")->required();
    cmd->add_option("--kind", args->kind,
                    "mistake (fails goals), alternative (full marks) or broken (a status)")
        ->required()
        ->check(CLI::IsMember({"mistake", "alternative", "broken"}));
    cmd->add_option("--fails", args->fails, "a mistake's goal ids: the goals whose idea it breaks");
    cmd->add_option("--status", args->status, "the status a broken case ends with")
        ->check(CLI::IsMember({"failed", "compile_error", "link_error", "missing", "timeout", "crashed"}));
    cmd->add_option("--about", args->about, "what the case does, as a student would have written it")
        ->required();
    cmd->add_option("--from", args->from,
                    "folder holding the lab's files (or a submission with <lab>/ in it)")
        ->required();
    cmd->add_option("--corpus", args->corpus_root, "folder of <lab>/cases.json (default: tests/corpus)");
    cmd->add_option("--reference", args->reference_root, "reference solutions folder");
    cmd->add_option("--labs", args->common.labs_root, kLabsHelp);
    return cmd;
}

// `new-lab` and `lab-check`: an instructor's own lab, from its scaffold to what CI asks of it.
CLI::App* addNewLab(CLI::App& app, NewLabArgs* args) {
    CLI::App* cmd = app.add_subcommand("new-lab",
                                       "start a lab of your own: labs/ID/, reference_solutions/ID/, "
                                       "tests/corpus/ID/ and its course index row");
    cmd->add_option("id", args->id, "the new lab's id, e.g. 12-normal-mapping")->required();
    cmd->add_option("--like", args->like,
                    "copy this lab's lab.json, files and README headings (e.g. 05-post-processing)");
    cmd->add_option("--title", args->title, "the lab's title (default: from the id)");
    cmd->add_option("--reference", args->reference_root,
                    "reference solutions folder (default: reference_solutions beside labs/)");
    cmd->add_option("--corpus", args->corpus_root, "folder of <lab>/cases.json (default: tests/corpus)");
    cmd->add_option("--labs", args->common.labs_root, kLabsHelp);
    return cmd;
}

CLI::App* addLabCheck(CLI::App& app, LabCheckArgs* args) {
    CLI::App* cmd = app.add_subcommand(
        "lab-check",
        "check one lab as CI does: lab.json, files, course index, README tables, goldens, corpus");
    cmd->add_option("lab", args->lab, "lab id, e.g. 12-normal-mapping")->required();
    cmd->add_flag("--fix", args->fix, "rewrite the README's generated goals and scenes tables from lab.json");
    cmd->add_option("--reference", args->reference_root,
                    "reference solutions folder (default: reference_solutions beside labs/)");
    cmd->add_option("--corpus", args->corpus_root, "folder of <lab>/cases.json (default: tests/corpus)");
    cmd->add_option("--out", args->out_dir,
                    "where the fresh goldens and corpus reports go (default: out/lab-check/LAB)");
    cmd->add_option("--timeout", args->timeout_s, "seconds one corpus case may take to render")
        ->check(CLI::Range(0.1, 600.0))
        ->capture_default_str();
    cmd->add_option("--backend", args->common.backend)->check(CLI::IsMember({"auto", "osmesa", "egl"}));
    cmd->add_option("--labs", args->common.labs_root, kLabsHelp);
    return cmd;
}

CLI::App* addMutants(CLI::App& app, MutantsArgs* args) {
    CLI::App* cmd = app.add_subcommand(
        "mutants",
        "grade mutants of the reference solution (a constant, an operator, a swizzle, a term, a call, a "
        "statement moved) and list those that pass every goal without being declared equivalent");
    cmd->add_option("lab", args->common.labs, "lab ids (default: every lab)");
    cmd->add_option("--reference", args->reference_root,
                    "reference solutions folder (default: reference_solutions beside labs/)");
    cmd->add_option(
        "--corpus", args->corpus_root,
        "folder of <lab>/cases.json, whose equivalent_mutants are declared (default: tests/corpus)");
    cmd->add_option("--out", args->out_dir, "where mutants.json goes (default: out/mutants beside labs/)");
    cmd->add_option("--max", args->max_per_lab, "at most this many mutants per lab, spread evenly (0: all)")
        ->check(CLI::Range(0, 100000))
        ->capture_default_str();
    cmd->add_option("--timeout", args->timeout_s, "seconds one mutant may take to render")
        ->check(CLI::Range(0.1, 600.0))
        ->capture_default_str();
    cmd->add_option("--backend", args->common.backend)->check(CLI::IsMember({"auto", "osmesa", "egl"}));
    cmd->add_option("--labs", args->common.labs_root, "folder holding the labs");
    return cmd;
}

CLI::App* addSceneSweep(CLI::App& app, SceneSweepArgs* args) {
    CLI::App* cmd = app.add_subcommand(
        "scene-sweep",
        "rank variants of a lab's scene by how well they separate each goal's corpus mistakes from the "
        "alternatives");
    cmd->add_option("lab", args->lab, "lab id, e.g. 08-gooch")->required();
    cmd->add_option("--scene", args->scene,
                    "the scene to vary, one of the lab's (or the sweep file's \"scene\")");
    cmd->add_option("--vary", args->vary,
                    "PATH=VALUES, repeatable: e.g. lights[0].direction=[1,-1,0]..[-1,-1,0]:5, "
                    "uniforms.u_shininess=2,8,32, file=scenes/sphere.gltf,scenes/torus.gltf")
        ->allow_extra_args(false);
    cmd->add_option("--sweep", args->sweep_file,
                    "a JSON file of {scene, goals, vary: {PATH: VALUES}, candidates: [scene objects]}");
    cmd->add_option("--goal", args->goals,
                    "judge the candidates under this goal (repeatable; \"all\": every goal; default: the "
                    "goals of the scene)")
        ->allow_extra_args(false);
    cmd->add_option("--mistake", args->mistakes,
                    "the scene is for this mistake of the corpus: the goals' other mistakes need not fail "
                    "on it (repeatable; default: every mistake of the goals)")
        ->allow_extra_args(false);
    cmd->add_option("--max-candidates", args->max_candidates, "refuse a sweep of more candidates than this")
        ->check(CLI::Range(std::size_t(1), std::size_t(512)))
        ->capture_default_str();
    cmd->add_option("--top", args->top, "print the best N candidates as lab.json scenes")
        ->check(CLI::Range(std::size_t(0), std::size_t(512)))
        ->capture_default_str();
    cmd->add_option("--timeout", args->timeout_s, "seconds one candidate may take to draw, per corpus case")
        ->check(CLI::Range(0.1, 600.0))
        ->capture_default_str();
    cmd->add_option("--out", args->out_dir,
                    "where sweep.json and the candidates' reference pictures go (default: "
                    "out/scene-sweep/LAB)");
    cmd->add_flag("--keep", args->keep, "keep the swept lab, its goldens and the case folders in <out>/work");
    cmd->add_option("--corpus", args->corpus_root, "folder of <lab>/cases.json (default: tests/corpus)");
    cmd->add_option("--reference", args->reference_root,
                    "reference solutions folder (default: reference_solutions beside labs/)");
    cmd->add_option("--backend", args->common.backend)->check(CLI::IsMember({"auto", "osmesa", "egl"}));
    cmd->add_option("--labs", args->common.labs_root, kLabsHelp);
    return cmd;
}

CLI::App* addBatch(CLI::App& app, BatchArgs* args) {
    CLI::App* cmd = app.add_subcommand(
        "batch",
        "grade every submission (a folder or a .zip) of a folder: one report each, summary.csv/json");
    cmd->add_option("submissions", args->submissions_dir, "folder of submissions (folders or .zip files)")
        ->required();
    cmd->add_option("--out", args->out_dir, "results folder")->required();
    cmd->add_option("--jobs,-j", args->jobs, "labs graded at once (default: the number of cores)")
        ->check(CLI::Range(1, 256));
    cmd->add_option("--timeout", args->timeout_s, "seconds one lab may take to draw its scenes")
        ->check(CLI::Range(0.1, 86400.0))
        ->capture_default_str();
    cmd->add_option("--compile-timeout", args->compile_timeout_s,
                    "seconds one lab may take to create its context, read, compile and link its shaders")
        ->check(CLI::Range(0.1, 86400.0))
        ->capture_default_str();
    cmd->add_option("--memory", args->memory,
                    "resident memory of each render process (e.g. 2G); workers get 4G more address space")
        ->capture_default_str();
    cmd->add_option("--shard", args->shard,
                    "K/N: grade only every N-th submission, from the K-th (job arrays)");
    cmd->add_option("--reference", args->reference_root,
                    "reference solutions folder (default: reference_solutions beside labs/)");
    cmd->add_flag("--no-reference", args->no_reference, "grade against the stored golden images");
    cmd->add_option("--cache", args->cache_dir,
                    "cache of reference renders and graded labs, shared by runs and shards "
                    "(default: in <out>/.shaderlab)");
    cmd->add_option("--format", args->formats, "extra report formats: gradescope (results.json), junit")
        ->check(CLI::IsMember({"json", "gradescope", "junit"}));
    cmd->add_option("--max-unpacked", args->max_unpacked_mib, "MiB a submitted zip may unpack to")
        ->check(CLI::Range(1, 1 << 20))
        ->capture_default_str();
    addCommon(cmd, &args->common);
    cmd->get_option("--lab")->description(
        "lab id, e.g. 01-phong (repeatable): grade these labs in every submission and total over them "
        "(default: each submission's labs that it hands in, totalled over those the class hands in)");
    return cmd;
}

// Started by `batch` for each unit of work; not for people, so hidden from --help.
CLI::App* addBatchWorker(CLI::App& app, BatchWorkerArgs* args) {
    CLI::App* cmd = app.add_subcommand("batch-worker", "grade one lab for `batch`")->group("");
    cmd->add_option("--mode", args->mode)->required()->check(CLI::IsMember({"grade", "reference"}));
    cmd->add_option("--labs", args->labs_root)->required();
    cmd->add_option("--lab", args->lab)->required();
    cmd->add_option("--out", args->out_dir)->required();
    cmd->add_option("--backend", args->backend);
    cmd->add_option("--submission", args->submission);
    cmd->add_option("--goldens", args->goldens_root);
    cmd->add_option("--reference", args->reference_root);
    cmd->add_option("--timeout", args->timeout_s);
    cmd->add_option("--compile-timeout", args->compile_timeout_s);
    cmd->add_option("--memory", args->memory);
    cmd->add_option("--also", args->also,
                    "more labs of the submission: lab, out folder, goldens (three each)");
    return cmd;
}

CLI::App* addMerge(CLI::App& app, MergeArgs* args) {
    CLI::App* cmd = app.add_subcommand(
        "merge", "merge the results folders of batch shards: summary.csv/json and reports");
    cmd->add_option("results", args->inputs, "results folders of `shaderlab batch --shard`")->required();
    cmd->add_option("--out", args->out_dir, "merged results folder")->required();
    return cmd;
}

CLI::App* addClass(CLI::App& app, ClassArgs* args) {
    CLI::App* cmd = app.add_subcommand(
        "class", "what the class did not learn: a page of goals met, known mistakes, points and statuses");
    cmd->add_option("results", args->results_dir, "results folder of `shaderlab batch` or `shaderlab merge`")
        ->required();
    cmd->add_option("--out", args->out_dir, "folder for index.html, class.json and the pictures")->required();
    cmd->add_option(
        "--labs", args->labs_root,
        "folder holding the labs, for the known mistakes' pictures (default: the course found from here)");
    return cmd;
}

CLI::App* addSimilarity(CLI::App& app, SimilarityArgs* args) {
    CLI::App* cmd = app.add_subcommand(
        "similarity",
        "who copied: pairs of similar solutions per lab, clusters, a side-by-side view (MOSS-like)");
    cmd->add_option("submissions", args->submissions_dir, "folder of submissions (folders or .zip files)")
        ->required();
    cmd->add_option("--out", args->out_dir, "folder for index.html, pairs.json and the side-by-side pages")
        ->required();
    cmd->add_option("--earlier", args->earlier,
                    "submissions folder of an earlier year, compared with this class only (repeatable)");
    cmd->add_option("--threshold", args->threshold,
                    "flag a pair at this score (0..1) plus --length-margin / sqrt(n) or above, n the smaller "
                    "document's fingerprints")
        ->check(CLI::Range(0.0, 1.0))
        ->capture_default_str();
    cmd->add_option("--length-margin", args->length_margin,
                    "how much more a short document must share: 0.5 asks 10 points more of 25 fingerprints")
        ->check(CLI::Range(0.0, 5.0))
        ->capture_default_str();
    cmd->add_option("--min-shared", args->min_shared, "and only when it shares this many fingerprints")
        ->check(CLI::Range(std::size_t(1), std::size_t(1000000)))
        ->capture_default_str();
    cmd->add_option("--max-views", args->max_views, "side-by-side pages per lab, highest scores first")
        ->check(CLI::Range(std::size_t(0), std::size_t(1000000)))
        ->capture_default_str();
    cmd->add_option("--kgram", args->kgram, "tokens per fingerprinted run (k): shorter matches never count")
        ->check(CLI::Range(std::size_t(4), std::size_t(100)))
        ->capture_default_str();
    cmd->add_option("--window", args->window,
                    "winnowing window (w): runs of k + w - 1 tokens are always found")
        ->check(CLI::Range(std::size_t(1), std::size_t(100)))
        ->capture_default_str();
    cmd->add_option("--jobs,-j", args->jobs, "labs compared at once (default: the number of cores)")
        ->check(CLI::Range(1, 256));
    cmd->add_option("--labs", args->common.labs_root, kLabsHelp);
    cmd->add_option("--lab", args->common.labs, "lab id (repeatable; default: all labs)");
    return cmd;
}

CLI::App* addGradescopeBundle(CLI::App& app, GradescopeBundleArgs* args) {
    CLI::App* cmd = app.add_subcommand(
        "gradescope-bundle",
        "write the autograder zip of a Gradescope assignment (setup.sh, run_autograder, a portable "
        "shaderlab, labs)");
    cmd->add_option("--out", args->out_zip, "the zip to write, e.g. autograder.zip")->required();
    cmd->add_option("--binary", args->binary,
                    "the shaderlab the autograder runs: a portable build (scripts/portable-build.sh); "
                    "default: this program, when it is one");
    cmd->add_option("--reference", args->reference_root,
                    "reference solutions folder (default: reference_solutions beside labs/)");
    cmd->add_option("--visibility", args->visibility, "when students see the results")
        ->check(CLI::IsMember({"visible", "hidden", "after_due_date", "after_published"}))
        ->capture_default_str();
    cmd->add_option("--tests", args->tests, "one Gradescope test per learning goal or per scene")
        ->check(CLI::IsMember({"goals", "scenes"}))
        ->capture_default_str();
    cmd->add_option("--timeout", args->timeout_s, "seconds one lab may take to render")
        ->check(CLI::Range(0.1, 3600.0))
        ->capture_default_str();
    cmd->add_option("--labs", args->common.labs_root, kLabsHelp);
    cmd->add_option("--lab", args->common.labs, "lab id (repeatable; default: all labs)");
    return cmd;
}

// Run by the bundle's run_autograder on Gradescope; hidden from --help.
CLI::App* addGradescopeRun(CLI::App& app, GradescopeRunArgs* args) {
    CLI::App* cmd =
        app.add_subcommand("gradescope-run", "grade <root>/submission into <root>/results/results.json")
            ->group("");
    cmd->add_option("--root", args->root)->capture_default_str();
    cmd->add_option("--reference", args->reference_root);
    cmd->add_option("--visibility", args->visibility)
        ->check(CLI::IsMember({"visible", "hidden", "after_due_date", "after_published"}));
    cmd->add_option("--tests", args->tests)->check(CLI::IsMember({"goals", "scenes"}));
    cmd->add_option("--timeout", args->timeout_s)->check(CLI::Range(0.1, 3600.0));
    addCommon(cmd, &args->common);
    return cmd;
}

CLI::App* addInfo(CLI::App& app, std::string* backend) {
    CLI::App* cmd = app.add_subcommand("info", "print the OpenGL context a backend gives");
    cmd->add_option("--backend", *backend)->check(CLI::IsMember({"auto", "osmesa", "egl"}));
    return cmd;
}

}  // namespace

int main(int argc, char** argv) {
#if defined(__GLIBC__)
    // Grading allocates and frees images of a megabyte or more per scene (float RGBA, their
    // 8-bit copies, masks, error maps). glibc would serve each from a fresh mmap and unmap it at
    // free, so the kernel faulted in and zeroed every page again (a third of judging an image
    // that matches): such blocks stay in the heap for reuse instead, up to 256 MB kept free.
    mallopt(M_MMAP_THRESHOLD, 64 << 20);
    mallopt(M_TRIM_THRESHOLD, 256 << 20);
#endif
    CLI::App app{"shaderlab: render and grade GLSL shading labs"};
    app.require_subcommand(1);

    // In the order `shaderlab --help` lists them.
    RenderArgs render;
    CLI::App* render_cmd = addRender(app, &render);
    GradeArgs grade;
    CLI::App* grade_cmd = addGrade(app, &grade);
    StartArgs start;
    CLI::App* start_cmd = addStart(app, &start);
    CheckArgs check;
    CLI::App* check_cmd = addCheck(app, &check);
    ViewArgs view;
    CLI::App* view_cmd = addView(app, &view);
    ServeArgs serve;
    CLI::App* serve_cmd = addServe(app, &serve);
    WatchArgs watch;
    CLI::App* watch_cmd = addWatch(app, &watch);
    CompareArgs compare;
    CLI::App* compare_cmd = addCompare(app, &compare);
    GoldensArgs goldens;
    CLI::App* goldens_cmd = addGoldens(app, &goldens);
    CorpusArgs corpus;
    CLI::App* corpus_cmd = addCorpus(app, &corpus);
    CorpusAddCaseArgs add_case;
    CLI::App* add_case_cmd = addCorpusAddCase(corpus_cmd, &add_case);
    NewLabArgs new_lab;
    CLI::App* new_lab_cmd = addNewLab(app, &new_lab);
    LabCheckArgs lab_check;
    CLI::App* lab_check_cmd = addLabCheck(app, &lab_check);
    MutantsArgs mutants;
    CLI::App* mutants_cmd = addMutants(app, &mutants);
    SceneSweepArgs scene_sweep;
    CLI::App* scene_sweep_cmd = addSceneSweep(app, &scene_sweep);
    BatchArgs batch;
    CLI::App* batch_cmd = addBatch(app, &batch);
    BatchWorkerArgs worker;
    CLI::App* worker_cmd = addBatchWorker(app, &worker);
    MergeArgs merge;
    CLI::App* merge_cmd = addMerge(app, &merge);
    ClassArgs class_args;
    CLI::App* class_cmd = addClass(app, &class_args);
    SimilarityArgs similarity;
    CLI::App* similarity_cmd = addSimilarity(app, &similarity);
    GradescopeBundleArgs bundle;
    CLI::App* bundle_cmd = addGradescopeBundle(app, &bundle);
    GradescopeRunArgs gs_run;
    CLI::App* gs_run_cmd = addGradescopeRun(app, &gs_run);
    std::string info_backend = "auto";
    CLI::App* info_cmd = addInfo(app, &info_backend);

    // "shaderlab chek": name the command meant instead of CLI11's "A subcommand is required".
    if (argc >= 2 && argv[1][0] != '-') {
        std::vector<std::string> shown;
        bool known = false;
        for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) {
            known = known || sub->get_name() == argv[1];
            if (!sub->get_group().empty()) shown.push_back(sub->get_name());
        }
        if (!known) {
            std::cerr << "shaderlab: there is no command '" << argv[1] << "'"
                      << shaderlab::didYouMean(argv[1], shown) << "; `shaderlab --help` lists them\n";
            return 2;
        }
    }

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        // CLI11 prints the message; every bad argument is exit code 2 (--help is 0).
        return app.exit(e) == 0 ? 0 : 2;
    }

    if (render_cmd->parsed()) return runRender(render);
    if (info_cmd->parsed()) return runInfo(info_backend);
    if (grade_cmd->parsed()) return runGrade(grade);
    if (check_cmd->parsed()) return runCheck(check);
    if (start_cmd->parsed()) return runStart(start);
    if (compare_cmd->parsed()) return runCompare(compare);
    if (view_cmd->parsed()) return runView(view);
    if (serve_cmd->parsed()) return runServe(serve);
    if (watch_cmd->parsed()) return runWatch(watch);
    if (goldens_cmd->parsed()) return runGoldens(goldens);
    if (add_case_cmd->parsed()) return runCorpusAddCase(add_case);
    if (corpus_cmd->parsed()) return runCorpus(corpus);
    if (new_lab_cmd->parsed()) return runNewLab(new_lab);
    if (lab_check_cmd->parsed()) return runLabCheck(lab_check);
    if (mutants_cmd->parsed()) return runMutants(mutants);
    if (scene_sweep_cmd->parsed()) return runSceneSweep(scene_sweep);
    if (batch_cmd->parsed()) return runBatch(batch);
    if (worker_cmd->parsed()) return runBatchWorker(worker);
    if (merge_cmd->parsed()) return runMerge(merge);
    if (class_cmd->parsed()) return runClass(class_args);
    if (similarity_cmd->parsed()) return runSimilarity(similarity);
    if (bundle_cmd->parsed()) return runGradescopeBundle(bundle);
    if (gs_run_cmd->parsed()) return runGradescopeRun(gs_run);
    return 2;
}
