// What a worker does (`shaderlab batch-worker`): one reference render or one lab graded, into a
// temporary folder renamed to the job's folder at the end; see workers.h. It runs in the
// worker's process, started by the batch (batch_workers.cpp); the render itself happens in a
// child of the worker with the time and memory limits (gradeSubmission, writeGoldens).
#include <unistd.h>

#include <filesystem>

#include "grader/reports/report.h"
#include "shaderlab/batch/batch.h"
#include "shaderlab/batch/plan.h"
#include "shaderlab/batch/workers.h"
#include "shaderlab/gl/gl_context.h"
#include "shaderlab/grading/grading.h"

namespace fs = std::filesystem;

namespace shaderlab::batch {

namespace {

// The reference solution's goldens of the lab, with the lab's hints beside them. Exit code.
int renderReference(const WorkerTask& task, Backend backend, const fs::path& tmp,
                    std::vector<std::string>* errors) {
    std::error_code ec;
    const std::vector<std::string> goldens =
        writeGoldens(task.reference_root, task.labs_root, {task.lab}, backend, tmp.string());
    errors->insert(errors->end(), goldens.begin(), goldens.end());
    if (!goldens.empty()) return 1;
    // The known-mistake hints come from the lab; they are read beside the goldens.
    const fs::path hints = fs::path(task.labs_root) / task.lab / "hints";
    if (fs::is_directory(hints, ec))
        fs::copy(hints, tmp / task.lab / "hints", fs::copy_options::recursive, ec);
    if (ec) {
        errors->push_back(hints.string() + ": " + ec.message());
        return 1;
    }
    return 0;
}

// The lab of the submission graded, its report.json written. Exit code.
int gradeLab(const WorkerTask& task, Backend backend, const fs::path& tmp, std::vector<std::string>* errors) {
    GradeOptions options;
    options.backend = backend;
    options.labs_root = task.labs_root;
    options.labs = {task.lab};
    options.out_dir = tmp.string();
    options.goldens_root = task.goldens_root;
    options.limits.timeout_s = task.timeout_s;
    options.limits.compile_timeout_s = task.compile_timeout_s;
    std::size_t memory = 0;
    if (parseMemory(task.memory, &memory)) options.limits.memory_bytes = memory;
    grader::Report report = gradeSubmission(task.submission, options);
    report.tool_version = task.tool_version;
    std::string err;
    if (!writeFileAtomically((tmp / "report.json").string(), grader::reportToJson(report), &err)) {
        errors->push_back(err);
        return 2;
    }
    return 0;
}

}  // namespace

int runWorkerTask(const WorkerTask& task, std::vector<std::string>* errors) {
    const fs::path final_dir = task.out_dir;
    // Named by host and process: batches on several machines may share the cache.
    char host[256] = "";
    gethostname(host, sizeof host - 1);
    const fs::path tmp = final_dir.string() + ".tmp-" + host + "-" + std::to_string(getpid());
    std::error_code ec;
    fs::remove_all(tmp, ec);
    fs::create_directories(tmp, ec);
    if (ec) {
        errors->push_back(tmp.string() + ": " + ec.message());
        return 2;
    }
    Backend backend{};
    parseBackend(task.backend, &backend);
    const int code = task.mode == "reference" ? renderReference(task, backend, tmp, errors)
                                              : gradeLab(task, backend, tmp, errors);
    if (code != 0) return code;
    fs::rename(tmp, final_dir, ec);
    if (ec) {  // another batch made it first: theirs is as good
        fs::remove_all(tmp, ec);
        return fs::exists(final_dir) ? 0 : 2;
    }
    return 0;
}

}  // namespace shaderlab::batch
