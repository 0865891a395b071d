// Child-process rendering; see isolated_render.h.
#include "shaderlab/render/isolated_render.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "grader/base/untrusted_text.h"
#include "shaderlab/base/sanitizer.h"

using json = nlohmann::json;

namespace shaderlab {

namespace {

// The render children in flight (their process groups), so that a grader stopped by SIGTERM,
// SIGINT or SIGHUP takes them along. (SIGKILL cannot be caught: PR_SET_PDEATHSIG covers it.)
// A queue's child may be drawing while a lone render of another lab runs beside it.
constexpr int kChildSlots = 8;
volatile sig_atomic_t g_render_children[kChildSlots] = {};

void stopChildAndDie(int sig) {
    for (int i = 0; i < kChildSlots; ++i) {
        const pid_t child = static_cast<pid_t>(g_render_children[i]);
        if (child > 0) {
            kill(-child, SIGKILL);
            kill(child, SIGKILL);
        }
    }
    signal(sig, SIG_DFL);
    raise(sig);
}

void rememberChild(pid_t pid) {
    for (int i = 0; i < kChildSlots; ++i)
        if (g_render_children[i] == 0) {
            g_render_children[i] = pid;
            return;
        }
    // More than kChildSlots at once: PR_SET_PDEATHSIG still takes this one along.
}

void forgetChild(pid_t pid) {
    for (int i = 0; i < kChildSlots; ++i)
        if (g_render_children[i] == pid) g_render_children[i] = 0;
}

void installStopHandlers() {
    static bool installed = false;
    if (installed) return;
    installed = true;
    for (int sig : {SIGTERM, SIGINT, SIGHUP}) {
        struct sigaction current {};
        sigaction(sig, nullptr, &current);
        if (current.sa_handler == SIG_DFL) signal(sig, stopChildAndDie);  // respect a caller's own handler
    }
}

// Between a child and its parent: a pipe of lines, and an anonymous file of results. The child
// says "L <lab>" when it begins a lab, "e <event>" for each progress event, and, once it has
// written a lab's raw images and then its result.json into the file, "R <lab> <offset> <size>"
// where that JSON lies. Labs are numbered by their place in the queue; offsets are from the start
// of the file. A child that dies half-way leaves no "R" line for its lab.
constexpr std::uint64_t kMaxResultJson = 64u << 20;
using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

bool writeAt(int fd, const void* data, std::size_t n, std::uint64_t offset) {
    const char* p = static_cast<const char*>(data);
    while (n > 0) {
        const ssize_t w = pwrite(fd, p, n, static_cast<off_t>(offset));
        if (w < 0 && errno == EINTR) continue;
        if (w <= 0) return false;
        p += w, n -= static_cast<std::size_t>(w), offset += static_cast<std::uint64_t>(w);
    }
    return true;
}

bool readAt(int fd, void* data, std::size_t n, std::uint64_t offset) {
    char* p = static_cast<char*>(data);
    while (n > 0) {
        const ssize_t r = pread(fd, p, n, static_cast<off_t>(offset));
        if (r < 0 && errno == EINTR) continue;
        if (r <= 0) return false;
        p += r, n -= static_cast<std::size_t>(r), offset += static_cast<std::uint64_t>(r);
    }
    return true;
}

// The child's part of a lab: its images into the result file from `*end` on, then its
// result.json after them; returns where the JSON lies, or exits on a failed write.
std::pair<std::uint64_t, std::uint64_t> writeLabResult(json result, const LabRender* r, int result_fd,
                                                       std::uint64_t* end) {
    if (r) {
        result["status"] = renderStatusName(r->status);
        result["message"] = r->message;
        result["endless_loop"] = r->endless_loop;
        json diags = json::array();
        for (const Diagnostic& d : r->diagnostics) diags.push_back(diagnosticToJson(d));
        result["diagnostics"] = diags;
        json scenes = json::array();
        for (const SceneRender& s : r->scenes) {
            json passes = json::array();
            for (const PassImage& p : s.passes) {
                const std::size_t color_bytes = p.color.pixels.size() * sizeof(float);
                const std::uint64_t color_at = *end, coverage_at = *end + color_bytes;
                if (!writeAt(result_fd, p.color.pixels.data(), color_bytes, color_at) ||
                    !writeAt(result_fd, p.coverage.data(), p.coverage.size(), coverage_at))
                    _exit(3);
                *end = coverage_at + p.coverage.size();
                passes.push_back({{"pass", p.pass},
                                  {"target", p.target},
                                  {"attachment", p.attachment},
                                  {"graded", p.graded},
                                  {"width", p.color.width},
                                  {"height", p.color.height},
                                  {"color_at", color_at},
                                  {"coverage_at", coverage_at}});
            }
            scenes.push_back(
                {{"scene", s.scene}, {"render_ms", s.render_ms}, {"passes", passes}, {"error", s.error}});
        }
        result["scenes"] = scenes;
    }
    // Shader logs may hold any bytes the student typed: replace invalid UTF-8 rather than throw.
    const std::string text = result.dump(-1, ' ', false, json::error_handler_t::replace);
    const std::uint64_t at = *end;
    if (!writeAt(result_fd, text.data(), text.size(), at)) _exit(3);
    *end = at + text.size();
    return {at, text.size()};
}

// Child side: one context, then the labs from `first` on, each handed back as it is done (the
// protocol above). Never returns.
[[noreturn]] void childMain(const std::vector<IsolatedLabJob>& jobs, std::size_t first, Backend backend,
                            const IsolationLimits& limits, int result_fd, pid_t parent_pid, int progress_fd) {
    const auto child_start = Clock::now();
    // Its own process group: the parent stops the child and anything it started with one
    // kill(), and a terminal's Ctrl-C reaches the grader, which then stops the child.
    setpgid(0, 0);
    // Die with the grader: a parent killed by a batch system's time limit (SIGKILL) must not
    // leave a child spinning on a shader. If it is already gone, stop now.
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != parent_pid) _exit(1);
    for (int sig : {SIGTERM, SIGINT, SIGHUP}) signal(sig, SIG_DFL);
#if !SHADERLAB_ASAN
    // The parent watches resident memory; this is the backstop for an allocation faster than its
    // polling. Not under AddressSanitizer: it reserves terabytes of address space for its shadow
    // memory up front, so under the cap its allocations would fail; the parent's watch still holds.
    rlimit as{};
    as.rlim_cur = as.rlim_max = limits.memory_bytes + kAddressSpaceHeadroom;
    setrlimit(RLIMIT_AS, &as);
#endif
    // A backstop should the parent's clock fail: CPU seconds of all the driver's threads, for
    // every lab this child is given.
    const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
    rlimit cpu{};
    cpu.rlim_cur = cpu.rlim_max = static_cast<rlim_t>((limits.timeout_s + limits.compile_timeout_s) *
                                                          threads * static_cast<double>(jobs.size() - first) +
                                                      10.0);
    setrlimit(RLIMIT_CPU, &cpu);
    rlimit core{};  // a crashing driver should not litter core files
    setrlimit(RLIMIT_CORE, &core);

