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

// `<final_dir>.tmp-<host>-<pid>`, emptied and made: where a result is put together before its
// rename. Named by host and process: batches on several machines may share the cache.
fs::path temporaryFor(const std::string& final_dir, std::vector<std::string>* errors) {
    char host[256] = "";
    gethostname(host, sizeof host - 1);
    const fs::path tmp = final_dir + ".tmp-" + host + "-" + std::to_string(getpid());
    std::error_code ec;
    fs::remove_all(tmp, ec);
    fs::create_directories(tmp, ec);
    if (ec) {
        errors->push_back(tmp.string() + ": " + ec.message());
        return {};
    }
    return tmp;
}

// `tmp` renamed to `final_dir`; when another batch made it first, theirs is as good. Exit code.
int land(const fs::path& tmp, const std::string& final_dir) {
    std::error_code ec;
    fs::rename(tmp, final_dir, ec);
    if (ec) {
        fs::remove_all(tmp, ec);
        return fs::exists(final_dir) ? 0 : 2;
    }
    return 0;
}

// The lab of the task, and those of task.also, graded by one gradeSubmission (one render child
// draws them all, IsolatedRenderQueue); as each is graded, its pictures and a report.json holding
// that lab alone land in its own folder, as a worker of its own would leave them. Exit code.
int gradeLabs(const WorkerTask& task, Backend backend, std::vector<std::string>* errors) {
    struct Place {
        std::string lab, final_dir;
    };
    std::vector<Place> places = {{task.lab, task.out_dir}};
    GradeOptions options;
    options.lab_goldens_roots[task.lab] = task.goldens_root;
    for (std::size_t i = 0; i + 2 < task.also.size(); i += 3) {
        if (options.lab_goldens_roots.count(task.also[i])) {
            errors->push_back("--also names lab " + task.also[i] + " twice");
            return 2;
        }
        places.push_back({task.also[i], task.also[i + 1]});
        options.lab_goldens_roots[task.also[i]] = task.also[i + 2];
    }
    // The pictures of every lab are drawn into one folder and moved to the lab's own when it lands.
    const fs::path work = temporaryFor(task.out_dir + "-labs", errors);
    if (work.empty()) return 2;
    options.backend = backend;
    options.labs_root = task.labs_root;
    options.isolation_root = task.reference_root;
    for (const Place& p : places) options.labs.push_back(p.lab);
    options.out_dir = work.string();
    options.limits.timeout_s = task.timeout_s;
    options.limits.compile_timeout_s = task.compile_timeout_s;
    std::size_t memory = 0;
    if (parseMemory(task.memory, &memory)) options.limits.memory_bytes = memory;
    int code = 0;
    gradeSubmission(task.submission, options, [&](const grader::Report& so_far) {
        const grader::ReportLab& lab = so_far.labs.back();
        const Place& place = places[so_far.labs.size() - 1];
        const fs::path tmp = temporaryFor(place.final_dir, errors);
        std::error_code ec;
        if (tmp.empty()) {
            code = 2;
            return;
        }
        if (fs::exists(work / lab.id, ec)) fs::rename(work / lab.id, tmp / lab.id, ec);
        grader::Report one;
        one.tool_version = task.tool_version;
        one.submission = so_far.submission;
        one.backend = so_far.backend;
        one.renderer = so_far.renderer;
        one.labs = {lab};
        one.score = lab.score;
        one.max_score = lab.max_score;
        std::string err;
        if (ec || !writeFileAtomically((tmp / "report.json").string(), grader::reportToJson(one), &err)) {
            errors->push_back(ec ? (tmp / lab.id).string() + ": " + ec.message() : err);
            fs::remove_all(tmp, ec);
            code = 2;
            return;
        }
        if (land(tmp, place.final_dir) != 0) code = 2;
    });
    std::error_code ec;
    fs::remove_all(work, ec);
    return code;
}

}  // namespace

int runWorkerTask(const WorkerTask& task, std::vector<std::string>* errors) {
    Backend backend{};
    parseBackend(task.backend, &backend);
    if (task.mode == "grade") {
        if (task.also.size() % 3 != 0) {
            errors->push_back("--also takes three values each: lab, out folder, goldens");
            return 2;
        }
        return gradeLabs(task, backend, errors);
    }
    const fs::path tmp = temporaryFor(task.out_dir, errors);
    if (tmp.empty()) return 2;
    const int code = renderReference(task, backend, tmp, errors);
    if (code != 0) return code;
    return land(tmp, task.out_dir);
}

}  // namespace shaderlab::batch
