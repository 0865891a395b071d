// Worker processes seen from the batch: started, reaped, killed with it; see workers.h. What a
// worker does is in batch_worker_task.cpp; when they run, in batch_schedule.cpp.
#include <fcntl.h>
#include <sched.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <thread>

#include "batch_detail.h"
#include "shaderlab/base/sanitizer.h"
#include "shaderlab/batch/batch.h"
#include "shaderlab/batch/workers.h"

namespace fs = std::filesystem;

namespace shaderlab::batch {

namespace {

// The workers in flight, for the signal handler: a batch stopped by SIGINT or SIGTERM takes
// every worker's process group (worker and render child) along. SIGKILL cannot be caught;
// PR_SET_PDEATHSIG does that part.
volatile sig_atomic_t g_workers[kMaxWorkers] = {};

void killWorkersAndDie(int sig) {
    for (int i = 0; i < kMaxWorkers; ++i)
        if (g_workers[i] > 0) kill(-static_cast<pid_t>(g_workers[i]), SIGKILL);
    signal(sig, SIG_DFL);
    raise(sig);
}

}  // namespace

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

void killWorkersOnSignals() {
    for (int sig : {SIGINT, SIGTERM, SIGHUP}) signal(sig, killWorkersAndDie);
}

std::string describeExit(int wstatus) {
    if (WIFSIGNALED(wstatus))
        return std::string("killed by signal ") + std::to_string(WTERMSIG(wstatus)) + " (" +
               strsignal(WTERMSIG(wstatus)) + ")";
    return "exit code " + std::to_string(WEXITSTATUS(wstatus));
}

std::string lastLogLine(const std::string& log) {
    std::istringstream in(batch_detail::readText(log, 1u << 20));
    std::string line, last;
    while (std::getline(in, line))
        if (!line.empty()) last = line;
    return (last.empty() ? std::string() : ": " + printable(last, 300)) + "; log: " + log;
}

std::string probeRenderer(const std::string& exe, const std::string& backend, const std::string& log) {
    // No address-space cap under AddressSanitizer (see the pool in batch_schedule.cpp).
    const Spawned s =
        spawnWorker({exe, "info", "--backend", backend}, log, SHADERLAB_ASAN ? 0 : std::size_t(8) << 30);
    if (s.pid < 0) return {};
    int wstatus = 0;
    while (waitpid(s.pid, &wstatus, 0) < 0 && errno == EINTR) {
    }
    forgetWorker(s.pid);
    std::istringstream in(batch_detail::readText(log));
    std::string line, renderer;
    while (std::getline(in, line))
        if (line.rfind("renderer:", 0) == 0 || line.rfind("version:", 0) == 0) renderer += line + "\n";
    return renderer;
}

int usableCores() {
    cpu_set_t set;
    CPU_ZERO(&set);
    if (sched_getaffinity(0, sizeof set, &set) == 0 && CPU_COUNT(&set) > 0) return CPU_COUNT(&set);
    return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

std::string selfExe() {
    std::error_code ec;
    const fs::path p = fs::read_symlink("/proc/self/exe", ec);
    return ec ? std::string("/proc/self/exe") : p.string();
}

}  // namespace shaderlab::batch
