// `shaderlab batch` (grade every submission of a folder), its worker, and `shaderlab merge`.
//
// The batch process never renders and never holds a GL context. It unpacks and hashes the
// submissions, then runs one worker process (`shaderlab batch-worker`, this same program) per
// lab to grade, at most --jobs at a time. Each worker is its own process group, dies with the
// batch (PR_SET_PDEATHSIG) and renders in a child of its own (renderLabIsolated) with the time
// and memory limits. What a worker made lands in the results folder under .shaderlab/ with one
// rename, keyed by a hash of everything it depends on, so that:
//   - the reference solution of a lab is rendered once, then taken from the cache;
//   - a lab folder that several students submitted unchanged (the starter code) is graded once;
//   - a batch killed half-way and run again grades only what is missing, and a submission whose
//     content and settings did not change since its report is skipped.
// See docs/instructors.md.
#include <fcntl.h>
#include <sched.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <thread>

#include "commands.h"
#include "grader/reports/report.h"
#include "shaderlab/batch/batch.h"
#include "shaderlab/gl/gl_context.h"
#include "shaderlab/grading/grading.h"
#include "shaderlab/lab/lab_catalog.h"
#include "shaderlab/lab/lab_spec.h"
#include "shaderlab/base/sanitizer.h"

namespace fs = std::filesystem;