    // One line to the parent; it says where a render stopped and which of its clocks runs.
    auto say = [progress_fd](const std::string& text) {
        const std::string line = text + "\n";
        for (std::size_t done = 0; done < line.size();) {
            const ssize_t n = write(progress_fd, line.data() + done, line.size() - done);
            if (n <= 0 && errno != EINTR) return;
            if (n > 0) done += static_cast<std::size_t>(n);
        }
    };
    std::uint64_t end = 0;
    ContextResult ctx = createHeadlessContext(backend);
    const std::string renderer =
        ctx.context ? ctx.context->info().renderer + ", OpenGL " + ctx.context->info().version
                    : std::string();
    auto lab_start = child_start;  // the first lab's time includes the context's
    for (std::size_t k = first; k < jobs.size(); ++k) {
        say("L " + std::to_string(k));
        json result;
        double compile_ms = -1.0;
        std::pair<std::uint64_t, std::uint64_t> where;
        if (!ctx.context) {
            result["status"] = "render_error";
            result["message"] = ctx.error;
            where = writeLabResult(std::move(result), nullptr, result_fd, &end);
        } else {
            result["renderer"] = renderer;
            RenderOptions options = jobs[k].options;
            options.progress = [&](const std::string& event) {
                if (compile_ms < 0.0 && event.rfind("compile ", 0) != 0) compile_ms = msSince(lab_start);
                say("e " + event);
            };
            const LabRender r = renderLab(*jobs[k].spec, jobs[k].shader_dir, options);
            const double wall_ms = msSince(lab_start);
            result["wall_ms"] = wall_ms;
            result["compile_ms"] = compile_ms < 0.0 ? wall_ms : compile_ms;
            where = writeLabResult(std::move(result), &r, result_fd, &end);
        }
        say("R " + std::to_string(k) + " " + std::to_string(where.first) + " " +
            std::to_string(where.second));
        lab_start = Clock::now();
    }
    // _exit: skip atexit handlers and static destructors of the copied parent state.
    std::fflush(nullptr);
    _exit(0);
}

// " while <what the child was doing>", from its last progress event.
std::string whereItStopped(const std::string& event) {
    std::istringstream in(event);
    std::string kind, a, b;
    in >> kind >> a >> b;
    if (kind == "compile") return " while compiling " + a + " and " + b;
    if (kind == "pass") return " while drawing pass '" + b + "' of scene '" + a + "'";
    if (kind == "scene") return " while setting up scene '" + a + "'";
    if (kind == "done") return " after scene '" + a + "'";
    return " while starting (creating the OpenGL context, reading the files)";
}

IsolatedStatus statusFromName(const std::string& s) {
    if (s == "ok") return IsolatedStatus::Ok;
    if (s == "missing") return IsolatedStatus::Missing;
    if (s == "compile_error") return IsolatedStatus::CompileError;
    if (s == "link_error") return IsolatedStatus::LinkError;
    return IsolatedStatus::RenderError;
}

RenderStatus renderStatusOf(IsolatedStatus s) {
    switch (s) {
        case IsolatedStatus::Ok:
            return RenderStatus::Ok;
        case IsolatedStatus::Missing:
            return RenderStatus::Missing;
        case IsolatedStatus::CompileError:
            return RenderStatus::CompileError;
        case IsolatedStatus::LinkError:
            return RenderStatus::LinkError;
        default:
            return RenderStatus::RenderError;
    }
}

// A string of the child's result, made printable and capped (it may hold anything the student
// wrote or the driver echoed).
std::string text(const json& object, const char* key, std::size_t max_bytes = 2000, bool newlines = false) {
    const auto it = object.find(key);
    if (it == object.end() || !it->is_string()) return {};
    return grader::printableText(it->get_ref<const std::string&>(), max_bytes, newlines);
}

int integer(const json& object, const char* key) {
    const auto it = object.find(key);
    if (it == object.end() || !it->is_number_integer()) return 0;
    const auto v = it->get<std::int64_t>();
    return static_cast<int>(std::clamp<std::int64_t>(v, INT32_MIN, INT32_MAX));
}

bool readResultJson(const json& result, int fd, std::uint64_t size, IsolatedRender* out);

// Parent side: read one lab's result where the child said it lies, trusting nothing about sizes.
bool readChildResult(int fd, std::uint64_t json_offset, std::uint64_t json_size, IsolatedRender* out) {
    struct stat st {};
    if (fstat(fd, &st) != 0 || st.st_size <= 0) return false;
    const std::uint64_t size = static_cast<std::uint64_t>(st.st_size);
    if (json_size > kMaxResultJson || json_offset > size || json_size > size - json_offset) return false;
    std::string bytes(json_size, '\0');
    if (!readAt(fd, bytes.data(), bytes.size(), json_offset)) return false;
    const json result = json::parse(bytes, nullptr, false);
    if (result.is_discarded() || !result.is_object()) return false;
    // A value of the wrong type makes the JSON library throw: such a result is unreadable.
    try {
        return readResultJson(result, fd, size, out);
    } catch (const json::exception&) {
        return false;
    }
}

// The rest of readChildResult(): the fields of a parsed result.json, images read from `fd`.
bool readResultJson(const json& result, int fd, std::uint64_t size, IsolatedRender* out) {
    out->status = statusFromName(result.value("status", ""));
    out->message = text(result, "message");
    out->renderer = text(result, "renderer", 500);
    // The child's own clock (the parent may have been busy when the lab ended): for reports only.
    const double wall_ms = result.value("wall_ms", -1.0), compile_ms = result.value("compile_ms", -1.0);
    if (std::isfinite(wall_ms) && wall_ms >= 0.0) {
        out->wall_ms = wall_ms;
        if (std::isfinite(compile_ms) && compile_ms >= 0.0) out->compile_ms = std::min(compile_ms, wall_ms);
    }
    out->render.status = renderStatusOf(out->status);
    out->render.message = out->message;
    // A loop stopped by the loop guard (shader_program.h): as good as a timeout, said as such.
    if (out->status == IsolatedStatus::RenderError && result.value("endless_loop", false)) {
        out->status = IsolatedStatus::Timeout;
        out->limit = "loop";
        out->render.endless_loop = true;
    }
    const json diags = result.value("diagnostics", json::array());
    for (const json& d : diags) {
        if (!d.is_object()) continue;
        if (out->render.diagnostics.size() == kMaxDiagnostics) {
            const std::size_t left = diags.size() - kMaxDiagnostics;
            out->render.diagnostics.push_back(
                {"", 0, 0, "note",
                 std::to_string(left) + " more message" + (left == 1 ? "" : "s") +
                     " left out (a report keeps the first " + std::to_string(kMaxDiagnostics) +
                     "): fix these first and compile again"});
            break;
        }
        out->render.diagnostics.push_back({text(d, "file", 300), integer(d, "line"), integer(d, "column"),
                                           text(d, "severity", 20), text(d, "message"),
                                           text(d, "explanation", 4000, true), text(d, "source_line", 1000),
                                           text(d, "driver_message", 2000, true), integer(d, "follow_on")});
    }
    for (const json& s : result.value("scenes", json::array())) {
        SceneRender scene;
        scene.scene = text(s, "scene", 300);
        scene.render_ms = s.value("render_ms", 0.0);
        scene.error = text(s, "error", 2000, true);
        for (const json& p : s.value("passes", json::array())) {
            PassImage img;
            img.pass = text(p, "pass", 300);
            img.target = text(p, "target", 300);
            img.attachment = text(p, "attachment", 300);
            img.graded = p.value("graded", false);
            const int w = p.value("width", 0), h = p.value("height", 0);
            if (w <= 0 || h <= 0 || w > 6 * 4096 || h > 4096) return false;
            const std::uint64_t color_at = p.value("color_at", std::uint64_t(0));
            const std::uint64_t coverage_at = p.value("coverage_at", std::uint64_t(0));
            const std::uint64_t pixels = static_cast<std::uint64_t>(w) * static_cast<std::uint64_t>(h);
            if (color_at > size || pixels * 4 * sizeof(float) > size - color_at || coverage_at > size ||
                pixels > size - coverage_at)
                return false;
            img.color = grader::Image(w, h, 4);
            img.coverage.resize(static_cast<std::size_t>(pixels));
            if (!readAt(fd, img.color.pixels.data(), img.color.pixels.size() * sizeof(float), color_at) ||
                !readAt(fd, img.coverage.data(), img.coverage.size(), coverage_at))
                return false;
            scene.passes.push_back(std::move(img));
        }
        out->render.scenes.push_back(std::move(scene));
    }
    return true;
}

// The child's resident memory in bytes (0 when it cannot be read).
std::size_t residentBytes(pid_t pid) {
    char path[64];
    std::snprintf(path, sizeof path, "/proc/%d/statm", static_cast<int>(pid));
    const int fd = open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0) return 0;
    char buf[128] = {};
    const ssize_t n = read(fd, buf, sizeof buf - 1);
    close(fd);
    if (n <= 0) return 0;
    unsigned long long total = 0, resident = 0;
    if (std::sscanf(buf, "%llu %llu", &total, &resident) != 2) return 0;
    return static_cast<std::size_t>(resident) * static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
}

