// Running a batch. runJobs() is the pool: the plan's jobs (plan.h) in worker processes
// (workers.h), at most BatchSettings::jobs_max at a time, references first, each under a
// watchdog; it prints nothing and tells the caller through hooks. gradeBatch() is the whole
// `shaderlab batch` once its options are read: plan, pool, one report folder per submission and
// the summary (results.h), with the progress and the messages on the terminal.
#pragma once

#include <chrono>
#include <functional>
#include <string>
#include <vector>

#include "shaderlab/batch/batch.h"
#include "shaderlab/batch/plan.h"

namespace shaderlab::batch {

struct ResultsFolder;  // results.h

// What runJobs() tells its caller. An empty hook is not called.
struct ScheduleHooks {
    // Every job of the submission is done (at once for one unchanged since its report, or with
    // none to run); called once per submission, `finished` already set.
    std::function<void(Submission&)> finished;
    // The reference solution of `job.lab` did not render (`why`): its labs are graded against
    // the stored goldens from now on.
    std::function<void(const Job& job, const std::string& why)> reference_failed;
    // Every few milliseconds while workers run.
    std::function<void()> tick;
};

// Runs every job of `plan` that is not done yet. A worker takes a grading job with the other
// grading jobs of its submission that can start (at most its share of the grading jobs left),
// drawn by one render child. A job is done when its result has landed; a job whose worker failed
// before it landed failed, with the reason in Job::error, if the worker was doing it, and goes
// back to the pool if the worker had not come to it. A grading job of a lab
// whose reference failed goes against the goldens, into a folder of its own.
void runJobs(Plan* plan, const ResultsFolder& folder, const BatchSettings& settings,
             const ScheduleHooks& hooks);

// What the workers are doing now, for the progress line: the submission each worker started for and
// its lab ("grading alice (01-phong), bob (02-toon) +1"), and the one running longest once it has
// run 10 s ("; alice (01-phong) for 40 s"); "" when none runs. Never the last one finished: a lab
// running to its limit would leave the line naming someone else for the whole wait.
std::string describeRunning(const Plan& plan, std::chrono::steady_clock::time_point now);

// Grades `sources` with `labs` into `folder` and writes summary.json and summary.csv, printing
// the progress to stdout and the problems to stderr. `started`: when the command began, for the
// figures printed at the end. Returns the exit code: 0, 1 when a worker failed, 2 when a report
// or the summary could not be written.
int gradeBatch(const BatchSettings& settings, const ResultsFolder& folder, std::vector<LabPlan> labs,
               const std::vector<SubmissionSource>& sources, std::chrono::steady_clock::time_point started);

}  // namespace shaderlab::batch