namespace shaderlab::cli {

namespace {

using Clock = std::chrono::steady_clock;

constexpr const char* kStateDir = ".shaderlab";  // inside the results folder

std::string readText(const fs::path& p, std::size_t max_bytes = 64u << 20) {
    std::ifstream in(p, std::ios::binary);
    if (!in) return {};
    std::string s;
    char buf[1 << 16];
    while (s.size() < max_bytes && in.read(buf, sizeof buf).gcount() > 0)
        s.append(buf, static_cast<std::size_t>(in.gcount()));
    if (s.size() > max_bytes) s.resize(max_bytes);
    return s;
}

bool parseMemory(const std::string& text, std::size_t* bytes, std::size_t minimum = std::size_t(64) << 20) {
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (!end || end == text.c_str() || !(v > 0)) return false;
    std::string unit(end);
    double scale = 1.0;
    if (unit == "K" || unit == "KiB")
        scale = 1024.0;
    else if (unit == "M" || unit == "MiB" || unit.empty())
        scale = 1024.0 * 1024.0;
    else if (unit == "G" || unit == "GiB")
        scale = 1024.0 * 1024.0 * 1024.0;
    else
        return false;
    *bytes = static_cast<std::size_t>(v * scale);
    return *bytes >= minimum;
}

std::string defaultReferenceRootOf(const std::string& labs_root) {
    const fs::path p = fs::path(labs_root).parent_path() / "reference_solutions";
    std::error_code ec;
    return fs::is_directory(p, ec) ? p.string() : std::string();
}

std::string selfExe() {
    std::error_code ec;
    const fs::path p = fs::read_symlink("/proc/self/exe", ec);
    return ec ? std::string("/proc/self/exe") : p.string();
}

// Replaces every occurrence of `from` in `s` by `to`.
void replaceAll(std::string* s, const std::string& from, const std::string& to) {
    if (from.empty()) return;
    for (std::size_t at = s->find(from); at != std::string::npos; at = s->find(from, at + to.size()))
        s->replace(at, from.size(), to);
}

// ---- worker processes ---------------------------------------------------------------------------

// The workers in flight, for the signal handler: a batch stopped by SIGINT or SIGTERM takes
// every worker's process group (worker and render child) along. SIGKILL cannot be caught;
// PR_SET_PDEATHSIG does that part.
constexpr int kMaxWorkers = 256;
volatile sig_atomic_t g_workers[kMaxWorkers] = {};

void killWorkersAndDie(int sig) {
    for (int i = 0; i < kMaxWorkers; ++i)
        if (g_workers[i] > 0) kill(-static_cast<pid_t>(g_workers[i]), SIGKILL);
    signal(sig, SIG_DFL);
    raise(sig);
}

struct Spawned {
    pid_t pid = -1;
    std::string error;
};

// Starts `argv` as a worker: its own process group, killed when this process dies, stdin from
// /dev/null, stdout and stderr into `log`, address space limited to `memory` bytes (0: unlimited).
Spawned spawnWorker(const std::vector<std::string>& argv, const std::string& log, std::size_t memory) {
    std::vector<char*> cargv;
    for (const std::string& a : argv) cargv.push_back(const_cast<char*>(a.c_str()));
    cargv.push_back(nullptr);
    std::fflush(nullptr);
    const pid_t parent = getpid();
    const pid_t pid = fork();
    if (pid < 0) return {-1, std::string("fork failed: ") + std::strerror(errno)};
    if (pid == 0) {
        setpgid(0, 0);
        prctl(PR_SET_PDEATHSIG, SIGKILL);
        if (getppid() != parent) _exit(127);  // the batch died before the line above
        for (int sig : {SIGINT, SIGTERM, SIGHUP}) signal(sig, SIG_DFL);
        if (memory > 0) {
            rlimit as{};
            as.rlim_cur = as.rlim_max = memory;
            setrlimit(RLIMIT_AS, &as);
        }
        rlimit core{};
        setrlimit(RLIMIT_CORE, &core);
        const int in = open("/dev/null", O_RDONLY);
        const int out = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW, 0644);
        if (in >= 0) dup2(in, STDIN_FILENO);
        if (out >= 0) {
            dup2(out, STDOUT_FILENO);
            dup2(out, STDERR_FILENO);
        }
        execv(cargv[0], cargv.data());
        _exit(127);
    }
    setpgid(pid, pid);  // also here, so that a kill of the group right away finds it
    for (int i = 0; i < kMaxWorkers; ++i)
        if (g_workers[i] == 0) {
            g_workers[i] = pid;
            break;
        }
    return {pid, {}};
}

void forgetWorker(pid_t pid) {
    for (int i = 0; i < kMaxWorkers; ++i)
        if (g_workers[i] == pid) g_workers[i] = 0;
}

std::string describeExit(int wstatus) {
    if (WIFSIGNALED(wstatus))
        return std::string("killed by signal ") + std::to_string(WTERMSIG(wstatus)) + " (" +
               strsignal(WTERMSIG(wstatus)) + ")";
    return "exit code " + std::to_string(WEXITSTATUS(wstatus));
}

// ": <the last line of a worker's log>; log: <path>", for the message of a worker that failed.
std::string lastLogLine(const std::string& log) {
    std::istringstream in(readText(log, 1u << 20));
    std::string line, last;
    while (std::getline(in, line))
        if (!line.empty()) last = line;
    return (last.empty() ? std::string() : ": " + batch::printable(last, 300)) + "; log: " + log;
}

// The GL renderer a worker would see, for the reference cache key: `shaderlab info`, in a child.
std::string probeRenderer(const std::string& exe, const std::string& backend, const fs::path& log) {
    // No address-space cap under AddressSanitizer (see runBatch).
    const Spawned s = spawnWorker({exe, "info", "--backend", backend}, log.string(),
                                  SHADERLAB_ASAN ? 0 : std::size_t(8) << 30);
    if (s.pid < 0) return {};
    int wstatus = 0;
    while (waitpid(s.pid, &wstatus, 0) < 0 && errno == EINTR) {
    }
    forgetWorker(s.pid);
    std::istringstream in(readText(log));
    std::string line, renderer;
    while (std::getline(in, line))
        if (line.rfind("renderer:", 0) == 0 || line.rfind("version:", 0) == 0) renderer += line + "\n";
    return renderer;
}

// ---- the plan -----------------------------------------------------------------------------------

// One unit of work for a worker: a reference render into the cache, or one lab of one
// submission folder. Identical units are one job.
struct Job {
    enum Kind { Reference, Grade } kind = Grade;
    std::string lab;
    std::string final_dir;  // where its result lands (a rename of final_dir + ".tmp-<pid>")
    std::vector<std::string> argv;
    pid_t pid = -1;
    Clock::time_point started;
    double watchdog_s = 0.0;
    bool done = false, ok = false;
    std::string error;
    std::string log;                   // its stdout and stderr
    std::vector<std::size_t> waiting;  // submissions
};

struct LabPlan {
    std::string id;
    std::string title;
    double max_score = 0.0;
    std::string key;           // hash of what its grading depends on, besides the student's files
    std::string goldens_root;  // reference cache entry; empty: the lab's own goldens
    std::size_t ref_job = SIZE_MAX;
};

struct Submission {
    batch::SubmissionSource source;
    std::string folder_name;  // its report folder below the results
    std::string key;          // content + settings
    std::string root;         // the folder graded (unpacked and unwrapped)
    std::string status = "graded";
    std::string message;
    bool skipped = false;  // unchanged since its report
    bool finished = false;
    std::vector<std::size_t> jobs;  // per lab (SIZE_MAX: not graded)
    batch::SummaryRow row;
};

class Progress {
  public:
    explicit Progress(std::size_t total) : total_(total), tty_(isatty(STDOUT_FILENO)), t0_(Clock::now()) {}
    void finished(const Submission& s) {
        ++done_;
        if (!tty_) {
            std::printf("[%zu/%zu] %s: %s %.2f / %.2f\n", done_, total_,
                        batch::printable(s.row.student, 80).c_str(),
                        s.skipped ? "unchanged," : s.row.status.c_str(), s.row.total, s.row.max_total);
            std::fflush(stdout);
        } else {
            draw(batch::printable(s.row.student, 30));
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

// The cores this process may run on (a Slurm task or a container may get fewer than the machine has).
int usableCores() {
    cpu_set_t set;
    CPU_ZERO(&set);
    if (sched_getaffinity(0, sizeof set, &set) == 0 && CPU_COUNT(&set) > 0) return CPU_COUNT(&set);
    return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

bool reservedName(const std::string& name) { return name == "summary.csv" || name == "summary.json"; }

// The report of one submission, from its labs' results.
grader::Report assembleReport(const Submission& sub, const std::vector<LabPlan>& labs,
                              const std::vector<Job>& jobs, const std::string& backend) {
    grader::Report report;
    report.tool_version = SHADERLAB_VERSION;
    report.submission = sub.source.path;
    report.backend = backend;
    for (std::size_t i = 0; i < labs.size(); ++i) {
        grader::ReportLab lab;
        lab.id = labs[i].id;
        lab.title = labs[i].title;
        lab.max_score = labs[i].max_score;
        const std::size_t j = sub.jobs.empty() ? SIZE_MAX : sub.jobs[i];
        if (j == SIZE_MAX) {
            lab.status = "missing";
            lab.message = sub.message;
        } else if (!jobs[j].ok) {
            lab.status = "crashed";
            lab.message = "the grading process stopped (" + jobs[j].error +
                          "): not the submission's fault; the next run of the batch grades it again (a "
                          "--memory too small for the program itself?)";
        } else {
            grader::Report one;
            std::string err;
            if (!grader::reportFromJson(readText(fs::path(jobs[j].final_dir) / "report.json"), &one, &err) ||
                one.labs.size() != 1) {
                lab.status = "crashed";
                lab.message = "the lab's result cannot be read: " + err;
            } else {
                lab = one.labs[0];
                if (!one.renderer.empty()) report.renderer = one.renderer;
                // The lab was graded in the folder of the first submission that had it: say this one.
                replaceAll(&lab.message, one.submission, sub.root);
                for (grader::ReportDiagnostic& d : lab.diagnostics)
                    replaceAll(&d.message, one.submission, sub.root);
                lab.folder = (fs::path(sub.root) / lab.id).lexically_normal().string();
            }
        }
        report.score += lab.score;
        report.max_score += lab.max_score;
        report.labs.push_back(std::move(lab));
    }
    return report;
}

batch::SummaryRow rowOf(const Submission& sub, const grader::Report& report) {
    batch::SummaryRow row;
    row.student = sub.source.student;
    row.source = sub.source.path;
    row.status = sub.status;
    row.message = sub.message;
    row.total = report.score;
    row.max_total = report.max_score;
    row.report = sub.folder_name + "/report.json";
    for (const grader::ReportLab& lab : report.labs)
        row.labs.push_back({lab.id, lab.score, lab.max_score, sub.status == "graded" ? lab.status : ""});
    return row;
}

// Writes the submission's report folder: built beside, then swapped in with renames.
bool writeSubmission(Submission* sub, const grader::Report& report, const std::vector<LabPlan>& labs,
                     const std::vector<Job>& jobs, const fs::path& out, const fs::path& state,
                     const std::vector<std::string>& formats, std::string* error) {
    const fs::path tmp = state / "tmp" / (sub->folder_name + ".new-" + std::to_string(getpid()));
    std::error_code ec;
    fs::remove_all(tmp, ec);
    fs::create_directories(tmp, ec);
    if (ec) {
        *error = tmp.string() + ": " + ec.message();
        return false;
    }
    for (std::size_t i = 0; i < labs.size() && !sub->jobs.empty(); ++i) {
        const std::size_t j = sub->jobs[i];
        if (j == SIZE_MAX || !jobs[j].ok) continue;
        const fs::path images = fs::path(jobs[j].final_dir) / labs[i].id;
        if (fs::is_directory(images, ec) &&
            !batch::linkTree(images.string(), (tmp / labs[i].id).string(), error))
            return false;
    }
    bool ok =
        batch::writeFileAtomically((tmp / "report.json").string(), grader::reportToJson(report), error) &&
        batch::writeFileAtomically((tmp / "report.html").string(),
                                   grader::reportToHtml(report, {tmp.string(), 20u << 20}), error);
    for (const std::string& f : formats) {
        if (ok && f == "gradescope")
            ok = batch::writeFileAtomically((tmp / "results.json").string(),
                                            grader::reportToGradescope(report, {tmp.string(), 2u << 20}),
                                            error);
        if (ok && f == "junit")
            ok = batch::writeFileAtomically((tmp / "report.junit.xml").string(),
                                            grader::reportToJunit(report), error);
    }
    sub->row = rowOf(*sub, report);
    // batch.json last: a report folder without it is redone on the next run, and so is one where a
    // worker failed (our fault, perhaps passing: the next run tries again).
    bool complete = true;
    for (std::size_t j : sub->jobs) complete = complete && j != SIZE_MAX && jobs[j].ok;
    ok = ok && (!complete || batch::writeFileAtomically((tmp / "batch.json").string(),
                                                        "{\"key\": \"" + sub->key + "\", \"row\": " +
                                                            batch::summaryRowToJson(sub->row) + "}\n",
                                                        error));
    if (!ok) return false;
    const fs::path dest = out / sub->folder_name;
    const fs::path old = state / "tmp" / (sub->folder_name + ".old-" + std::to_string(getpid()));
    fs::remove_all(old, ec);
    if (fs::exists(fs::symlink_status(dest, ec))) {
        fs::rename(dest, old, ec);  // a symlink planted there is moved away, never followed
        if (ec) {
            *error = dest.string() + ": cannot replace it: " + ec.message();
            return false;
        }
    }
    fs::rename(tmp, dest, ec);
    if (ec) {
        *error = dest.string() + ": " + ec.message();
        return false;
    }
    fs::remove_all(old, ec);
    return true;
}

// What a finished report folder says about itself, when its key is `key`.
bool unchangedSince(const fs::path& folder, const std::string& key, batch::SummaryRow* row) {
    std::error_code ec;
    if (fs::is_symlink(folder, ec) || !fs::is_regular_file(folder / "report.json", ec)) return false;
    const std::string text = readText(folder / "batch.json", 1u << 20);
    const std::string marker = "{\"key\": \"" + key + "\", \"row\": ";
    if (text.compare(0, marker.size(), marker) != 0 || text.size() < marker.size() + 2) return false;
    std::string rest = text.substr(marker.size());
    while (!rest.empty() && (rest.back() == '\n' || rest.back() == ' ')) rest.pop_back();
    if (rest.empty() || rest.back() != '}') return false;
    rest.pop_back();
    return batch::summaryRowFromJson(rest, row);
}

bool parseShard(const std::string& text, int* k, int* n) {
    if (text.empty()) {
        *k = 1;
        *n = 1;
        return true;
    }
    char extra = 0;
    return std::sscanf(text.c_str(), "%d/%d%c", k, n, &extra) == 2 && *n >= 1 && *k >= 1 && *k <= *n;
}

// Removes what an interrupted run left half-made under the state folder.
void removeLeftovers(const fs::path& state) {
    std::error_code ec;
    fs::remove_all(state / "tmp", ec);
    for (const char* sub : {"labs", "references", "work"}) {
        std::vector<fs::path> stale;
        for (fs::recursive_directory_iterator it(state / sub, ec), end; !ec && it != end; it.increment(ec)) {
            if (it->path().filename().string().find(".tmp-") != std::string::npos) {
                stale.push_back(it->path());
                it.disable_recursion_pending();
            } else if (it.depth() >= 1) {
                it.disable_recursion_pending();
            }
        }
        for (const fs::path& p : stale) fs::remove_all(p, ec);
    }
    fs::create_directories(state / "tmp", ec);
}

}  // namespace

int runBatch(const BatchArgs& args) {
    const auto t_start = Clock::now();
    // Mesa's on-disk shader cache stays off in every worker (inherited); see gl_context.h.
    setenv("MESA_SHADER_CACHE_DISABLE", "true", 0);

    std::string labs_root;
    if (!resolveLabsRoot(args.common, &labs_root)) return 2;
    const std::vector<std::string> all_ids = listLabIds(labs_root);
    const std::vector<std::string> ids = args.common.labs.empty() ? all_ids : args.common.labs;
    if (ids.empty()) {
        std::cerr << "shaderlab: no labs found in " << labs_root << "\n";
        return 2;
    }
    std::vector<LabPlan> labs;
    for (const std::string& id : ids) {
        const LabSpecResult parsed = parseLabSpec((fs::path(labs_root) / id).string());
        for (const std::string& e : parsed.errors) std::cerr << e << "\n";
        if (!parsed.ok) return 2;
        LabPlan lab;
        lab.id = id;
        lab.title = parsed.spec.title;
        lab.max_score = parsed.spec.grading.points;
        labs.push_back(lab);
    }
    std::size_t memory = 0;
    if (!parseMemory(args.memory, &memory)) {
        std::cerr << "shaderlab: --memory " << args.memory
                  << ": expected a size such as 4G or 2048M (64M at least)\n";
        return 2;
    }
    int shard_k = 1, shard_n = 1;
    if (!parseShard(args.shard, &shard_k, &shard_n)) {
        std::cerr << "shaderlab: --shard " << args.shard << ": expected K/N with 1 <= K <= N, e.g. 2/8\n";
        return 2;
    }
    std::error_code ec;
    if (!fs::is_directory(args.submissions_dir, ec)) {
        std::cerr << "shaderlab: " << args.submissions_dir << ": submissions folder not found\n";
        return 2;
    }
    std::string error;
    std::vector<batch::SubmissionSource> sources = batch::listSubmissions(args.submissions_dir, &error);
    if (!error.empty()) {
        std::cerr << "shaderlab: " << error << "\n";
        return 2;
    }
    // The results folder, when it lies in the submissions folder, is not a submission.
    {
        const fs::path out_canonical = fs::weakly_canonical(args.out_dir, ec);
        sources.erase(std::remove_if(sources.begin(), sources.end(),
                                     [&](const batch::SubmissionSource& s) {
                                         std::error_code e;
                                         return fs::weakly_canonical(s.path, e) == out_canonical;
                                     }),
                      sources.end());
    }
    // Every K-th of the sorted list: shards of a job array take their share without talking.
    {
        std::vector<batch::SubmissionSource> mine;
        for (std::size_t i = 0; i < sources.size(); ++i)
            if (static_cast<int>(i % static_cast<std::size_t>(shard_n)) == shard_k - 1)
                mine.push_back(sources[i]);
        sources.swap(mine);
    }

    // The results folder: made, writable and ours alone before any work.
    const fs::path out = fs::absolute(args.out_dir, ec).lexically_normal();
    fs::create_directories(out, ec);
    if (!fs::is_directory(out, ec) ||
        !batch::writeFileAtomically((out / ".shaderlab-write-test").string(), "ok\n", &error)) {
        std::cerr << "shaderlab: " << out.string() << ": cannot write the results there"
                  << (error.empty() ? "" : ": " + error) << "\n";
        return 2;
    }
    fs::remove(out / ".shaderlab-write-test", ec);
    const fs::path state = out / kStateDir;
    if (fs::is_symlink(state, ec)) {  // everything of ours goes in there: it must be ours
        std::cerr << "shaderlab: " << state.string() << " is a symlink; remove it\n";
        return 2;
    }
    fs::create_directories(state, ec);
    batch::FolderLock lock;
    if (!lock.acquire((state / "lock").string(), &error)) {
        std::cerr << "shaderlab: " << out.string() << ": " << error << "\n";
        return 2;
    }
    removeLeftovers(state);
    const fs::path cache = args.cache_dir.empty() ? state / "references" : fs::absolute(args.cache_dir, ec);
    fs::create_directories(cache, ec);
    fs::create_directories(state / "labs", ec);
    fs::create_directories(state / "work", ec);
    fs::create_directories(state / "logs", ec);

    for (int sig : {SIGINT, SIGTERM, SIGHUP}) signal(sig, killWorkersAndDie);
    const std::string exe = selfExe();
    const std::string renderer = probeRenderer(exe, args.common.backend, state / "logs" / "renderer.log");
    if (renderer.empty()) {
        std::cerr << "shaderlab: no OpenGL context with backend " << args.common.backend << ": see "
                  << (state / "logs" / "renderer.log").string() << "\n";
        return 2;
    }
    const std::string reference_root =
        args.no_reference ? std::string()
                          : (args.reference_root.empty() ? defaultReferenceRootOf(labs_root)
                                                         : fs::absolute(args.reference_root, ec).string());
    const int jobs_max = std::max(1, std::min(kMaxWorkers, args.jobs > 0 ? args.jobs : usableCores()));
    char timeout_text[32], compile_timeout_text[32];
    std::snprintf(timeout_text, sizeof timeout_text, "%g", args.timeout_s);
    std::snprintf(compile_timeout_text, sizeof compile_timeout_text, "%g", args.compile_timeout_s);

    // Keys. A lab's: the program, the driver, the lab folder (lab.json, scenes, hints, goldens),
    // the shared folders beside the labs, its reference solution, and the limits.
    std::vector<std::string> shared_dirs;
    for (const fs::directory_entry& e : fs::directory_iterator(labs_root, ec))
        if (e.is_directory(ec) &&
            std::find(all_ids.begin(), all_ids.end(), e.path().filename().string()) == all_ids.end())
            shared_dirs.push_back(e.path().string());
    std::sort(shared_dirs.begin(), shared_dirs.end());
    std::vector<Job> jobs;
    for (LabPlan& lab : labs) {
        const bool has_reference =
            !reference_root.empty() && fs::is_directory(fs::path(reference_root) / lab.id, ec);
        batch::Hasher ref;
        ref.add(std::string(SHADERLAB_VERSION));
        ref.add(args.common.backend);
        ref.add(renderer);
        ref.add(lab.id);
        ref.addTree((fs::path(labs_root) / lab.id).string(), labs_root,
                    has_reference ? std::vector<std::string>{"golden"} : std::vector<std::string>{});
        for (const std::string& d : shared_dirs) ref.addTree(d, labs_root);
        if (has_reference) {
            ref.add("reference");
            ref.addTree((fs::path(reference_root) / lab.id).string(), reference_root);
            lab.goldens_root = (cache / (lab.id + "-" + ref.hex())).string();
            if (!fs::is_directory(lab.goldens_root, ec)) {
                Job job;
                job.kind = Job::Reference;
                job.lab = lab.id;
                job.final_dir = lab.goldens_root;
                job.watchdog_s = 1800.0;
                job.argv = {exe,       "batch-worker",   "--mode",    "reference",        "--labs",
                            labs_root, "--lab",          lab.id,      "--reference",      reference_root,
                            "--out",   lab.goldens_root, "--backend", args.common.backend};
                lab.ref_job = jobs.size();
                jobs.push_back(job);
            }
        }
        ref.add(timeout_text);
        ref.add(compile_timeout_text);
        ref.addNumber(memory);
        lab.key = ref.hex();
    }

    // The submissions: unchanged ones skipped, zips unpacked, every lab folder hashed.
    std::vector<Submission> subs;
    std::map<std::string, std::size_t> job_of;  // lab/hash -> job
    for (const batch::SubmissionSource& source : sources) {
        Submission sub;
        sub.source = source;
        sub.folder_name = reservedName(source.student) ? source.student + "-submission" : source.student;
        batch::Hasher key;
        key.add(std::string(SHADERLAB_VERSION));
        if (source.is_zip)
            key.addFile(source.path);
        else
            key.addTree(source.path, source.path);
        for (const LabPlan& lab : labs) key.add(lab.key);
        for (const std::string& f : args.formats) key.add(f);
        sub.key = key.hex();
        if (unchangedSince(out / sub.folder_name, sub.key, &sub.row)) {
            sub.skipped = true;
            subs.push_back(std::move(sub));
            continue;
        }
        sub.root = source.path;
        if (source.is_zip) {
            const fs::path into = state / "work" / (sub.folder_name + "-" + sub.key);
            if (!fs::is_directory(into, ec)) {
                const fs::path tmp = into.string() + ".tmp-" + std::to_string(getpid());
                fs::remove_all(tmp, ec);
                batch::ArchiveLimits limits;
                limits.max_total_bytes = args.max_unpacked_mib << 20;
                const batch::ExtractResult x = batch::extractZip(source.path, tmp.string(), limits);
                if (x.status != "ok") {
                    sub.status = x.status;
                    sub.message = fs::path(source.path).filename().string() + ": " + x.message;
                    fs::remove_all(tmp, ec);
                } else {
                    fs::rename(tmp, into, ec);
                }
            }
            sub.root = into.string();
        }
        if (sub.status == "graded") {
            sub.root = batch::unwrapSubmissionRoot(sub.root, all_ids);
            bool any = false;
            for (const std::string& id : all_ids) any = any || fs::is_directory(fs::path(sub.root) / id, ec);
            if (!any) {
                sub.status = "empty";
                sub.message = "no lab folder (such as " + all_ids.front() +
                              "/) in the submission; it holds " + batch::describeFolder(sub.root);
            }
        }
        if (sub.status == "graded") {
            for (std::size_t i = 0; i < labs.size(); ++i) {
                const LabPlan& lab = labs[i];
                const fs::path folder = fs::path(sub.root) / lab.id;
                batch::Hasher h;
                h.add(lab.key);
                // A symlinked lab folder is not entered (it may point anywhere); the render decides
                // what of it lies inside the submission.
                if (fs::is_symlink(folder, ec))
                    h.add("link " + fs::read_symlink(folder, ec).string());
                else if (fs::is_directory(folder, ec))
                    h.addTree(folder.string(), sub.root);
                else
                    h.add("absent");
                const std::string id = lab.id + "/" + h.hex();
                auto it = job_of.find(id);
                if (it == job_of.end()) {
                    Job job;
                    job.lab = lab.id;
                    job.final_dir = (state / "labs" / lab.id / h.hex()).string();
                    job.watchdog_s = 2.0 * args.timeout_s + 300.0;
                    job.argv = {exe,
                                "batch-worker",
                                "--mode",
                                "grade",
                                "--labs",
                                labs_root,
                                "--lab",
                                lab.id,
                                "--submission",
                                sub.root,
                                "--out",
                                job.final_dir,
                                "--backend",
                                args.common.backend,
                                "--timeout",
                                timeout_text,
                                "--compile-timeout",
                                compile_timeout_text,
                                "--memory",
                                std::to_string(memory >> 20) + "M"};
                    if (!lab.goldens_root.empty()) {
                        job.argv.push_back("--goldens");
                        job.argv.push_back(lab.goldens_root);
                    }
                    if (fs::is_regular_file(fs::path(job.final_dir) / "report.json", ec))
                        job.done = job.ok = true;
                    it = job_of.emplace(id, jobs.size()).first;
                    jobs.push_back(job);
                }
                jobs[it->second].waiting.push_back(subs.size());
                sub.jobs.push_back(it->second);
            }
        }
        subs.push_back(std::move(sub));
    }

    // Zips unpacked for an earlier version of a submission are of no use any more (shards have
    // results folders of their own, so every submission of this folder is in this list).
    {
        std::set<std::string> current;
        for (const Submission& sub : subs)
            if (sub.source.is_zip) current.insert(sub.folder_name + "-" + sub.key);
        std::vector<fs::path> stale;
        for (const fs::directory_entry& e : fs::directory_iterator(state / "work", ec))
            if (!current.count(e.path().filename().string())) stale.push_back(e.path());
        for (const fs::path& p : stale) fs::remove_all(p, ec);
    }

    Progress progress(subs.size());
    int exit_code = 0;
    auto finishSubmission = [&](Submission& sub) {
        sub.finished = true;
        if (!sub.skipped) {
            const grader::Report report = assembleReport(sub, labs, jobs, args.common.backend);
            std::string err;
            if (!writeSubmission(&sub, report, labs, jobs, out, state, args.formats, &err)) {
                std::cerr << "shaderlab: " << batch::printable(sub.source.student)
                          << ": cannot write the report: " << err << "\n";
                exit_code = 2;
            }
            for (std::size_t j : sub.jobs)
                if (j != SIZE_MAX && !jobs[j].ok) exit_code = std::max(exit_code, 1);
        }
        progress.finished(sub);
    };
    auto subReady = [&](const Submission& sub) {
        for (std::size_t j : sub.jobs)
            if (!jobs[j].done) return false;
        return true;
    };
    for (Submission& sub : subs)
        if (sub.skipped || subReady(sub)) finishSubmission(sub);

    // The pool: references first (grading jobs wait on their lab's), then labs in submission order.
    std::map<pid_t, std::size_t> running;
    std::size_t next = 0;
    auto startable = [&](const Job& job) {
        if (job.done || job.pid > 0) return false;
        if (job.kind == Job::Grade)
            for (const LabPlan& lab : labs)
                if (lab.id == job.lab && lab.ref_job != SIZE_MAX && !jobs[lab.ref_job].done) return false;
        return true;
    };
    auto complete = [&](std::size_t j, bool ok, const std::string& why) {
        Job& job = jobs[j];
        job.done = true;
        job.ok = ok;
        job.error = why;
        if (job.kind == Job::Reference && !ok) {
            std::cerr << "shaderlab: the reference solution of " << job.lab << " did not render (" << why
                      << "); its labs are graded against the stored goldens\n";
            for (LabPlan& lab : labs)
                if (lab.id == job.lab) lab.goldens_root.clear();
        }
        for (std::size_t s : job.waiting)
            if (!subs[s].finished && subReady(subs[s])) finishSubmission(subs[s]);
    };
    for (;;) {
        while (static_cast<int>(running.size()) < jobs_max) {
            std::size_t pick = SIZE_MAX;
            for (std::size_t j = next; j < jobs.size(); ++j)
                if (startable(jobs[j])) {
                    pick = j;
                    break;
                }
            if (pick == SIZE_MAX) break;
            Job& job = jobs[pick];
            // A grading job of a lab whose reference failed goes against the goldens. Its result is
            // kept apart, so that a later run with the reference grades it again.
            if (job.kind == Job::Grade)
                for (const LabPlan& lab : labs) {
                    auto g = std::find(job.argv.begin(), job.argv.end(), "--goldens");
                    if (lab.id != job.lab || !lab.goldens_root.empty() || g == job.argv.end()) continue;
                    job.argv.erase(g, g + 2);
                    job.final_dir += "-goldens";
                    *(std::find(job.argv.begin(), job.argv.end(), "--out") + 1) = job.final_dir;
                }
            const std::string log = (state / "logs" /
                                     ((job.kind == Job::Reference ? "reference-" : "grade-") + job.lab + "-" +
                                      fs::path(job.final_dir).filename().string() + ".log"))
                                        .string();
            job.log = log;
            // The render child below the worker watches its resident memory against `memory` and
            // caps its address space at 4 GiB more (isolated_render.cpp); the worker gets the same cap.
            // Not under AddressSanitizer, whose shadow memory reserves terabytes of address space
            // (the render child's resident-memory watch still holds there).
            // SHADERLAB_WORKER_ADDRESS_SPACE (a size such as 64M) replaces that cap, also under
            // ASan: for machines whose driver reserves more, and for the test of a worker that dies
            // (an ASan worker under such a cap dies at its start, which that test wants).
            std::size_t worker_as = SHADERLAB_ASAN ? 0 : memory + (std::size_t(4) << 30);
            if (const char* env = std::getenv("SHADERLAB_WORKER_ADDRESS_SPACE"))
                parseMemory(env, &worker_as, 1);
            const Spawned s = spawnWorker(job.argv, log, worker_as);
            if (s.pid < 0) {
                complete(pick, false, s.error);
                continue;
            }
            job.pid = s.pid;
            job.started = Clock::now();
            running[s.pid] = pick;
            while (next < jobs.size() && (jobs[next].done || jobs[next].pid > 0)) ++next;
        }
        if (running.empty()) break;
        int wstatus = 0;
        const pid_t pid = waitpid(-1, &wstatus, WNOHANG);
        if (pid > 0 && running.count(pid)) {
            const std::size_t j = running[pid];
            running.erase(pid);
            forgetWorker(pid);
            kill(-pid, SIGKILL);  // anything the worker left in its group
            const Job& job = jobs[j];
            const bool landed = fs::exists(
                job.kind == Job::Grade ? fs::path(job.final_dir) / "report.json" : fs::path(job.final_dir),
                ec);
            const bool ok = WIFEXITED(wstatus) && WEXITSTATUS(wstatus) == 0 && landed;
            complete(j, ok, ok ? std::string() : describeExit(wstatus) + lastLogLine(job.log));
            continue;
        }
        if (pid < 0 && errno == ECHILD) break;
        for (auto& [p, j] : running) {
            if (std::chrono::duration<double>(Clock::now() - jobs[j].started).count() > jobs[j].watchdog_s)
                kill(-p, SIGKILL);  // reaped above as a failed job
        }
        progress.tick();
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    for (Submission& sub : subs)
        if (!sub.finished) finishSubmission(sub);  // only when a worker could not be started
    progress.end();

    batch::Summary summary;
    summary.tool_version = SHADERLAB_VERSION;
    for (const LabPlan& lab : labs) summary.labs.push_back(lab.id);
    std::size_t graded = 0, reused = 0;
    for (const Submission& sub : subs) {
        summary.rows.push_back(sub.row);
        graded += sub.skipped ? 0 : 1;
        reused += sub.skipped ? 1 : 0;
    }
    if (!batch::writeFileAtomically((out / "summary.json").string(), batch::summaryToJson(summary), &error) ||
        !batch::writeFileAtomically((out / "summary.csv").string(), batch::summaryToCsv(summary), &error)) {
        std::cerr << "shaderlab: cannot write the summary: " << error << "\n";
        return 2;
    }
    std::size_t ran = 0;
    for (const Job& job : jobs) ran += job.pid > 0 ? 1 : 0;
    const double wall = std::chrono::duration<double>(Clock::now() - t_start).count();
    rusage self{}, children{};
    getrusage(RUSAGE_SELF, &self);
    getrusage(RUSAGE_CHILDREN, &children);
    auto seconds = [](const timeval& t) { return static_cast<double>(t.tv_sec) + t.tv_usec / 1e6; };
    const double cpu = seconds(self.ru_utime) + seconds(self.ru_stime) + seconds(children.ru_utime) +
                       seconds(children.ru_stime);
    std::printf(
        "%zu submissions (%zu graded, %zu unchanged since their report), %zu worker runs, %d jobs at a "
        "time; %.1f s wall, %.1f s CPU, %.0f submissions per minute\n",
        subs.size(), graded, reused, ran, jobs_max, wall, cpu, wall > 0 ? 60.0 * subs.size() / wall : 0.0);
    std::printf("summary: %s\n         %s\n", (out / "summary.csv").string().c_str(),
                (out / "summary.json").string().c_str());
    return exit_code;
}

int runBatchWorker(const BatchWorkerArgs& args) {
    const fs::path final_dir = args.out_dir;
    const fs::path tmp = final_dir.string() + ".tmp-" + std::to_string(getpid());
    std::error_code ec;
    fs::remove_all(tmp, ec);
    fs::create_directories(tmp, ec);
    if (ec) {
        std::cerr << "shaderlab: " << tmp.string() << ": " << ec.message() << "\n";
        return 2;
    }
    Backend backend{};
    parseBackend(args.backend, &backend);
    if (args.mode == "reference") {
        const std::vector<std::string> errors =
            writeGoldens(args.reference_root, args.labs_root, {args.lab}, backend, tmp.string());
        for (const std::string& e : errors) std::cerr << "shaderlab: " << e << "\n";
        if (!errors.empty()) return 1;
        // The known-mistake hints come from the lab; they are read beside the goldens.
        const fs::path hints = fs::path(args.labs_root) / args.lab / "hints";
        if (fs::is_directory(hints, ec))
            fs::copy(hints, tmp / args.lab / "hints", fs::copy_options::recursive, ec);
        if (ec) {
            std::cerr << "shaderlab: " << hints.string() << ": " << ec.message() << "\n";
            return 1;
        }
    } else {
        GradeOptions options;
        options.backend = backend;
        options.labs_root = args.labs_root;
        options.labs = {args.lab};
        options.out_dir = tmp.string();
        options.goldens_root = args.goldens_root;
        options.limits.timeout_s = args.timeout_s;
        options.limits.compile_timeout_s = args.compile_timeout_s;
        std::size_t memory = 0;
        if (parseMemory(args.memory, &memory)) options.limits.memory_bytes = memory;
        grader::Report report = gradeSubmission(args.submission, options);
        report.tool_version = SHADERLAB_VERSION;
        std::string err;
        if (!batch::writeFileAtomically((tmp / "report.json").string(), grader::reportToJson(report), &err)) {
            std::cerr << "shaderlab: " << err << "\n";
            return 2;
        }
    }
    fs::rename(tmp, final_dir, ec);
    if (ec) {  // another batch made it first: theirs is as good
        fs::remove_all(tmp, ec);
        return fs::exists(final_dir) ? 0 : 2;
    }
    return 0;
}

int runMerge(const MergeArgs& args) {
    batch::Summary merged;
    std::map<std::string, std::string> seen;  // student -> results folder
    std::error_code ec;
    const fs::path out = fs::absolute(args.out_dir, ec).lexically_normal();
    std::vector<std::pair<fs::path, batch::SummaryRow>> rows;
    for (const std::string& input : args.inputs) {
        const fs::path in = fs::absolute(input, ec).lexically_normal();
        const std::string text = readText(in / "summary.json");
        batch::Summary s;
        std::string err;
        if (text.empty() || !batch::summaryFromJson(text, &s, &err)) {
            std::cerr << "shaderlab: " << (in / "summary.json").string() << ": "
                      << (text.empty() ? "not found" : err) << "\n";
            return 2;
        }
        if (merged.labs.empty() && merged.rows.empty()) {
            merged.labs = s.labs;
            merged.tool_version = s.tool_version;
        } else if (s.labs != merged.labs) {
            std::cerr << "shaderlab: " << (in / "summary.json").string()
                      << ": graded other labs than the first results folder; merge shards of one batch\n";
            return 2;
        }
        for (batch::SummaryRow& r : s.rows) {
            auto [it, fresh] = seen.emplace(r.student, in.string());
            if (!fresh) {
                std::cerr << "shaderlab: " << batch::printable(r.student) << " is in both " << it->second
                          << " and " << in.string() << "\n";
                return 2;
            }
            rows.emplace_back(in, std::move(r));
        }
    }
    fs::create_directories(out, ec);
    std::string error;
    if (!fs::is_directory(out, ec) ||
        !batch::writeFileAtomically((out / ".shaderlab-write-test").string(), "ok\n", &error)) {
        std::cerr << "shaderlab: " << out.string() << ": cannot write there " << error << "\n";
        return 2;
    }
    fs::remove(out / ".shaderlab-write-test", ec);
    batch::FolderLock lock;
    if (fs::is_symlink(out / kStateDir, ec)) {
        std::cerr << "shaderlab: " << (out / kStateDir).string() << " is a symlink; remove it\n";
        return 2;
    }
    fs::create_directories(out / kStateDir, ec);
    if (!lock.acquire((out / kStateDir / "lock").string(), &error)) {
        std::cerr << "shaderlab: " << out.string() << ": " << error << "\n";
        return 2;
    }
    std::sort(rows.begin(), rows.end(),
              [](const auto& a, const auto& b) { return a.second.student < b.second.student; });
    for (auto& [in, row] : rows) {
        // The report folders come along (hard links where possible) unless they are already there.
        const std::string folder = fs::path(row.report).parent_path().string();
        if (!folder.empty() && in != out && folder.find("..") == std::string::npos) {
            const fs::path dest = out / folder;
            fs::remove_all(dest, ec);
            if (!batch::linkTree((in / folder).string(), dest.string(), &error)) {
                std::cerr << "shaderlab: " << error << "\n";
                return 2;
            }
        }
        merged.rows.push_back(std::move(row));
    }
    if (!batch::writeFileAtomically((out / "summary.json").string(), batch::summaryToJson(merged), &error) ||
        !batch::writeFileAtomically((out / "summary.csv").string(), batch::summaryToCsv(merged), &error)) {
        std::cerr << "shaderlab: cannot write the summary: " << error << "\n";
        return 2;
    }
    std::printf("%zu submissions from %zu results folders\nsummary: %s\n", merged.rows.size(),
                args.inputs.size(), (out / "summary.csv").string().c_str());
    return 0;
}

}  // namespace shaderlab::cli
