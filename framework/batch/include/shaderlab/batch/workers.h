// The worker processes of a batch, from both sides.
//
// The batch's side: a worker is `<exe> batch-worker ...` (the same program) in its own process
// group, killed when the batch dies (PR_SET_PDEATHSIG) or is stopped by a signal, with its output
// in a log file and its address space limited. The batch itself never renders and never holds a
// GL context: what the driver is, it asks a child (probeRenderer).
//
// The worker's side: runWorkerTask() does one job of the plan (plan.h), a reference render or one
// lab graded (renderLabIsolated, with the time and memory limits, in a child of its own), or
// several grading jobs of one submission (their labs drawn by one render child), and lands each
// result in its job's folder with one rename. POSIX only.
#pragma once

#include <sys/types.h>

#include <cstddef>
#include <string>
#include <vector>

namespace shaderlab::batch {

constexpr int kMaxWorkers = 256;  // at once

struct Spawned {
    pid_t pid = -1;
    std::string error;
};

// Starts `argv` as a worker: its own process group, killed when this process dies, stdin from
// /dev/null, stdout and stderr into `log`, address space limited to `memory` bytes (0: unlimited).
Spawned spawnWorker(const std::vector<std::string>& argv, const std::string& log, std::size_t memory);

// Once the worker `pid` is reaped: the signal handler no longer kills its group.
void forgetWorker(pid_t pid);

// From now on SIGINT, SIGTERM and SIGHUP kill every worker's process group (worker and render
// child), then this process.
void killWorkersOnSignals();

// "exit code N" or "killed by signal N (name)", for a waitpid() status.
std::string describeExit(int wstatus);

// ": <the last line of a worker's log>; log: <path>", for the message of a worker that failed.
std::string lastLogLine(const std::string& log);

// The GL renderer a worker would see, for the reference cache key: `shaderlab info`, in a child,
// its output in `log`. Empty when there is no context.
std::string probeRenderer(const std::string& exe, const std::string& backend, const std::string& log);

// The cores this process may run on (a Slurm task or a container may get fewer than the machine has).
int usableCores();

// This program's path, for the workers' command line.
std::string selfExe();

// One job, as `shaderlab batch-worker` is given it.
struct WorkerTask {
    std::string mode;  // grade | reference
    std::string labs_root, lab, backend = "auto";
    std::string submission, out_dir, goldens_root, reference_root;
    double timeout_s = 60.0;
    double compile_timeout_s = 30.0;
    std::string memory = "2G";
    std::string tool_version;  // in the report
    // More labs of the same submission, graded by the same render child after `lab` (grade
    // mode): three strings each, the lab, its out_dir and its goldens_root (may be empty). Each
    // lab lands in its own out_dir as soon as it is graded, as a worker of its own would leave it.
    std::vector<std::string> also;
};

// Does `task` into `<out_dir>.tmp-<pid>`, then renames that to `out_dir` (when another batch made
// it first, theirs is kept). Returns the worker's exit code: 0, 1 when the reference did not
// render, 2 when the results cannot be written; the messages go to `errors`.
int runWorkerTask(const WorkerTask& task, std::vector<std::string>* errors);

}  // namespace shaderlab::batch
