// shaderlab: render, grade and check GLSL lab submissions. Argument parsing only; the work is
// in the command functions (commands.h) and the libraries.
#include <CLI/CLI.hpp>
#include <cstdio>

#include "commands.h"

int main(int argc, char** argv) {
    using namespace shaderlab::cli;
    CLI::App app{"shaderlab: render and grade GLSL shading labs"};
    app.require_subcommand(1);

    // The limits of each lab's render process, for grade and check (docs/grading.md, "Limits").
    auto add_limits = [](CLI::App* cmd, LimitArgs* limits, const char* draw_help) {
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
    };

    auto add_common = [](CLI::App* cmd, CommonOptions* common) {
        cmd->add_option("--backend", common->backend, "OpenGL context backend")
            ->check(CLI::IsMember({"osmesa", "egl"}))
            ->capture_default_str();
        cmd->add_option("--labs", common->labs_root, "folder holding the labs (default: the bundled labs/)");
        cmd->add_option("--lab", common->labs, "lab id, e.g. 01-phong (repeatable; default: all labs)");
    };

    RenderArgs render;
    CLI::App* render_cmd =
        app.add_subcommand("render", "render a submission's labs to PNG, one per graded scene");
    render_cmd
        ->add_option("submission", render.submission, "folder mirroring labs/ (e.g. reference_solutions)")
        ->required();
    render_cmd->add_option("--out", render.out_dir, "output folder")->required();
    render_cmd->add_flag("--all-passes", render.all_passes,
                         "also write the ungraded passes of multi-pass labs");
    add_common(render_cmd, &render.common);

    GradeArgs grade;
    CLI::App* grade_cmd =
        app.add_subcommand("grade", "grade a submission: report.json, report.html and images");
    grade_cmd->add_option("submission", grade.submission, "folder mirroring labs/")->required();
    grade_cmd->add_option("--out", grade.out_dir, "output folder")->required();
    grade_cmd->add_option("--format", grade.formats, "extra report formats: gradescope (results.json), junit")
        ->check(CLI::IsMember({"json", "gradescope", "junit"}));
    grade_cmd->add_option("--reference", grade.reference_root,
                          "reference solutions folder (default: reference_solutions beside labs/)");
    grade_cmd->add_flag("--no-reference", grade.no_reference, "grade against the stored golden images");
    add_limits(grade_cmd, &grade.limits, "seconds one lab may take to draw its scenes");
    add_common(grade_cmd, &grade.common);

    StartArgs start;
    CLI::App* start_cmd =
        app.add_subcommand("start", "copy a lab's starter files into work/<lab>/, your own copy to edit");
    start_cmd->add_option("lab", start.lab, "lab id, e.g. 01-phong")->required();
    start_cmd->add_option("--into", start.into, "folder to copy into (default: work/ beside labs/)");
    start_cmd->add_flag("--force", start.force, "overwrite files already there with the starter code");
    start_cmd->add_option("--labs", start.common.labs_root, "folder holding the labs");

    CheckArgs check;
    CLI::App* check_cmd =
        app.add_subcommand("check", "check one lab of your work (work/<lab>/) and print a verdict");
    check_cmd->add_option("lab", check.lab, "lab id, e.g. 01-phong")->required();
    check_cmd->add_option("--submission", check.submission,
                          "folder mirroring labs/ (default: work/ beside labs/, made by `shaderlab start`)");
    check_cmd->add_option("--out", check.out_dir, "where images and the report go (default: out/check)");
    check_cmd->add_flag("--no-reference", check.no_reference, "use the stored golden images");
    add_limits(check_cmd, &check.limits, "seconds the lab may take to draw its scenes");
    check_cmd->add_option("--backend", check.common.backend)->check(CLI::IsMember({"osmesa", "egl"}));
    check_cmd->add_option("--labs", check.common.labs_root, "folder holding the labs");

    ViewArgs view;
    CLI::App* view_cmd = app.add_subcommand(
        "view", "open a window on one lab of your work that follows every save, beside the reference");
    view_cmd->add_option("lab", view.lab, "lab id, e.g. 01-phong")->required();
    view_cmd->add_option(
        "--submission", view.submission,
        "folder mirroring labs/ (default: work/ beside labs/; reference_solutions works too)");
    view_cmd->add_option("--reference", view.reference_root,
                         "reference solutions folder (default: reference_solutions beside labs/)");
    view_cmd->add_flag("--no-reference", view.no_reference, "compare with the stored golden images");
    view_cmd->add_option("--scene", view.scene, "scene shown first");
    view_cmd->add_option("--image", view.image, "image shown first: PASS.ATTACHMENT, e.g. bright.color");
    view_cmd
        ->add_option("--orbit", view.orbit,
                     "start turned from the graded view: YAW PITCH (degrees) ZOOM (R in the window resets)")
        ->expected(3);
    view_cmd->add_option("--mode", view.mode, "first view")
        ->check(CLI::IsMember({"student", "reference", "diff", "split"}))
        ->capture_default_str();
    view_cmd->add_option("--timeout", view.timeout_s, "seconds one scene may take to render")
        ->check(CLI::Range(0.1, 600.0))
        ->capture_default_str();
    view_cmd->add_option("--frames", view.frames, "exit after N frames once the first picture is shown")
        ->check(CLI::Range(1, 1000000));
    view_cmd
        ->add_option("--exit-after-reloads", view.exit_after_reloads,
                     "exit once N pictures (or errors) made after a file change are shown")
        ->check(CLI::Range(1, 1000000));
    view_cmd->add_option("--screenshot", view.screenshot,
                         "at exit, save the picture as shown, one pixel per image pixel (PNG)");
    view_cmd->add_option("--screenshot-window", view.screenshot_window,
                         "at exit, save the whole window (PNG)");
    view_cmd->add_option("--backend", view.common.backend)->check(CLI::IsMember({"osmesa", "egl"}));
    view_cmd->add_option("--labs", view.common.labs_root, "folder holding the labs");

    WatchArgs watch;
    CLI::App* watch_cmd = app.add_subcommand(
        "watch", "check one lab of your work again on every save, without a window (like `check`)");
    watch_cmd->add_option("lab", watch.check.lab, "lab id, e.g. 01-phong")->required();
    watch_cmd->add_option("--submission", watch.check.submission,
                          "folder mirroring labs/ (default: work/ beside labs/)");
    watch_cmd->add_option("--out", watch.check.out_dir,
                          "where images and the report go (default: out/check)");
    watch_cmd->add_flag("--no-reference", watch.check.no_reference, "use the stored golden images");
    add_limits(watch_cmd, &watch.check.limits, "seconds the lab may take to draw its scenes");
    watch_cmd->add_option("--max-checks", watch.max_checks, "stop after N checks (default: until Ctrl-C)")
        ->check(CLI::Range(1, 1000000));
    watch_cmd->add_option("--backend", watch.check.common.backend)->check(CLI::IsMember({"osmesa", "egl"}));
    watch_cmd->add_option("--labs", watch.check.common.labs_root, "folder holding the labs");

    CompareArgs compare;
    CLI::App* compare_cmd =
        app.add_subcommand("compare", "print PSNR, SSIM, FLIP and mismatch of two PNG images");
    compare_cmd->add_option("reference", compare.a, "reference image")->required();
    compare_cmd->add_option("test", compare.b, "test image")->required();
    compare_cmd->add_flag("--json", compare.json, "print JSON");
    compare_cmd->add_option("--tolerance", compare.tolerance, "per-channel tolerance of the mismatch count")
        ->check(CLI::Range(0.0f, 1.0f))
        ->capture_default_str();

    GoldensArgs goldens;
    CLI::App* goldens_cmd =
        app.add_subcommand("goldens",
                           "render the reference solutions into labs/*/golden/ and the corpus "
                           "mistakes into labs/*/hints/");
    goldens_cmd->add_option("--reference", goldens.reference_root, "reference solutions folder");
    goldens_cmd->add_option("--into", goldens.golden_root,
                            "write to DIR/<lab>/golden/ instead of the labs (to compare)");
    goldens_cmd->add_option("--corpus", goldens.corpus_root,
                            "folder of <lab>/cases.json whose mistakes become hints (default: tests/corpus)");
    goldens_cmd->add_flag("--no-hints", goldens.no_hints,
                          "only the goldens: do not render the corpus mistakes into labs/*/hints/");
    add_common(goldens_cmd, &goldens.common);

    CorpusArgs corpus;
    CLI::App* corpus_cmd = app.add_subcommand(
        "corpus", "grade each lab's known mistakes and alternative solutions and check the verdicts");
    corpus_cmd->add_option("--corpus", corpus.corpus_root,
                           "folder of <lab>/cases.json (default: tests/corpus)");
    corpus_cmd->add_option("--reference", corpus.reference_root, "reference solutions folder");
    corpus_cmd->add_option("--out", corpus.out_dir, "output folder")->required();
    corpus_cmd->add_flag("--render-reference", corpus.use_reference,
                         "render the reference for every case instead of reading the goldens");
    corpus_cmd->add_option("--timeout", corpus.timeout_s, "seconds one case may take to render")
        ->check(CLI::Range(0.1, 600.0))
        ->capture_default_str();
    add_common(corpus_cmd, &corpus.common);

    BatchArgs batch;
    CLI::App* batch_cmd = app.add_subcommand(
        "batch",
        "grade every submission (a folder or a .zip) of a folder: one report each, summary.csv/json");
    batch_cmd
        ->add_option("submissions", batch.submissions_dir, "folder of submissions (folders or .zip files)")
        ->required();
    batch_cmd->add_option("--out", batch.out_dir, "results folder")->required();
    batch_cmd->add_option("--jobs,-j", batch.jobs, "labs graded at once (default: the number of cores)")
        ->check(CLI::Range(1, 256));
    batch_cmd->add_option("--timeout", batch.timeout_s, "seconds one lab may take to draw its scenes")
        ->check(CLI::Range(0.1, 86400.0))
        ->capture_default_str();
    batch_cmd
        ->add_option("--compile-timeout", batch.compile_timeout_s,
                     "seconds one lab may take to create its context, read, compile and link its shaders")
        ->check(CLI::Range(0.1, 86400.0))
        ->capture_default_str();
    batch_cmd
        ->add_option("--memory", batch.memory,
                     "resident memory of each render process (e.g. 2G); workers get 4G more address space")
        ->capture_default_str();
    batch_cmd->add_option("--shard", batch.shard,
                          "K/N: grade only every N-th submission, from the K-th (job arrays)");
    batch_cmd->add_option("--reference", batch.reference_root,
                          "reference solutions folder (default: reference_solutions beside labs/)");
    batch_cmd->add_flag("--no-reference", batch.no_reference, "grade against the stored golden images");
    batch_cmd->add_option("--cache", batch.cache_dir,
                          "where reference renders are kept (default: <out>/.shaderlab/references)");
    batch_cmd->add_option("--format", batch.formats, "extra report formats: gradescope (results.json), junit")
        ->check(CLI::IsMember({"json", "gradescope", "junit"}));
    batch_cmd->add_option("--max-unpacked", batch.max_unpacked_mib, "MiB a submitted zip may unpack to")
        ->check(CLI::Range(1, 1 << 20))
        ->capture_default_str();
    add_common(batch_cmd, &batch.common);

    BatchWorkerArgs worker;
    // Started by `batch` for each unit of work; not for people, so hidden from --help.
    CLI::App* worker_cmd = app.add_subcommand("batch-worker", "grade one lab for `batch`")->group("");
    worker_cmd->add_option("--mode", worker.mode)->required()->check(CLI::IsMember({"grade", "reference"}));
    worker_cmd->add_option("--labs", worker.labs_root)->required();
    worker_cmd->add_option("--lab", worker.lab)->required();
    worker_cmd->add_option("--out", worker.out_dir)->required();
    worker_cmd->add_option("--backend", worker.backend);
    worker_cmd->add_option("--submission", worker.submission);
    worker_cmd->add_option("--goldens", worker.goldens_root);
    worker_cmd->add_option("--reference", worker.reference_root);
    worker_cmd->add_option("--timeout", worker.timeout_s);
    worker_cmd->add_option("--compile-timeout", worker.compile_timeout_s);
    worker_cmd->add_option("--memory", worker.memory);

    MergeArgs merge;
    CLI::App* merge_cmd = app.add_subcommand(
        "merge", "merge the results folders of batch shards: summary.csv/json and reports");
    merge_cmd->add_option("results", merge.inputs, "results folders of `shaderlab batch --shard`")
        ->required();
    merge_cmd->add_option("--out", merge.out_dir, "merged results folder")->required();

    GradescopeBundleArgs bundle;
    CLI::App* bundle_cmd = app.add_subcommand(
        "gradescope-bundle",
        "write the autograder zip of a Gradescope assignment (setup.sh, run_autograder, labs)");
    bundle_cmd->add_option("--out", bundle.out_zip, "the zip to write, e.g. autograder.zip")->required();
    bundle_cmd->add_option("--reference", bundle.reference_root,
                           "reference solutions folder (default: reference_solutions beside labs/)");
    bundle_cmd->add_option("--visibility", bundle.visibility, "when students see the results")
        ->check(CLI::IsMember({"visible", "hidden", "after_due_date", "after_published"}))
        ->capture_default_str();
    bundle_cmd->add_option("--tests", bundle.tests, "one Gradescope test per learning goal or per scene")
        ->check(CLI::IsMember({"goals", "scenes"}))
        ->capture_default_str();
    bundle_cmd->add_option("--timeout", bundle.timeout_s, "seconds one lab may take to render")
        ->check(CLI::Range(0.1, 3600.0))
        ->capture_default_str();
    bundle_cmd->add_option("--labs", bundle.common.labs_root, "folder holding the labs");
    bundle_cmd->add_option("--lab", bundle.common.labs, "lab id (repeatable; default: all labs)");

    // Run by the bundle's run_autograder on Gradescope; hidden from --help.
    GradescopeRunArgs gs_run;
    CLI::App* gs_run_cmd =
        app.add_subcommand("gradescope-run", "grade <root>/submission into <root>/results/results.json")
            ->group("");
    gs_run_cmd->add_option("--root", gs_run.root)->capture_default_str();
    gs_run_cmd->add_option("--reference", gs_run.reference_root);
    gs_run_cmd->add_option("--visibility", gs_run.visibility)
        ->check(CLI::IsMember({"visible", "hidden", "after_due_date", "after_published"}));
    gs_run_cmd->add_option("--tests", gs_run.tests)->check(CLI::IsMember({"goals", "scenes"}));
    gs_run_cmd->add_option("--timeout", gs_run.timeout_s)->check(CLI::Range(0.1, 3600.0));
    add_common(gs_run_cmd, &gs_run.common);

    std::string info_backend = "osmesa";
    CLI::App* info_cmd = app.add_subcommand("info", "print the OpenGL context a backend gives");
    info_cmd->add_option("--backend", info_backend)->check(CLI::IsMember({"osmesa", "egl"}));

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
    if (watch_cmd->parsed()) return runWatch(watch);
    if (goldens_cmd->parsed()) return runGoldens(goldens);
    if (corpus_cmd->parsed()) return runCorpus(corpus);
    if (batch_cmd->parsed()) return runBatch(batch);
    if (worker_cmd->parsed()) return runBatchWorker(worker);
    if (merge_cmd->parsed()) return runMerge(merge);
    if (bundle_cmd->parsed()) return runGradescopeBundle(bundle);
    if (gs_run_cmd->parsed()) return runGradescopeRun(gs_run);
    return 2;
}