std::string seconds(double s) {
    char buf[32];
    std::snprintf(buf, sizeof buf, s < 10.0 ? "%.1f" : "%.0f", s);
    return buf;
}

// How a child's part in one lab ended: `finished` is false when a limit ran out (the result's
// `limit` names it); `lost`: reaped elsewhere.
struct ChildEnd {
    int wstatus = 0;
    bool finished = false, lost = false;
};

// The status and message of a lab whose child ended or was killed before handing it back: the
// limit that ran out, the signal it died of, or an exit without a result.
// `killed` false: a later lab of a queue that went past a clock while the grader was busy, and
// finished before the grader looked again.
void chargeChild(const IsolationLimits& limits, const ChildEnd& end, IsolatedRender* result,
                 bool killed = true) {
    IsolatedRender& out = *result;
    const int wstatus = end.wstatus;
    const std::string where = whereItStopped(out.last_event);
    const std::string stopped =
        killed ? "; the process was killed"
               : "; it ran on while the grader was busy, and counts as stopped at the limit";
    if (out.limit == "compile_timeout") {
        out.status = IsolatedStatus::Timeout;
        out.message = "compile timeout: not ready to draw within " + seconds(limits.compile_timeout_s) +
                      " s (the compile limit)" + where +
                      " (a very large or complex shader, e.g. a huge array or a macro that doubles "
                      "itself?)" +
                      stopped;
    } else if (out.limit == "draw_timeout") {
        out.status = IsolatedStatus::Timeout;
        out.message = "draw timeout: drawing did not finish within " + seconds(limits.timeout_s) +
                      " s (the draw limit)" + where + " (an endless or very long loop in a shader?)" +
                      stopped;
    } else if (out.limit == "memory") {
        out.status = IsolatedStatus::Crashed;
        out.message = "memory limit: the render process used more than " +
                      std::to_string(limits.memory_bytes >> 20) + " MiB" + where +
                      " (a huge array, or a macro that doubles itself?); the process was killed";
    } else if (!end.lost && WIFSIGNALED(wstatus)) {
        out.status = IsolatedStatus::Crashed;
        const int sig = WTERMSIG(wstatus);
        out.message = std::string("the render process died of signal ") + std::to_string(sig) + " (" +
                      strsignal(sig) + ")" + where;
        if (sig == SIGKILL || sig == SIGSEGV || sig == SIGABRT)
            out.message += "; the shader may have crashed the driver or exceeded the memory limit";
        if (sig == SIGXCPU) out.message += "; it used more processor time than its limits allow";
    } else {
        out.status = IsolatedStatus::Crashed;
        out.message =
            (end.lost ? std::string("the render process ended")
                      : "the render process exited (code " + std::to_string(WEXITSTATUS(wstatus)) + ")") +
            " without a readable result" + where + "; out of memory?";
    }
}

