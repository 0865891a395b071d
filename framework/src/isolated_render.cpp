// Child-process rendering; see isolated_render.h.
#include "shaderlab/isolated_render.h"

#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/resource.h>
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
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace shaderlab {

namespace {

// The render child in flight, so that a grader stopped by SIGTERM or SIGINT takes it along.
volatile sig_atomic_t g_render_child = 0;

void stopChildAndDie(int sig) {
    if (g_render_child > 0) kill(static_cast<pid_t>(g_render_child), SIGKILL);
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

bool writeBytes(const fs::path& p, const void* data, std::size_t n) {
    std::ofstream out(p, std::ios::binary);
    out.write(static_cast<const char*>(data), static_cast<std::streamsize>(n));
    return static_cast<bool>(out);
}

bool readBytes(const fs::path& p, void* data, std::size_t n) {
    std::error_code ec;
    if (fs::file_size(p, ec) != n || ec) return false;
    std::ifstream in(p, std::ios::binary);
    in.read(static_cast<char*>(data), static_cast<std::streamsize>(n));
    return static_cast<bool>(in);
}

// Child side: render, then write result.json and one raw file per image. Never returns.
[[noreturn]] void childMain(const LabSpec& spec, const std::string& shader_dir, Backend backend,
                            const IsolationLimits& limits, RenderOptions options, const fs::path& dir,
                            pid_t parent_pid, int progress_fd) {
    // Die with the grader: a parent killed by a batch system's time limit must not leave a
    // child spinning on a shader. If it is already gone, stop now.
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != parent_pid) _exit(1);
#if !defined(__SANITIZE_ADDRESS__)
    // (AddressSanitizer maps terabytes of shadow memory up front, so a sanitizer build goes
    // without the address-space limit.)
    rlimit as{};
    as.rlim_cur = as.rlim_max = limits.memory_bytes;
    setrlimit(RLIMIT_AS, &as);
#endif
    // A backstop should the parent's clock fail: CPU seconds of all the driver's threads.
    const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
    rlimit cpu{};
    cpu.rlim_cur = cpu.rlim_max = static_cast<rlim_t>(limits.timeout_s * threads + 10.0);
    setrlimit(RLIMIT_CPU, &cpu);
    rlimit core{};  // a crashing driver should not litter core files
    setrlimit(RLIMIT_CORE, &core);

    json result;
    ContextResult ctx = createHeadlessContext(backend);
    if (!ctx.context) {
        result["status"] = "render_error";
        result["message"] = ctx.error;
    } else {
        result["renderer"] = ctx.context->info().renderer + ", OpenGL " + ctx.context->info().version;
        // Progress goes to the parent line by line, so it can say where a render stopped.
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
        json diags = json::array();
        for (const Diagnostic& d : r.diagnostics)
            diags.push_back({{"file", d.file},
                             {"line", d.line},
                             {"column", d.column},
                             {"severity", d.severity},
                             {"message", d.message},
                             {"explanation", d.explanation},
                             {"source_line", d.source_line},
                             {"driver_message", d.driver_message},
                             {"follow_on", d.follow_on}});
        result["diagnostics"] = diags;
        json scenes = json::array();
        int n = 0;
        for (const SceneRender& s : r.scenes) {
            json passes = json::array();
            for (const PassImage& p : s.passes) {
                const std::string stem = "img" + std::to_string(n++);
                writeBytes(dir / (stem + ".rgba"), p.color.pixels.data(),
                           p.color.pixels.size() * sizeof(float));
                writeBytes(dir / (stem + ".cov"), p.coverage.data(), p.coverage.size());
                passes.push_back({{"pass", p.pass},
                                  {"target", p.target},
                                  {"attachment", p.attachment},
                                  {"graded", p.graded},
                                  {"width", p.color.width},
                                  {"height", p.color.height},
                                  {"file", stem}});
            }
            scenes.push_back(
                {{"scene", s.scene}, {"render_ms", s.render_ms}, {"passes", passes}, {"error", s.error}});
        }
        result["scenes"] = scenes;
    }
    // Shader logs may hold any bytes the student typed: replace invalid UTF-8 rather than throw.
    const std::string text = result.dump(-1, ' ', false, json::error_handler_t::replace);
    writeBytes(dir / "result.json.tmp", text.data(), text.size());
    std::error_code ec;
    fs::rename(dir / "result.json.tmp", dir / "result.json", ec);
    // _exit: skip atexit handlers and static destructors of the copied parent state.
    std::fflush(nullptr);
    _exit(0);
}

// " while <what the child was doing>", from its last progress event.
std::string whereItStopped(const std::string& event) {
    std::istringstream in(event);
    std::string kind, a, b;
    in >> kind >> a >> b;
    if (kind == "compile")
        return " while compiling " + a + " and " + b + " (a very large or complex shader?)";
    if (kind == "pass")
        return " while drawing pass '" + b + "' of scene '" + a +
               "' (an endless or very long loop in a shader?)";
    if (kind == "scene") return " while setting up scene '" + a + "'";
    return " (an endless loop in a shader?)";
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

// Parent side: read what the child wrote, trusting nothing about sizes.
bool readChildResult(const fs::path& dir, IsolatedRender* out) {
    std::ifstream in(dir / "result.json");
    if (!in) return false;
    json result = json::parse(in, nullptr, false);
    if (result.is_discarded() || !result.is_object()) return false;
    out->status = statusFromName(result.value("status", ""));
    out->message = result.value("message", "");
    out->renderer = result.value("renderer", "");
    out->render.status = renderStatusOf(out->status);
    out->render.message = out->message;
    for (const json& d : result.value("diagnostics", json::array())) {
        out->render.diagnostics.push_back({d.value("file", ""), d.value("line", 0), d.value("column", 0),
                                           d.value("severity", ""), d.value("message", ""),
                                           d.value("explanation", ""), d.value("source_line", ""),
                                           d.value("driver_message", ""), d.value("follow_on", 0)});
    }
    for (const json& s : result.value("scenes", json::array())) {
        SceneRender scene;
        scene.scene = s.value("scene", "");
        scene.render_ms = s.value("render_ms", 0.0);
        scene.error = s.value("error", "");
        for (const json& p : s.value("passes", json::array())) {
            PassImage img;
            img.pass = p.value("pass", "");
            img.target = p.value("target", "");
            img.attachment = p.value("attachment", "");
            img.graded = p.value("graded", false);
            const int w = p.value("width", 0), h = p.value("height", 0);
            if (w <= 0 || h <= 0 || w > 6 * 4096 || h > 4096) return false;
            img.color = grader::Image(w, h, 4);
            img.coverage.resize(static_cast<std::size_t>(w) * h);
            const std::string stem = p.value("file", "");
            if (!readBytes(dir / (stem + ".rgba"), img.color.pixels.data(),
                           img.color.pixels.size() * sizeof(float)) ||
                !readBytes(dir / (stem + ".cov"), img.coverage.data(), img.coverage.size()))
                return false;
            scene.passes.push_back(std::move(img));
        }
        out->render.scenes.push_back(std::move(scene));
    }
    return true;
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
                                 const IsolationLimits& limits, const RenderOptions& options) {
    IsolatedRender out;
    char tmpl[] = "/tmp/shaderlab-render-XXXXXX";
    if (!mkdtemp(tmpl)) {
        out.status = IsolatedStatus::RenderError;
        out.message = std::string("cannot create a temporary folder: ") + std::strerror(errno);
        return out;
    }
    const fs::path dir = tmpl;
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
        sigaction(SIGCHLD, &old_chld, nullptr);
        out.status = IsolatedStatus::RenderError;
        out.message = std::string("fork failed: ") + std::strerror(errno);
        fs::remove_all(dir);
        return out;
    }
    if (pid == 0) {
        if (progress_pipe[0] >= 0) close(progress_pipe[0]);
        childMain(spec, shader_dir, backend, limits, options, dir, parent_pid, progress_pipe[1]);
    }
    g_render_child = pid;
    if (progress_pipe[1] >= 0) close(progress_pipe[1]);
    if (progress_pipe[0] >= 0) fcntl(progress_pipe[0], F_SETFL, O_NONBLOCK);
    std::string pending;
    // Reads what the child reported so far: the caller hears every event, and the last one says
    // where a render that has to be stopped was.
    auto drainProgress = [&]() {
        if (progress_pipe[0] < 0) return;
        char buf[4096];
        for (;;) {
            const ssize_t n = read(progress_pipe[0], buf, sizeof buf);
            if (n <= 0) break;
            pending.append(buf, static_cast<std::size_t>(n));
        }
        for (std::size_t nl = pending.find('\n'); nl != std::string::npos; nl = pending.find('\n')) {
            std::string event = pending.substr(0, nl);
            pending.erase(0, nl + 1);
            if (event.size() > 1000) event.resize(1000);
            if (event.rfind("done ", 0) != 0) out.last_event = event;
            if (options.progress) options.progress(event);
        }
        if (pending.size() > 1000000) pending.clear();  // a line without end: not ours
    };

    int wstatus = 0;
    bool finished = false, lost = false;
    // Poll rather than block: the parent must be able to give up on a child that never ends.
    while (true) {
        const pid_t r = waitpid(pid, &wstatus, WNOHANG);
        if (r == pid) {
            finished = true;
            break;
        }
        if (r < 0 && errno != EINTR) {  // reaped elsewhere: judge by what it left behind
            finished = lost = true;
            break;
        }
        const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (elapsed > limits.timeout_s) break;
        drainProgress();
        std::this_thread::sleep_for(std::chrono::milliseconds(elapsed < 1.0 ? 2 : 20));
    }
    drainProgress();
    if (progress_pipe[0] >= 0) close(progress_pipe[0]);
    if (!finished) {
        kill(pid, SIGKILL);
        // Bounded: a child stuck in the kernel (a GPU driver) may take a while to die.
        for (int i = 0; i < 500 && waitpid(pid, &wstatus, WNOHANG) == 0; ++i)
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    g_render_child = 0;
    sigaction(SIGCHLD, &old_chld, nullptr);
    out.wall_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (!finished) {
        kill(pid, SIGKILL);
        waitpid(pid, &wstatus, 0);
        out.status = IsolatedStatus::Timeout;
        char buf[64];
        std::snprintf(buf, sizeof buf, "%.0f", limits.timeout_s);
        out.message = "rendering did not finish within " + std::string(buf) + " s" +
                      whereItStopped(out.last_event) + "; the process was killed";
    } else if (!lost && WIFSIGNALED(wstatus)) {
        out.status = IsolatedStatus::Crashed;
        const int sig = WTERMSIG(wstatus);
        out.message = std::string("the render process died of signal ") + std::to_string(sig) + " (" +
                      strsignal(sig) + ")";
        if (sig == SIGKILL || sig == SIGSEGV || sig == SIGABRT)
            out.message += "; the shader may have crashed the driver or exceeded the memory limit";
    } else if (!readChildResult(dir, &out)) {
        out.status = IsolatedStatus::Crashed;
        out.message =
            (lost ? std::string("the render process ended")
                  : "the render process exited (code " + std::to_string(WEXITSTATUS(wstatus)) + ")") +
            " without a readable result; out of memory?";
    }
    if (out.status == IsolatedStatus::Timeout || out.status == IsolatedStatus::Crashed) {
        out.render.status = RenderStatus::RenderError;
        out.render.message = out.message;
    }
    std::error_code ec;
    fs::remove_all(dir, ec);
    return out;
}

}  // namespace shaderlab
