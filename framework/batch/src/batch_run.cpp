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

// One line per finished submission, or a bar redrawn in place on a terminal that names the
// submissions being graded now (not the last one finished: a lab that runs to its limit would
// leave the bar naming someone else for the whole wait).
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
            draw(running_);
        }
    }
    void tick(const std::string& running) {
        running_ = running;
        if (tty_ && std::chrono::duration<double>(Clock::now() - last_draw_).count() > 0.5) draw(running_);
    }
    void end() {
        if (tty_) std::printf("\n");
    }

  private:
    void draw(const std::string& running) {
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
        std::printf("\r\033[K[%s] %zu/%zu  ETA %s  %s", bar.c_str(), done_, total_, eta, running.c_str());
        std::fflush(stdout);
    }
    std::size_t total_, done_ = 0;
    bool tty_;
    Clock::time_point t0_, last_draw_{};
    std::string running_;
};

// The labs the batch grades, and how many submissions hand each in, before any work: what the
// totals are out of is said at once.
void printClassLabs(const BatchSettings& settings, const Plan& plan) {
    std::string list;
    for (const LabPlan& lab : plan.labs) {
        std::size_t n = 0;
        for (const Submission& sub : plan.subs)
            n += std::count(sub.handed_in.begin(), sub.handed_in.end(), lab.id) > 0 ? 1 : 0;
        list +=
            (list.empty() ? "" : ", ") + lab.id + (settings.labs_named ? "" : " (" + std::to_string(n) + ")");
    }
    if (settings.labs_named)
        std::printf("labs: %s (named with --lab)\n", list.c_str());
    else if (!plan.labs.empty())
        std::printf(
            "labs: %s: those handed in (how many hand each in); totals are out of these. Name the "
            "assignment's labs with --lab to grade exactly those\n",
            list.c_str());
    else
        std::printf("labs: none: no submission hands in a lab's files\n");
    std::fflush(stdout);
}

// The summary of every submission, in the plan's order.
Summary summaryOf(const BatchSettings& settings, const Plan& plan) {
    Summary summary;
    summary.tool_version = settings.tool_version;
    summary.shard = settings.shard;
    summary.labs_named = settings.labs_named;
    for (const LabPlan& lab : plan.labs) summary.labs.push_back(lab.id);
    for (const Submission& sub : plan.subs) summary.rows.push_back(sub.row);
    return summary;
}

// The figures of the run: submissions graded and reused, labs graded by the workers and taken
// from the cache, wall and CPU time.
void printFigures(const BatchSettings& settings, const Plan& plan, Clock::time_point started) {
    std::size_t graded = 0, reused = 0;
    for (const Submission& sub : plan.subs) {
        graded += sub.skipped ? 0 : 1;
        reused += sub.skipped ? 1 : 0;
    }
    std::size_t labs_graded = 0, cached = 0, references = 0;
    std::set<pid_t> workers;  // a worker may have done several jobs
    for (const Job& job : plan.jobs) {
        if (job.pid > 0) workers.insert(job.pid);
        if (job.kind == Job::Reference) {
            references += job.pid > 0 ? 1 : 0;
            continue;
        }
        labs_graded += job.pid > 0 ? 1 : 0;
        cached += job.pid <= 0 && job.ok ? 1 : 0;
    }
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
    // A lab folder is graded once however many submissions hold the same files, and one graded by
    // an earlier run (or by another shard sharing the cache) is taken as it is. "N worker runs" is
    // read by scripts (bench/run_bench.py, tests/slurm): it keeps its form.
    std::printf(
        "%zu submissions (%zu graded, %zu unchanged since their report), %zu worker runs (%zu lab "
        "folders graded, %zu reference solutions rendered), %zu lab folders found graded by an earlier "
        "run; %d jobs at a time; %.1f s wall, %.1f s CPU, %.0f submissions per minute\n",
        plan.subs.size(), graded, reused, workers.size(), labs_graded, references, cached, settings.jobs_max,
        wall, cpu, wall > 0 ? 60.0 * plan.subs.size() / wall : 0.0);
}

}  // namespace

std::string describeRunning(const Plan& plan, Clock::time_point now) {
    std::vector<std::string> names;
    double longest = 0.0;
    std::string longest_name;
    std::set<pid_t> seen;  // a worker grading several labs of a submission is named once
    for (const Job& job : plan.jobs) {
        if (job.done || job.pid <= 0 || !seen.insert(job.pid).second) continue;
        const double s = std::chrono::duration<double>(now - job.started).count();
        const std::string name =
            job.kind == Job::Reference ? "the reference of " + job.lab
            : job.waiting.empty()
                ? job.lab
                : printable(plan.subs[job.waiting.front()].source.student, 30) + " (" + job.lab + ")";
        names.push_back(name);
        if (s > longest) longest = s, longest_name = name;
    }
    if (names.empty()) return {};
    std::string out = "grading ";
    for (std::size_t i = 0; i < names.size() && i < 2; ++i) out += (i ? ", " : "") + names[i];
    if (names.size() > 2) out += " +" + std::to_string(names.size() - 2);
    if (longest >= 10.0) out += "; " + longest_name + " for " + std::to_string(int(longest)) + " s";
    return out;
}

int gradeBatch(const BatchSettings& settings, const ResultsFolder& folder, std::vector<LabPlan> labs,
               const std::vector<SubmissionSource>& sources, Clock::time_point started) {
    Plan plan;
    plan.labs = std::move(labs);
    surveySubmissions(settings, folder, sources, &plan);
    chooseClassLabs(settings, &plan);
    printClassLabs(settings, plan);
    planLabs(settings, folder, &plan);
    planSubmissions(settings, folder, &plan);
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
    hooks.tick = [&] { progress.tick(describeRunning(plan, Clock::now())); };
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