// A lab after the child's first may have run while the grader was busy elsewhere, unwatched: by
// the child's clocks it is charged as the grader would have stopped it.
void chargeIfLate(const IsolationLimits& limits, IsolatedRender* out) {
    const bool compile_late = out->compile_ms > limits.compile_timeout_s * 1000.0;
    const bool draw_late = out->wall_ms - out->compile_ms > limits.timeout_s * 1000.0;
    if (!compile_late && !draw_late) return;
    IsolatedRender late;
    late.limit = compile_late ? "compile_timeout" : "draw_timeout";
    late.last_event = out->last_event;
    late.renderer = out->renderer;
    late.wall_ms = out->wall_ms;
    late.compile_ms = out->compile_ms;
    late.peak_rss_bytes = out->peak_rss_bytes;
    ChildEnd none;
    none.finished = true;
    chargeChild(limits, none, &late, false);
    *out = std::move(late);
}

}  // namespace

struct IsolatedRenderQueue::State {
    std::vector<IsolatedLabJob> jobs;
    Backend backend = Backend::OSMesa;
    IsolationLimits limits;
    std::size_t next = 0;  // the lab next() hands back

    // The child in flight, if any.
    pid_t pid = -1;
    std::size_t first = 0;  // the first lab it was given
    int result_fd = -1, progress_fd = -1;
    std::string pending;             // bytes of the pipe not yet taken as lines
    std::size_t current = SIZE_MAX;  // the lab it said it began
    bool drawing = false;            // the lab `next` reported its first scene: the draw clock runs
    Clock::time_point lab_start, phase_start;
    std::map<std::size_t, std::pair<std::uint64_t, std::uint64_t>> ready;  // lab -> its result.json
    std::uint64_t freed_to = 0;  // the result file below this is handed back and freed

