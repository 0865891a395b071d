// The pool that runs a batch's jobs in worker processes; see schedule.h. It decides what runs
// when and what a worker's end means, and prints nothing: gradeBatch (batch_run.cpp) does.
#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <thread>

#include "shaderlab/base/sanitizer.h"
#include "shaderlab/batch/plan.h"
#include "shaderlab/batch/results.h"
#include "shaderlab/batch/schedule.h"
#include "shaderlab/batch/workers.h"

namespace fs = std::filesystem;

namespace shaderlab::batch {

namespace {

using Clock = std::chrono::steady_clock;

// The pool: references first (grading jobs wait on their lab's), then labs in submission order.
class Pool {
  public:
    Pool(Plan* plan, const ResultsFolder& folder, const BatchSettings& settings, const ScheduleHooks& hooks)
        : labs_(plan->labs),
          jobs_(plan->jobs),
          subs_(plan->subs),
          folder_(folder),
          settings_(settings),
          hooks_(hooks) {}

    void run() {
        for (Submission& sub : subs_)
            if (sub.skipped || ready(sub)) finish(sub);
        for (;;) {
            startJobs();
            if (running_.empty() && !anyDeferred()) break;
            int wstatus = 0;
            const pid_t pid = running_.empty() ? 0 : waitpid(-1, &wstatus, WNOHANG);
            if (pid > 0 && running_.count(pid)) {
                reaped(pid, wstatus);
                continue;
            }
            if (pid < 0 && errno == ECHILD && !anyDeferred()) break;
            for (auto& [p, group] : running_) {
                double watchdog_s = 0.0;  // a worker of several jobs has the time of them all
                for (std::size_t j : group) watchdog_s += jobs_[j].watchdog_s;
                if (std::chrono::duration<double>(Clock::now() - jobs_[group.front()].started).count() >
                    watchdog_s)
                    kill(-p, SIGKILL);  // reaped above as a failed job
            }
            if (hooks_.tick) hooks_.tick();
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
        }
        for (Submission& sub : subs_)
            if (!sub.finished) finish(sub);  // only when a worker could not be started
    }

  private:
    bool ready(const Submission& sub) const {
        for (std::size_t j : sub.jobs)
            if (j != SIZE_MAX && !jobs_[j].done) return false;  // SIZE_MAX: a lab not handed in
        return true;
    }

    void finish(Submission& sub) {
        sub.finished = true;
        if (hooks_.finished) hooks_.finished(sub);
    }

    bool anyDeferred() const {
        for (const Job& job : jobs_)
            if (job.deferred && !job.done) return true;
        return false;
    }

    bool startable(const Job& job) const {
        if (job.done || job.pid > 0) return false;
        if (job.deferred && Clock::now() < job.retry_at) return false;
        if (job.kind == Job::Grade)
            for (const LabPlan& lab : labs_)
                if (lab.id == job.lab && lab.ref_job != SIZE_MAX && !jobs_[lab.ref_job].done) return false;
        return true;
    }

    void complete(std::size_t j, bool ok, const std::string& why) {
        Job& job = jobs_[j];
        if (job.claim_fd >= 0) {
            // Landed: the lock file has done its work. A batch waiting on it opens the path anew
            // (or holds the old file) and finds the result either way.
            if (ok) unlink((job.final_dir + ".lock").c_str());
            close(job.claim_fd);
            job.claim_fd = -1;
        }
        job.done = true;
        job.ok = ok;
        job.error = why;
        if (job.kind == Job::Reference && !ok) {
            if (hooks_.reference_failed) hooks_.reference_failed(job, why);
            for (LabPlan& lab : labs_)
                if (lab.id == job.lab) lab.goldens_root.clear();
        }
        for (std::size_t s : job.waiting)
            if (!subs_[s].finished && ready(subs_[s])) finish(subs_[s]);
    }

