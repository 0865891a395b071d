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
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "grader/base/untrusted_text.h"
#include "shaderlab/base/sanitizer.h"

using json = nlohmann::json;

namespace shaderlab {

namespace {

// The render child in flight (its process group), so that a grader stopped by SIGTERM, SIGINT
// or SIGHUP takes it along. (SIGKILL cannot be caught: PR_SET_PDEATHSIG covers it.)
volatile sig_atomic_t g_render_child = 0;

void stopChildAndDie(int sig) {
    const pid_t child = static_cast<pid_t>(g_render_child);
    if (child > 0) {
        kill(-child, SIGKILL);
        kill(child, SIGKILL);
    }
    signal(sig, SIG_DFL);
    raise(sig);
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

// The result file: a header written last (so a child that dies half-way leaves no header), the
// raw images, then result.json. All offsets are from the start of the file.
struct ResultHeader {
    char magic[8];
    std::uint64_t json_offset;
    std::uint64_t json_size;
};
constexpr char kMagic[8] = {'S', 'L', 'R', 'E', 'S', 'U', 'L', 'T'};
constexpr std::uint64_t kMaxResultJson = 64u << 20;

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

// Child side: render, then write the images and result.json into the result file. Never returns.
[[noreturn]] void childMain(const LabSpec& spec, const std::string& shader_dir, Backend backend,
                            const IsolationLimits& limits, RenderOptions options, int result_fd,
                            pid_t parent_pid, int progress_fd) {
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
    // A backstop should the parent's clock fail: CPU seconds of all the driver's threads.
    const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
    rlimit cpu{};
    cpu.rlim_cur = cpu.rlim_max =
        static_cast<rlim_t>((limits.timeout_s + limits.compile_timeout_s) * threads + 10.0);
    setrlimit(RLIMIT_CPU, &cpu);
    rlimit core{};  // a crashing driver should not litter core files
    setrlimit(RLIMIT_CORE, &core);

    json result;
    std::uint64_t end = sizeof(ResultHeader);
    ContextResult ctx = createHeadlessContext(backend);
    if (!ctx.context) {
        result["status"] = "render_error";
        result["message"] = ctx.error;
    } else {
        result["renderer"] = ctx.context->info().renderer + ", OpenGL " + ctx.context->info().version;
        // Progress goes to the parent line by line, so it can say where a render stopped and
        // which of its clocks runs.
        options.progress = [progress_fd](const std::string& event) {
            const std::string line = event + "\n";
            for (std::size_t done = 0; done < line.size();) {
                const ssize_t n = write(progress_fd, line.data() + done, line.size() - done);
                if (n <= 0 && errno != EINTR) return;
                if (n > 0) done += static_cast<std::size_t>(n);
            }
        };
        const LabRender r = renderLab(spec, shader_dir, options);
        result["status"] = renderStatusName(r.status);
        result["message"] = r.message;
        result["endless_loop"] = r.endless_loop;
        json diags = json::array();
        for (const Diagnostic& d : r.diagnostics) diags.push_back(diagnosticToJson(d));
        result["diagnostics"] = diags;
        json scenes = json::array();
        for (const SceneRender& s : r.scenes) {
            json passes = json::array();
            for (const PassImage& p : s.passes) {
                const std::size_t color_bytes = p.color.pixels.size() * sizeof(float);
                const std::uint64_t color_at = end, coverage_at = end + color_bytes;
                if (!writeAt(result_fd, p.color.pixels.data(), color_bytes, color_at) ||
                    !writeAt(result_fd, p.coverage.data(), p.coverage.size(), coverage_at))
                    _exit(3);
                end = coverage_at + p.coverage.size();
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
    ResultHeader header{};
    std::memcpy(header.magic, kMagic, sizeof kMagic);
    header.json_offset = end;
    header.json_size = text.size();
    if (!writeAt(result_fd, text.data(), text.size(), end) || !writeAt(result_fd, &header, sizeof header, 0))
        _exit(3);
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

// Parent side: read what the child wrote, trusting nothing about sizes.
bool readChildResult(int fd, IsolatedRender* out) {
    struct stat st {};
    if (fstat(fd, &st) != 0 || st.st_size < static_cast<off_t>(sizeof(ResultHeader))) return false;
    const std::uint64_t size = static_cast<std::uint64_t>(st.st_size);
    ResultHeader header{};
    if (!readAt(fd, &header, sizeof header, 0) || std::memcmp(header.magic, kMagic, sizeof kMagic) != 0)
        return false;
    if (header.json_size > kMaxResultJson || header.json_offset > size ||
        header.json_size > size - header.json_offset)
        return false;
    std::string bytes(header.json_size, '\0');
    if (!readAt(fd, bytes.data(), bytes.size(), header.json_offset)) return false;
    const json result = json::parse(bytes, nullptr, false);
    if (result.is_discarded() || !result.is_object()) return false;
    out->status = statusFromName(result.value("status", ""));
    out->message = text(result, "message");
    out->renderer = text(result, "renderer", 500);
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

// The child's progress as the parent reads it: a pipe the child writes one line per event into.
struct ChildProgress {
    ChildProgress(int read_fd, const RenderOptions& render_options, IsolatedRender* result,
                  std::chrono::steady_clock::time_point start)
        : fd(read_fd), options(render_options), out(*result), t0(start), phase_start(start) {}

    // Reads what the child reported so far: the caller hears every event, and the last one says
    // where a render that has to be stopped was.
    void drain() {
        if (fd < 0) return;
        char buf[4096];
        for (;;) {
            const ssize_t n = read(fd, buf, sizeof buf);
            if (n <= 0) break;
            pending.append(buf, static_cast<std::size_t>(n));
        }
        for (std::size_t nl = pending.find('\n'); nl != std::string::npos; nl = pending.find('\n')) {
            const std::string event = grader::printableText(std::string_view(pending).substr(0, nl), 1000);
            pending.erase(0, nl + 1);
            if (!drawing && event.rfind("compile ", 0) != 0) {
                drawing = true;
                phase_start = std::chrono::steady_clock::now();
                out.compile_ms = std::chrono::duration<double, std::milli>(phase_start - t0).count();
            }
            if (event.rfind("done ", 0) != 0) out.last_event = event;
            if (options.progress) options.progress(event);
        }
        if (pending.size() > 1000000) pending.clear();  // a line without end: not ours
    }

    const int fd;  // the pipe's read end; -1: none
    const RenderOptions& options;
    IsolatedRender& out;
    const std::chrono::steady_clock::time_point t0;
    std::string pending;
    bool drawing = false;  // the child reported its first scene: the draw clock runs
    std::chrono::steady_clock::time_point phase_start;
};

// How watching a child ended: `finished` is false when a limit ran out (out.limit names it).
struct ChildEnd {
    int wstatus = 0;
    bool finished = false, lost = false;  // lost: reaped elsewhere
};

ChildEnd watchChild(pid_t pid, const IsolationLimits& limits, ChildProgress& progress) {
    IsolatedRender& out = progress.out;
    ChildEnd end;
    // Poll rather than block: the parent must be able to give up on a child that never ends or
    // grows too large.
    while (true) {
        const pid_t r = waitpid(pid, &end.wstatus, WNOHANG);
        if (r == pid) {
            end.finished = true;
            break;
        }
        if (r < 0 && errno != EINTR) {  // reaped elsewhere: judge by what it left behind
            end.finished = end.lost = true;
            break;
        }
        progress.drain();
        const auto now = std::chrono::steady_clock::now();
        const double in_phase = std::chrono::duration<double>(now - progress.phase_start).count();
        if (in_phase > (progress.drawing ? limits.timeout_s : limits.compile_timeout_s)) {
            out.limit = progress.drawing ? "draw_timeout" : "compile_timeout";
            break;
        }
        const std::size_t rss = residentBytes(pid);
        out.peak_rss_bytes = std::max(out.peak_rss_bytes, rss);
        if (rss > limits.memory_bytes) {
            out.limit = "memory";
            break;
        }
        const double elapsed = std::chrono::duration<double>(now - progress.t0).count();
        std::this_thread::sleep_for(std::chrono::milliseconds(elapsed < 1.0 ? 2 : 10));
    }
    return end;
}

// The status and message of a child that ended or was killed: the limit that ran out, the signal
// it died of, or else the result it wrote.
void judgeChild(const IsolationLimits& limits, const ChildEnd& end, int result_fd, IsolatedRender* result) {
    IsolatedRender& out = *result;
    const int wstatus = end.wstatus;
    const bool lost = end.lost;
    const std::string where = whereItStopped(out.last_event);
    if (out.limit == "compile_timeout") {
        out.status = IsolatedStatus::Timeout;
        out.message = "compile timeout: not ready to draw within " + seconds(limits.compile_timeout_s) +
                      " s (the compile limit)" + where +
                      " (a very large or complex shader, e.g. a huge array or a macro that doubles "
                      "itself?); the process was killed";
    } else if (out.limit == "draw_timeout") {
        out.status = IsolatedStatus::Timeout;
        out.message = "draw timeout: drawing did not finish within " + seconds(limits.timeout_s) +
                      " s (the draw limit)" + where +
                      " (an endless or very long loop in a shader?); the process was killed";
    } else if (out.limit == "memory") {
        out.status = IsolatedStatus::Crashed;
        out.message = "memory limit: the render process used more than " +
                      std::to_string(limits.memory_bytes >> 20) + " MiB" + where +
                      " (a huge array, or a macro that doubles itself?); the process was killed";
    } else if (!lost && WIFSIGNALED(wstatus)) {
        out.status = IsolatedStatus::Crashed;
        const int sig = WTERMSIG(wstatus);
        out.message = std::string("the render process died of signal ") + std::to_string(sig) + " (" +
                      strsignal(sig) + ")" + where;
        if (sig == SIGKILL || sig == SIGSEGV || sig == SIGABRT)
            out.message += "; the shader may have crashed the driver or exceeded the memory limit";
        if (sig == SIGXCPU) out.message += "; it used more processor time than its limits allow";
    } else if (!readChildResult(result_fd, &out)) {
        out.status = IsolatedStatus::Crashed;
        out.message =
            (lost ? std::string("the render process ended")
                  : "the render process exited (code " + std::to_string(WEXITSTATUS(wstatus)) + ")") +
            " without a readable result" + where + "; out of memory?";
    }
    if (out.status == IsolatedStatus::Timeout || out.status == IsolatedStatus::Crashed) {
        out.render.status = RenderStatus::RenderError;
        out.render.scenes.clear();  // an interrupted render's images are not graded
        out.render.message = out.message;
    }
}

}  // namespace

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
    IsolatedRender out;
    // An anonymous file: the parent keeps it open, the child writes into it, and it is gone
    // with the last descriptor however either process ends.
    const int result_fd = memfd_create("shaderlab-render", MFD_CLOEXEC);
    if (result_fd < 0) {
        out.status = IsolatedStatus::RenderError;
        out.message = std::string("cannot create the result file: ") + std::strerror(errno);
        return out;
    }
    installStopHandlers();
    const auto t0 = std::chrono::steady_clock::now();
    std::fflush(nullptr);  // buffered output would otherwise be written twice
    // An inherited SIG_IGN for SIGCHLD would make the kernel reap the child itself and waitpid
    // fail; the default disposition is restored around the render.
    struct sigaction dfl {
    }, old_chld{};
    dfl.sa_handler = SIG_DFL;
    sigemptyset(&dfl.sa_mask);
    sigaction(SIGCHLD, &dfl, &old_chld);
    int progress_pipe[2] = {-1, -1};
    if (pipe2(progress_pipe, O_CLOEXEC) != 0) progress_pipe[0] = progress_pipe[1] = -1;
    const pid_t parent_pid = getpid();
    const pid_t pid = fork();
    if (pid < 0) {
        for (int fd : progress_pipe)
            if (fd >= 0) close(fd);
        close(result_fd);
        sigaction(SIGCHLD, &old_chld, nullptr);
        out.status = IsolatedStatus::RenderError;
        out.message = std::string("fork failed: ") + std::strerror(errno);
        return out;
    }
    if (pid == 0) {
        if (progress_pipe[0] >= 0) close(progress_pipe[0]);
        childMain(spec, shader_dir, backend, limits, options, result_fd, parent_pid, progress_pipe[1]);
    }
    setpgid(pid, pid);  // as the child does itself: whichever runs first
    g_render_child = pid;
    if (progress_pipe[1] >= 0) close(progress_pipe[1]);
    if (progress_pipe[0] >= 0) fcntl(progress_pipe[0], F_SETFL, O_NONBLOCK);
    // The caller's work meanwhile; should it throw, the child is still watched and reaped first.
    std::exception_ptr meanwhile_failed;
    try {
        if (while_rendering) while_rendering();
    } catch (...) {
        meanwhile_failed = std::current_exception();
    }
    ChildProgress progress(progress_pipe[0], options, &out, t0);
    ChildEnd end = watchChild(pid, limits, progress);
    progress.drain();
    if (progress_pipe[0] >= 0) close(progress_pipe[0]);
    if (!end.finished) {
        kill(-pid, SIGKILL);
        kill(pid, SIGKILL);
        // A child stuck in the kernel (a GPU driver) may take a while to die; it is reaped.
        waitpid(pid, &end.wstatus, 0);
    }
    g_render_child = 0;
    sigaction(SIGCHLD, &old_chld, nullptr);
    out.wall_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (!progress.drawing) out.compile_ms = out.wall_ms;
    judgeChild(limits, end, result_fd, &out);
    close(result_fd);
    if (meanwhile_failed) std::rethrow_exception(meanwhile_failed);
    return out;
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