    ChildEnd ended;  // how it ended, once reaped (its files stay open until the next)
    std::size_t children_started = 0;

    bool sigchld_saved = false;
    struct sigaction old_chld {};

    bool startChild(std::string* error);
    void stopChild();  // kills (if running) and reaps it, and closes its files
    void takeLines(IsolatedRender* out);
    ChildEnd watch(IsolatedRender* out);
};

bool IsolatedRenderQueue::State::startChild(std::string* error) {
    stopChild();  // the files of one that ended
    // An anonymous file: the parent keeps it open, the child writes into it, and it is gone
    // with the last descriptor however either process ends.
    result_fd = memfd_create("shaderlab-render", MFD_CLOEXEC);
    if (result_fd < 0) {
        *error = std::string("cannot create the result file: ") + std::strerror(errno);
        return false;
    }
    installStopHandlers();
    std::fflush(nullptr);  // buffered output would otherwise be written twice
    // An inherited SIG_IGN for SIGCHLD would make the kernel reap the child itself and waitpid
    // fail; the default disposition is restored while the queue lives.
    if (!sigchld_saved) {
        struct sigaction dfl {};
        dfl.sa_handler = SIG_DFL;
        sigemptyset(&dfl.sa_mask);
        sigaction(SIGCHLD, &dfl, &old_chld);
        sigchld_saved = true;
    }
    int progress_pipe[2] = {-1, -1};
    if (pipe2(progress_pipe, O_CLOEXEC) != 0) {
        *error = std::string("cannot create a pipe: ") + std::strerror(errno);
        close(result_fd);
        result_fd = -1;
        return false;
    }
    const pid_t parent_pid = getpid();
    const auto t0 = Clock::now();
    const pid_t child = fork();
    if (child < 0) {
        *error = std::string("fork failed: ") + std::strerror(errno);
        for (int fd : progress_pipe) close(fd);
        close(result_fd);
        result_fd = -1;
        return false;
    }
    if (child == 0) {
        close(progress_pipe[0]);
        childMain(jobs, next, backend, limits, result_fd, parent_pid, progress_pipe[1]);
    }
    setpgid(child, child);  // as the child does itself: whichever runs first
    rememberChild(child);
    pid = child;
    close(progress_pipe[1]);
    progress_fd = progress_pipe[0];
    fcntl(progress_fd, F_SETFL, O_NONBLOCK);
    ++children_started;
    first = next;
    current = SIZE_MAX;
    ended = ChildEnd{};
    drawing = false;
    lab_start = phase_start = t0;
    pending.clear();
    ready.clear();
    freed_to = 0;
    return true;
}

