// gradeBatch (schedule.h): a whole batch from its plan to its summary, and everything it prints
// on the terminal while it runs (the progress, the problems, the figures at the end). Reading
// the options is the command's (framework/cli/command_batch.cpp).
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <set>

#include "shaderlab/batch/batch.h"
#include "shaderlab/batch/plan.h"
#include "shaderlab/batch/results.h"
#include "shaderlab/batch/schedule.h"

namespace shaderlab::batch {

namespace {

using Clock = std::chrono::steady_clock;

// One line per finished submission, or a bar redrawn in place on a terminal.
class Progress {
  public:
    explicit Progress(std::size_t total) : total_(total), tty_(isatty(STDOUT_FILENO)), t0_(Clock::now()) {}
    void finished(const Submission& s) {
        ++done_;
        if (!tty_) {
            std::printf("[%zu/%zu] %s: %s %.2f / %.2f\n", done_, total_, printable(s.row.student, 80).c_str(),
                        s.skipped ? "unchanged," : s.row.status.c_str(), s.row.total, s.row.max_total);
            std::fflush(stdout);
        } else {
            draw(printable(s.row.student, 30));
        }
    }
    void tick() {
        if (tty_ && std::chrono::duration<double>(Clock::now() - last_draw_).count() > 0.5) draw(last_name_);
    }
    void end() {
        if (tty_) std::printf("\n");
    }

  private:
    void draw(const std::string& name) {
        last_name_ = name;
        last_draw_ = Clock::now();
        const double elapsed = std::chrono::duration<double>(Clock::now() - t0_).count();
        const int width = 30;
        const int filled = total_ ? static_cast<int>(width * done_ / total_) : width;
        std::string bar(static_cast<std::size_t>(filled), '#');
        bar += std::string(static_cast<std::size_t>(width - filled), '.');
        char eta[32] = "--:--";
        if (done_ > 0 && done_ < total_) {
            const int s = static_cast<int>(elapsed / done_ * (total_ - done_));
            std::snprintf(eta, sizeof eta, "%d:%02d", s / 60, s % 60);
        } else if (done_ == total_) {
            std::snprintf(eta, sizeof eta, "0:00");
        }
        std::printf("\r\033[K[%s] %zu/%zu  ETA %s  %s", bar.c_str(), done_, total_, eta, name.c_str());
        std::fflush(stdout);
    }
    std::size_t total_, done_ = 0;
    bool tty_;
    Clock::time_point t0_, last_draw_{};
    std::string last_name_;
};

// The summary of every submission, in the plan's order.
Summary summaryOf(const BatchSettings& settings, const Plan& plan) {
    Summary summary;
    summary.tool_version = settings.tool_version;
    summary.shard = settings.shard;
    for (const LabPlan& lab : plan.labs) summary.labs.push_back(lab.id);
    for (const Submission& sub : plan.subs) summary.rows.push_back(sub.row);
    return summary;
}

// The figures of the run: submissions graded and reused, worker runs, wall and CPU time.
void printFigures(const BatchSettings& settings, const Plan& plan, Clock::time_point started) {
    std::size_t graded = 0, reused = 0;
    for (const Submission& sub : plan.subs) {
        graded += sub.skipped ? 0 : 1;
        reused += sub.skipped ? 1 : 0;
    }
    std::size_t cached = 0;
    std::set<pid_t> workers;  // a worker may have done several jobs
    for (const Job& job : plan.jobs) {
        if (job.pid > 0) workers.insert(job.pid);
        cached += job.pid <= 0 && job.ok && job.kind == Job::Grade ? 1 : 0;
    }
    const std::size_t ran = workers.size();
    const double wall = std::chrono::duration<double>(Clock::now() - started).count();
    rusage self{}, children{};
    getrusage(RUSAGE_SELF, &self);
    getrusage(RUSAGE_CHILDREN, &children);
    auto seconds = [](const timeval& t) { return static_cast<double>(t.tv_sec) + t.tv_usec / 1e6; };
    const double cpu = seconds(self.ru_utime) + seconds(self.ru_stime) + seconds(children.ru_utime) +
                       seconds(children.ru_stime);
    if (settings.shard.count > 0)
        std::printf("shard %d/%d: %zu of the %zu submissions\n", settings.shard.index, settings.shard.count,
                    plan.subs.size(), settings.shard.submissions);
    std::printf(
        "%zu submissions (%zu graded, %zu unchanged since their report), %zu worker runs, %zu graded labs "
        "taken from the cache, %d jobs at a time; %.1f s wall, %.1f s CPU, %.0f submissions per minute\n",
        plan.subs.size(), graded, reused, ran, cached, settings.jobs_max, wall, cpu,
        wall > 0 ? 60.0 * plan.subs.size() / wall : 0.0);
}

}  // namespace

int gradeBatch(const BatchSettings& settings, const ResultsFolder& folder, std::vector<LabPlan> labs,
               const std::vector<SubmissionSource>& sources, Clock::time_point started) {
    Plan plan;
    plan.labs = std::move(labs);
    planLabs(settings, folder, &plan);
    planSubmissions(settings, folder, sources, &plan);
    removeStaleWork(folder, plan.subs);

    Progress progress(plan.subs.size());
    int exit_code = 0;
    ScheduleHooks hooks;
    hooks.finished = [&](Submission& sub) {
        if (!sub.skipped) {
            std::string err;
            if (!writeSubmissionResults(&sub, plan.labs, plan.jobs, folder, settings, &err)) {
                std::cerr << "shaderlab: " << printable(sub.source.student)
                          << ": cannot write the report: " << err << "\n";
                exit_code = 2;
            }
            for (std::size_t j : sub.jobs)
                if (j != SIZE_MAX && !plan.jobs[j].ok) exit_code = std::max(exit_code, 1);
        }
        progress.finished(sub);
    };
    hooks.reference_failed = [](const Job& job, const std::string& why) {
        std::cerr << "shaderlab: the reference solution of " << job.lab << " did not render (" << why
                  << "); its labs are graded against the stored goldens\n";
    };
    hooks.tick = [&] { progress.tick(); };
    runJobs(&plan, folder, settings, hooks);
    progress.end();

    std::string error;
    if (!writeSummary(folder.out, summaryOf(settings, plan), &error)) {
        std::cerr << "shaderlab: cannot write the summary: " << error << "\n";
        return 2;
    }
    printFigures(settings, plan, started);
    std::printf("summary: %s\n         %s\n", (folder.out / "summary.csv").string().c_str(),
                (folder.out / "summary.json").string().c_str());
    return exit_code;
}

}  // namespace shaderlab::batch