    // Starts the first startable jobs until jobs_max run.
    void startJobs() {
        while (static_cast<int>(running_.size()) < settings_.jobs_max) {
            std::size_t pick = SIZE_MAX;
            for (std::size_t j = next_; j < jobs_.size(); ++j)
                if (startable(jobs_[j])) {
                    pick = j;
                    break;
                }
            if (pick == SIZE_MAX) break;
            start(pick);
        }
    }

    // A grading job of a lab whose reference failed goes against the goldens. Its result is
    // kept apart, so that a later run with the reference grades it again.
    void useGoldensIfNeeded(Job& job) {
        if (job.kind != Job::Grade) return;
        for (const LabPlan& lab : labs_) {
            auto g = std::find(job.argv.begin(), job.argv.end(), "--goldens");
            if (lab.id != job.lab || !lab.goldens_root.empty() || g == job.argv.end()) continue;
            job.argv.erase(g, g + 2);
            job.final_dir += "-goldens";
            *(std::find(job.argv.begin(), job.argv.end(), "--out") + 1) = job.final_dir;
        }
    }

    static std::string argument(const Job& job, const char* flag) {
        const auto it = std::find(job.argv.begin(), job.argv.end(), flag);
        return it != job.argv.end() && it + 1 != job.argv.end() ? *(it + 1) : std::string();
    }

    // Claims the job and tells whether it is still to be run: false when another batch holds it
    // (tried later) or made it since the plan (done).
    bool take(std::size_t j) {
        Job& job = jobs_[j];
        useGoldensIfNeeded(job);
        if (!claim(job)) return false;
        if (landed(job)) {  // another batch sharing the cache made it since the plan
            complete(j, true, "");
            return false;
        }
        return true;
    }

    // The grading jobs of the same submission that one worker takes with `pick`: their labs are
    // drawn by one render child, which saves a process, a GL context and a driver start per lab.
    // At most a share of what is left to start per worker, so that the workers stay busy.
    std::vector<std::size_t> groupOf(std::size_t pick) {
        std::vector<std::size_t> group = {pick};
        const Job& first = jobs_[pick];
        if (first.kind != Job::Grade) return group;
        const std::string submission = argument(first, "--submission");
        std::size_t left = 0;
        for (const Job& job : jobs_) left += job.kind == Job::Grade && !job.done && job.pid <= 0;
        const std::size_t most =
            std::max<std::size_t>(1, left / static_cast<std::size_t>(settings_.jobs_max));
        for (std::size_t j = pick + 1; j < jobs_.size() && group.size() < most; ++j) {
            const Job& job = jobs_[j];
            if (job.kind != Job::Grade || !startable(job) || argument(job, "--submission") != submission)
                continue;
            if (take(j)) group.push_back(j);
        }
        return group;
    }

    void start(std::size_t pick) {
        if (!take(pick)) return;
        const std::vector<std::size_t> group = groupOf(pick);
        Job& job = jobs_[pick];
        std::vector<std::string> argv = job.argv;
        for (std::size_t k = 1; k < group.size(); ++k) {
            const Job& more = jobs_[group[k]];
            for (const std::string& value : {more.lab, more.final_dir, argument(more, "--goldens")}) {
                argv.push_back("--also");
                argv.push_back(value);
            }
        }
        const std::string log = (folder_.state / "logs" /
                                 ((job.kind == Job::Reference ? "reference-" : "grade-") + job.lab + "-" +
                                  fs::path(job.final_dir).filename().string() + ".log"))
                                    .string();
        // The render child below the worker watches its resident memory against `memory` and
        // caps its address space at 4 GiB more (isolated_render.cpp); the worker gets the same cap.
        // Not under AddressSanitizer, whose shadow memory reserves terabytes of address space
        // (the render child's resident-memory watch still holds there).
        // SHADERLAB_WORKER_ADDRESS_SPACE (a size such as 64M) replaces that cap, also under
        // ASan: for machines whose driver reserves more, and for the test of a worker that dies
        // (an ASan worker under such a cap dies at its start, which that test wants).
        std::size_t worker_as = SHADERLAB_ASAN ? 0 : settings_.memory + (std::size_t(4) << 30);
        if (const char* env = std::getenv("SHADERLAB_WORKER_ADDRESS_SPACE")) parseMemory(env, &worker_as, 1);
        const Spawned s = spawnWorker(argv, log, worker_as);
        for (std::size_t j : group) jobs_[j].log = log;
        if (s.pid < 0) {
            for (std::size_t j : group) complete(j, false, s.error);
            return;
        }
        for (std::size_t j : group) {
            jobs_[j].pid = s.pid;
            jobs_[j].started = Clock::now();
        }
        running_[s.pid] = group;
        while (next_ < jobs_.size() && (jobs_[next_].done || jobs_[next_].pid > 0)) ++next_;
    }