void IsolatedRenderQueue::State::stopChild() {
    if (pid > 0) {
        kill(-pid, SIGKILL);
        kill(pid, SIGKILL);
        // A child stuck in the kernel (a GPU driver) may take a while to die; it is reaped.
        int wstatus = 0;
        while (waitpid(pid, &wstatus, 0) < 0 && errno == EINTR) {
        }
        forgetChild(pid);
    }
    pid = -1;
    if (progress_fd >= 0) close(progress_fd);
    if (result_fd >= 0) close(result_fd);
    progress_fd = result_fd = -1;
}

// Reads what the child reported so far and takes its lines up to the end of lab `next`: the
// caller hears every event of that lab, and the last one says where a render that has to be
// stopped was. Lines of the labs after it wait for the next call.
void IsolatedRenderQueue::State::takeLines(IsolatedRender* out) {
    if (progress_fd < 0) return;
    char buf[4096];
    for (;;) {
        const ssize_t n = read(progress_fd, buf, sizeof buf);
        if (n <= 0) break;
        pending.append(buf, static_cast<std::size_t>(n));
    }
    std::size_t from = 0;
    for (std::size_t nl = pending.find('\n'); nl != std::string::npos && !ready.count(next);
         nl = pending.find('\n', from)) {
        const std::string_view line = std::string_view(pending).substr(from, nl - from);
        from = nl + 1;
        if (line.size() < 2 || line[1] != ' ') continue;  // not ours
        const std::string_view rest = line.substr(2);
        if (line[0] == 'e' && current == next) {
            const std::string event = grader::printableText(rest, 1000);
            if (!drawing && event.rfind("compile ", 0) != 0) {
                drawing = true;
                phase_start = Clock::now();
                out->compile_ms = std::chrono::duration<double, std::milli>(phase_start - lab_start).count();
            }
            if (event.rfind("done ", 0) != 0) out->last_event = event;
            const std::function<void(const std::string&)>& progress = jobs[next].options.progress;
            if (progress) progress(event);
        } else if (line[0] == 'L' || line[0] == 'R') {
            unsigned long long lab = 0, at = 0, size = 0;
            const std::string fields(rest);
            const int got = std::sscanf(fields.c_str(), "%llu %llu %llu", &lab, &at, &size);
            if (got < 1 || lab != next) continue;  // the child says labs in order, this one next
            if (line[0] == 'L') {
                current = next;
            } else if (got == 3) {
                ready[next] = {at, size};
                // The next lab's clocks start now: its compile clock runs until its first scene.
                drawing = false;
                lab_start = phase_start = Clock::now();
            }
        }
    }
    pending.erase(0, from);
    // A line without end: not ours. (Whole lines of the labs after `next` are kept.)
    const std::size_t last = pending.rfind('\n');
    const std::size_t tail = last == std::string::npos ? 0 : last + 1;
    if (pending.size() - tail > 1000000) pending.erase(tail);
}

