// `shaderlab batch` (grade every submission of a folder), its worker, and `shaderlab merge`.
//
// The batch process never renders and never holds a GL context. It unpacks and hashes the
// submissions, then runs worker processes (`shaderlab batch-worker`, this same program), at most
// --jobs at a time, each grading labs of one submission. Each worker is its own process group,
// dies with the batch (PR_SET_PDEATHSIG) and renders in a child of its own (IsolatedRenderQueue)
// with the time and memory limits. What a worker made lands in the results folder under .shaderlab/, or in
// the cache given with --cache, with one rename, keyed by a hash of everything it depends on, so that:
//   - the reference solution of a lab is rendered once, then taken from the cache;
//   - a lab folder that several students submitted unchanged (the starter code) is graded once,
//     in the whole class when its shards (--shard K/N) share a cache;
//   - a batch killed half-way and run again grades only what is missing, and a submission whose
//     content and settings did not change since its report is skipped.
// See docs/instructors.md.
//
// This file only reads the options and says what is wrong with them; the work is the batch
// library's (framework/batch: plan.h, schedule.h, workers.h, results.h).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>

#include "commands.h"
#include "shaderlab/batch/batch.h"
#include "shaderlab/batch/plan.h"
#include "shaderlab/batch/results.h"
#include "shaderlab/batch/schedule.h"
#include "shaderlab/batch/workers.h"
#include "shaderlab/lab/lab_catalog.h"

namespace fs = std::filesystem;

namespace shaderlab::cli {

namespace {

std::string defaultReferenceRootOf(const std::string& labs_root) {
    const fs::path p = fs::path(labs_root).parent_path() / "reference_solutions";
    std::error_code ec;
    return fs::is_directory(p, ec) ? p.string() : std::string();
}

// The labs to grade (all_lab_ids set), read from their lab.json. false after saying why.
bool readBatchLabs(const BatchArgs& args, batch::BatchSettings* settings, std::vector<batch::LabPlan>* labs) {
    if (!resolveLabsRoot(args.common, &settings->labs_root)) return false;
    settings->all_lab_ids = listLabIds(settings->labs_root);
    // Named labs are graded in every submission; otherwise each submission's own (plan.h).
    settings->labs_named = !args.common.labs.empty();
    const std::vector<std::string> ids = args.common.labs.empty() ? settings->all_lab_ids : args.common.labs;
    if (ids.empty()) {
        std::cerr << "shaderlab: no labs found in " << settings->labs_root << "\n";
        return false;
    }
    std::vector<std::string> errors;
    const bool ok = batch::readLabs(settings->labs_root, ids, labs, &errors);
    for (const std::string& e : errors) std::cerr << e << "\n";
    return ok;
}

}  // namespace

int runBatch(const BatchArgs& args) {
    const auto t_start = std::chrono::steady_clock::now();

    batch::BatchSettings settings;
    std::vector<batch::LabPlan> labs;
    if (!readBatchLabs(args, &settings, &labs)) return 2;
    if (!batch::parseMemory(args.memory, &settings.memory)) {
        std::cerr << "shaderlab: --memory " << args.memory
                  << ": expected a size such as 4G or 2048M (64M at least)\n";
        return 2;
    }
    int shard_k = 1, shard_n = 1;
    if (!batch::parseShard(args.shard, &shard_k, &shard_n)) {
        std::cerr << "shaderlab: --shard " << args.shard << ": expected K/N with 1 <= K <= N, e.g. 2/8\n";
        return 2;
    }
    // Each shard would otherwise take the labs its own share hands in, and shards with other
    // labs (and totals) do not merge.
    if (!args.shard.empty() && args.common.labs.empty()) {
        std::cerr << "shaderlab: --shard needs --lab: name the assignment's labs, so that every shard "
                     "grades and totals the same ones\n";
        return 2;
    }
    std::string error;
    std::vector<batch::SubmissionSource> sources;
    if (!batch::selectSubmissions(args.submissions_dir, args.out_dir, shard_k, shard_n, &sources, &error,
                                  &settings.shard)) {
        std::cerr << "shaderlab: " << error << "\n";
        return 2;
    }
    // A shard says which it is, and of what, in its summary, so that `merge` can tell when one
    // is missing. Without --shard the summary is a whole batch's.
    if (!args.shard.empty()) {
        settings.shard.index = shard_k;
        settings.shard.count = shard_n;
    }
    // The results folder: made, writable and ours alone before any work.
    batch::ResultsFolder folder;
    if (!batch::openResultsFolder(args.out_dir, args.cache_dir, &folder, &error)) {
        std::cerr << "shaderlab: " << error << "\n";
        return 2;
    }

    // Mesa's compiled shaders are kept for every worker (inherited), private to this batch's
    // state folder (or the cache shards share): the lab's own programs are compiled once, not
    // once per student. A student's warnings survive it (gl_context.h: useShaderCache).
    useShaderCache(fs::absolute(args.cache_dir.empty() ? folder.state / "shader-cache"
                                                       : fs::path(args.cache_dir) / "shader-cache")
                       .string());
    batch::killWorkersOnSignals();
    settings.exe = batch::selfExe();
    settings.backend = backendName(chooseBackend(args.common.backend));  // workers get the resolved one
    const fs::path renderer_log = folder.state / "logs" / "renderer.log";
    settings.renderer = batch::probeRenderer(settings.exe, settings.backend, renderer_log.string());
    if (settings.renderer.empty()) {
        std::cerr << "shaderlab: no OpenGL context with backend " << args.common.backend << ": see "
                  << renderer_log.string() << "\n";
        return 2;
    }
    std::error_code ec;
    settings.reference_root =
        args.no_reference ? std::string()
                          : (args.reference_root.empty() ? defaultReferenceRootOf(settings.labs_root)
                                                         : fs::absolute(args.reference_root, ec).string());
    settings.jobs_max =
        std::max(1, std::min(batch::kMaxWorkers, args.jobs > 0 ? args.jobs : batch::usableCores()));
    settings.tool_version = SHADERLAB_VERSION;
    settings.formats = args.formats;
    settings.timeout_s = args.timeout_s;
    settings.compile_timeout_s = args.compile_timeout_s;
    settings.max_unpacked_mib = args.max_unpacked_mib;
    return batch::gradeBatch(settings, folder, std::move(labs), sources, t_start);
}

int runBatchWorker(const BatchWorkerArgs& args) {
    batch::WorkerTask task = args;
    task.tool_version = SHADERLAB_VERSION;
    std::vector<std::string> errors;
    const int code = batch::runWorkerTask(task, &errors);
    for (const std::string& e : errors) std::cerr << "shaderlab: " << e << "\n";
    return code;
}

int runMerge(const MergeArgs& args) {
    batch::MergeResult merged;
    std::string error;
    if (!batch::mergeResults(args.inputs, args.out_dir, &merged, &error)) {
        std::cerr << "shaderlab: " << error << "\n";
        return 2;
    }
    std::printf("%zu submissions from %zu results folders\nsummary: %s\n", merged.submissions,
                args.inputs.size(), merged.summary_csv.c_str());
    return 0;
}

}  // namespace shaderlab::cli