    static bool landed(const Job& job) {
        std::error_code ec;
        return fs::exists(
            job.kind == Job::Grade ? fs::path(job.final_dir) / "report.json" : fs::path(job.final_dir), ec);
    }

    // Takes the job's lock file (<final_dir>.lock, flock) so that batches sharing the cache run it
    // once. false when another holds it: the job is tried again a little later, and run anyway
    // once it has waited longer than its watchdog (the other batch may be stopped for good).
    bool claim(Job& job) {
        std::error_code ec;
        fs::create_directories(fs::path(job.final_dir).parent_path(), ec);
        const int fd =
            open((job.final_dir + ".lock").c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
        if (fd >= 0 && flock(fd, LOCK_EX | LOCK_NB) == 0) {
            job.claim_fd = fd;
            job.deferred = false;
            return true;
        }
        const bool busy = fd >= 0 && errno == EWOULDBLOCK;
        if (fd >= 0) close(fd);
        const Clock::time_point now = Clock::now();
        if (!busy) return true;  // no lock to be had (a read-only cache): run it
        if (!job.deferred) job.deferred_since = now;
        if (std::chrono::duration<double>(now - job.deferred_since).count() > job.watchdog_s) {
            job.deferred = false;
            return true;
        }
        job.deferred = true;
        job.retry_at = now + std::chrono::milliseconds(100);
        return false;
    }

    // The worker `pid` ended: each of its jobs is done when its result landed. A worker that
    // failed fails the first job it had not landed, the one it was doing; the jobs after that
    // one go back to the pool, to be run again.
    void reaped(pid_t pid, int wstatus) {
        const std::vector<std::size_t> group = running_[pid];
        running_.erase(pid);
        forgetWorker(pid);
        kill(-pid, SIGKILL);  // anything the worker left in its group
        const bool exited_ok = WIFEXITED(wstatus) && WEXITSTATUS(wstatus) == 0;
        bool failed_one = false;
        for (std::size_t j : group) {
            Job& job = jobs_[j];
            if (landed(job)) {
                complete(j, true, "");
            } else if (!failed_one || exited_ok) {
                failed_one = true;
                complete(j, false, describeExit(wstatus) + lastLogLine(job.log));
            } else {
                job.pid = -1;
                if (job.claim_fd >= 0) close(job.claim_fd);
                job.claim_fd = -1;
                next_ = std::min(next_, j);
            }
        }
    }

    std::vector<LabPlan>& labs_;
    std::vector<Job>& jobs_;
    std::vector<Submission>& subs_;
    const ResultsFolder& folder_;
    const BatchSettings& settings_;
    const ScheduleHooks& hooks_;
    std::map<pid_t, std::vector<std::size_t>> running_;  // a worker's jobs, in the order it does them
    std::size_t next_ = 0;
};

}  // namespace

void runJobs(Plan* plan, const ResultsFolder& folder, const BatchSettings& settings,
             const ScheduleHooks& hooks) {
    Pool(plan, folder, settings, hooks).run();
}

}  // namespace shaderlab::batch