// Waits for lab `next`: until the child hands it back, ends, or meets a limit.
ChildEnd IsolatedRenderQueue::State::watch(IsolatedRender* out) {
    if (pid < 0) {  // it ended while the grader was busy: what it finished is in its files
        takeLines(out);
        return ended;
    }
    ChildEnd end;
    // Poll rather than block: the parent must be able to give up on a child that never ends or
    // grows too large.
    while (true) {
        const pid_t r = waitpid(pid, &end.wstatus, WNOHANG);
        if (r == pid || (r < 0 && errno != EINTR)) {  // ended, or reaped elsewhere
            end.finished = true;
            end.lost = r != pid;
            forgetChild(pid);
            pid = -1;
            ended = end;
            takeLines(out);
            return end;
        }
        takeLines(out);
        if (ready.count(next)) {
            end.finished = true;
            return end;
        }
        const auto now = Clock::now();
        const double in_phase = std::chrono::duration<double>(now - phase_start).count();
        if (in_phase > (drawing ? limits.timeout_s : limits.compile_timeout_s)) {
            out->limit = drawing ? "draw_timeout" : "compile_timeout";
            return end;
        }
        const std::size_t rss = residentBytes(pid);
        out->peak_rss_bytes = std::max(out->peak_rss_bytes, rss);
        if (rss > limits.memory_bytes) {
            out->limit = "memory";
            return end;
        }
        const double elapsed = std::chrono::duration<double>(now - lab_start).count();
        std::this_thread::sleep_for(std::chrono::milliseconds(elapsed < 1.0 ? 2 : 10));
    }
}

IsolatedRenderQueue::IsolatedRenderQueue(std::vector<IsolatedLabJob> jobs, Backend backend,
                                         const IsolationLimits& limits)
    : state_(std::make_unique<State>()) {
    state_->jobs = std::move(jobs);
    state_->backend = backend;
    state_->limits = limits;
}

IsolatedRenderQueue::~IsolatedRenderQueue() {
    state_->stopChild();
    if (state_->sigchld_saved) sigaction(SIGCHLD, &state_->old_chld, nullptr);
}

std::size_t IsolatedRenderQueue::handedBack() const { return state_->next; }

std::size_t IsolatedRenderQueue::childrenStarted() const { return state_->children_started; }

void IsolatedRenderQueue::start() {
    State& s = *state_;
    std::string error;
    if (s.pid < 0 && s.result_fd < 0 && s.next < s.jobs.size() && !s.startChild(&error)) s.stopChild();
}

IsolatedRender IsolatedRenderQueue::next(const std::function<void()>& while_rendering) {
    State& s = *state_;
    IsolatedRender out;
    if (s.next >= s.jobs.size()) {
        out.status = IsolatedStatus::RenderError;
        out.message = out.render.message = "no lab left to render";
        out.render.status = RenderStatus::RenderError;
        return out;
    }
    std::exception_ptr meanwhile_failed;
    bool meanwhile_done = !while_rendering;
    for (;;) {
        std::string error;
        if (s.pid < 0 && s.result_fd < 0 && !s.startChild(&error)) {
            s.stopChild();
            out.status = IsolatedStatus::RenderError;
            out.message = out.render.message = error;
            out.render.status = RenderStatus::RenderError;
            break;
        }
        // The caller's work meanwhile; should it throw, the child is still watched and reaped first.
        if (!meanwhile_done) {
            meanwhile_done = true;
            try {
                while_rendering();
            } catch (...) {
                meanwhile_failed = std::current_exception();
            }
        }
        const bool first = s.next == s.first;
        const ChildEnd end = s.watch(&out);
        const auto found = s.ready.find(s.next);
        if (found != s.ready.end()) {
            const bool read = readChildResult(s.result_fd, found->second.first, found->second.second, &out);
            // What is handed back is freed: a child running ahead holds only the labs not taken yet.
            const std::uint64_t taken = found->second.first + found->second.second;
            if (read && taken > s.freed_to) {
                fallocate(s.result_fd, FALLOC_FL_PUNCH_HOLE | FALLOC_FL_KEEP_SIZE,
                          static_cast<off_t>(s.freed_to), static_cast<off_t>(taken - s.freed_to));
                s.freed_to = taken;
            }
            if (!read) {
                s.stopChild();
                out = IsolatedRender{};
                out.status = IsolatedStatus::Crashed;
                out.message = "the render process handed back a result that cannot be read";
            } else if (!first) {
                chargeIfLate(s.limits, &out);
            }
            break;
        }
        // No result: a limit ran out, or the child ended without it.
        out.wall_ms = msSince(s.lab_start);
        if (!s.drawing) out.compile_ms = out.wall_ms;
        s.stopChild();
        if (!first && out.limit != "compile_timeout" && out.limit != "draw_timeout") {
            out = IsolatedRender{};  // again, in a child of its own
            continue;
        }
        chargeChild(s.limits, end, &out);
        break;
    }
    if (out.status == IsolatedStatus::Timeout || out.status == IsolatedStatus::Crashed) {
        out.render.status = RenderStatus::RenderError;
        out.render.scenes.clear();  // an interrupted render's images are not graded
        out.render.message = out.message;
    }
    ++s.next;
    if (meanwhile_failed) std::rethrow_exception(meanwhile_failed);
    return out;
}

const char* isolatedStatusName(IsolatedStatus status) {
    switch (status) {
        case IsolatedStatus::Ok:
            return "ok";
        case IsolatedStatus::Missing:
            return "missing";
        case IsolatedStatus::CompileError:
            return "compile_error";
        case IsolatedStatus::LinkError:
            return "link_error";
        case IsolatedStatus::RenderError:
            return "render_error";
        case IsolatedStatus::Timeout:
            return "timeout";
        default:
            return "crashed";
    }
}

IsolatedRender renderLabIsolated(const LabSpec& spec, const std::string& shader_dir, Backend backend,
                                 const IsolationLimits& limits, const RenderOptions& options,
                                 const std::function<void()>& while_rendering) {
    IsolatedRenderQueue queue({IsolatedLabJob{&spec, shader_dir, options}}, backend, limits);
    return queue.next(while_rendering);
}

json diagnosticToJson(const Diagnostic& d) {
    return {{"file", d.file},
            {"line", d.line},
            {"column", d.column},
            {"severity", d.severity},
            {"message", d.message},
            {"explanation", d.explanation},
            {"source_line", d.source_line},
            {"driver_message", d.driver_message},
            {"follow_on", d.follow_on}};
}

}  // namespace shaderlab
