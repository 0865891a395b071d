// The viewer's render server; see render_service.h. The protocol over two pipes: a request is
// one JSON line; an answer is a 64-bit length, that many bytes of JSON (status, message,
// diagnostics, scenes and the size of every image), then each image's floats and coverage bytes.
#include "shaderlab/live/render_service.h"

#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdint>
#include <cstring>
#include <nlohmann/json.hpp>

#include "shaderlab/grading/grading.h"
#include "shaderlab/render/debug_view.h"

namespace shaderlab::viewer {

using json = nlohmann::json;

namespace {

bool writeAll(int fd, const void* data, std::size_t n) {
    const char* p = static_cast<const char*>(data);
    while (n > 0) {
        const ssize_t w = write(fd, p, n);
        if (w < 0 && errno == EINTR) continue;
        if (w <= 0) return false;
        p += w;
        n -= static_cast<std::size_t>(w);
    }
    return true;
}

bool readAll(int fd, void* data, std::size_t n) {
    char* p = static_cast<char*>(data);
    while (n > 0) {
        const ssize_t r = read(fd, p, n);
        if (r < 0 && errno == EINTR) continue;
        if (r <= 0) return false;
        p += r;
        n -= static_cast<std::size_t>(r);
    }
    return true;
}

IsolatedStatus statusFromName(const std::string& s) {
    for (IsolatedStatus st :
         {IsolatedStatus::Ok, IsolatedStatus::Missing, IsolatedStatus::CompileError,
          IsolatedStatus::LinkError, IsolatedStatus::RenderError, IsolatedStatus::Timeout})
        if (s == isolatedStatusName(st)) return st;
    return IsolatedStatus::Crashed;
}

Diagnostic diagnosticFrom(const json& d) {
    return {d.value("file", ""),        d.value("line", 0),
            d.value("column", 0),       d.value("severity", ""),
            d.value("message", ""),     d.value("explanation", ""),
            d.value("source_line", ""), d.value("driver_message", ""),
            d.value("follow_on", 0)};
}

bool sendAnswer(int fd, const IsolatedRender& r) {
    json head = {{"status", isolatedStatusName(r.status)},
                 {"message", r.message},
                 {"renderer", r.renderer},
                 {"last_event", r.last_event},
                 {"limit", r.limit},
                 {"endless_loop", r.render.endless_loop},
                 {"wall_ms", r.wall_ms}};
    json diags = json::array();
    for (const Diagnostic& d : r.render.diagnostics) diags.push_back(diagnosticToJson(d));
    head["diagnostics"] = diags;
    json scenes = json::array();
    for (const SceneRender& s : r.render.scenes) {
        json passes = json::array();
        for (const PassImage& p : s.passes)
            passes.push_back({{"pass", p.pass},
                              {"target", p.target},
                              {"attachment", p.attachment},
                              {"graded", p.graded},
                              {"width", p.color.width},
                              {"height", p.color.height},
                              {"channels", p.color.channels},
                              {"coverage", p.coverage.size()}});
        scenes.push_back({{"scene", s.scene}, {"render_ms", s.render_ms}, {"passes", passes}});
    }
    head["scenes"] = scenes;
    const std::string text = head.dump(-1, ' ', false, json::error_handler_t::replace);
    const std::uint64_t n = text.size();
    if (!writeAll(fd, &n, sizeof n) || !writeAll(fd, text.data(), text.size())) return false;
    for (const SceneRender& s : r.render.scenes)
        for (const PassImage& p : s.passes)
            if (!writeAll(fd, p.color.pixels.data(), p.color.pixels.size() * sizeof(float)) ||
                !writeAll(fd, p.coverage.data(), p.coverage.size()))
                return false;
    return true;
}

bool readAnswer(int fd, IsolatedRender* out) {
    std::uint64_t n = 0;
    if (!readAll(fd, &n, sizeof n) || n > (64u << 20)) return false;
    std::string text(n, '\0');
    if (!readAll(fd, text.data(), n)) return false;
    const json head = json::parse(text, nullptr, false);
    if (head.is_discarded() || !head.is_object()) return false;
    out->status = statusFromName(head.value("status", ""));
    out->message = head.value("message", "");
    out->renderer = head.value("renderer", "");
    out->last_event = head.value("last_event", "");
    out->limit = head.value("limit", "");
    out->render.endless_loop = head.value("endless_loop", false);
    out->wall_ms = head.value("wall_ms", 0.0);
    out->render.message = out->message;
    out->render.status = out->status == IsolatedStatus::Ok ? RenderStatus::Ok : RenderStatus::RenderError;
    for (const json& d : head.value("diagnostics", json::array()))
        out->render.diagnostics.push_back(diagnosticFrom(d));
    for (const json& s : head.value("scenes", json::array())) {
        SceneRender scene;
        scene.scene = s.value("scene", "");
        scene.render_ms = s.value("render_ms", 0.0);
        for (const json& p : s.value("passes", json::array())) {
            PassImage img;
            img.pass = p.value("pass", "");
            img.target = p.value("target", "");
            img.attachment = p.value("attachment", "");
            img.graded = p.value("graded", false);
            const int w = p.value("width", 0), h = p.value("height", 0), c = p.value("channels", 4);
            const std::size_t cov = p.value("coverage", std::size_t(0));
            if (w < 0 || h < 0 || w > 6 * 4096 || h > 4096 || c < 1 || c > 4 || cov > std::size_t(w) * h)
                return false;
            img.color = grader::Image(w, h, c);
            img.coverage.resize(cov);
            if (!readAll(fd, img.color.pixels.data(), img.color.pixels.size() * sizeof(float)) ||
                !readAll(fd, img.coverage.data(), cov))
                return false;
            scene.passes.push_back(std::move(img));
        }
        out->render.scenes.push_back(std::move(scene));
    }
    return true;
}

bool sendText(int fd, const std::string& text) {
    const std::uint64_t n = text.size();
    return writeAll(fd, &n, sizeof n) && writeAll(fd, text.data(), text.size());
}

// The lab graded as `check` grades it, as report.json's text.
std::string gradeAnswer(const LabSpec& spec, Backend backend, const json& req) {
    GradeOptions options;
    options.backend = backend;
    options.labs_root = req.value("labs", "");
    options.reference_root = req.value("reference", "");
    options.labs = {spec.id};
    options.limits.timeout_s = req.value("timeout", 10.0);
    options.limits.compile_timeout_s = req.value("compile_timeout", 30.0);
    options.limits.memory_bytes = req.value("memory", std::size_t(2048) << 20);
    return grader::reportToJson(gradeSubmission(req.value("submission", ""), options));
}

[[noreturn]] void serverMain(const LabSpec& spec, Backend backend, int in_fd, int out_fd) {
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    std::string line;
    char c;
    for (;;) {
        line.clear();
        while (true) {
            const ssize_t r = read(in_fd, &c, 1);
            if (r < 0 && errno == EINTR) continue;
            if (r <= 0) _exit(0);  // the window closed the pipe
            if (c == '\n') break;
            line.push_back(c);
        }
        const json req = json::parse(line, nullptr, false);
        if (req.is_object() && req.value("kind", "") == "grade") {
            if (!sendText(out_fd, gradeAnswer(spec, backend, req))) _exit(0);
            continue;
        }
        IsolatedRender result;
        if (req.is_discarded() || !req.is_object()) {
            result.status = IsolatedStatus::RenderError;
            result.message = "viewer: malformed render request";
        } else {
            RenderOptions options;
            options.keep_all_passes = true;
            options.only_scenes = {req.value("scene", "")};
            options.containment_root = req.value("root", "");
            options.orbit.yaw_deg = req.value("yaw", 0.0f);
            options.orbit.pitch_deg = req.value("pitch", 0.0f);
            options.orbit.zoom = req.value("zoom", 1.0f);
            parseDebugView(req.value("debug", "off"), &options.debug_view);
            IsolationLimits limits;
            limits.timeout_s = req.value("timeout", 5.0);
            result = renderLabIsolated(spec, req.value("dir", ""), backend, limits, options);
        }
        if (!sendAnswer(out_fd, result)) _exit(0);
    }
}

}  // namespace

std::unique_ptr<RenderService> RenderService::start(const LabSpec& spec, Backend backend,
                                                    std::string* error) {
    int to_server[2], from_server[2];
    if (pipe2(to_server, O_CLOEXEC) != 0) {
        *error = std::string("cannot create a pipe: ") + std::strerror(errno);
        return nullptr;
    }
    if (pipe2(from_server, O_CLOEXEC) != 0) {
        *error = std::string("cannot create a pipe: ") + std::strerror(errno);
        close(to_server[0]);
        close(to_server[1]);
        return nullptr;
    }
    std::fflush(nullptr);
    const pid_t pid = fork();
    if (pid < 0) {
        *error = std::string("fork failed: ") + std::strerror(errno);
        for (int fd : {to_server[0], to_server[1], from_server[0], from_server[1]}) close(fd);
        return nullptr;
    }
    if (pid == 0) {
        close(to_server[1]);
        close(from_server[0]);
        serverMain(spec, backend, to_server[0], from_server[1]);
    }
    close(to_server[0]);
    close(from_server[1]);
    // A server gone away must give an error answer, not kill the window with SIGPIPE.
    signal(SIGPIPE, SIG_IGN);
    std::unique_ptr<RenderService> service(new RenderService());
    service->pid_ = pid;
    service->to_server_ = to_server[1];
    service->from_server_ = from_server[0];
    return service;
}

RenderService::~RenderService() {
    if (to_server_ >= 0) close(to_server_);
    if (from_server_ >= 0) close(from_server_);
    if (pid_ > 0) {
        kill(pid_, SIGKILL);
        waitpid(pid_, nullptr, 0);
    }
}

bool RenderService::grade(const GradeRequest& request, grader::Report* out, std::string* error) {
    const json req = {{"kind", "grade"},
                      {"submission", request.submission_root},
                      {"labs", request.labs_root},
                      {"reference", request.reference_root},
                      {"timeout", request.limits.timeout_s},
                      {"compile_timeout", request.limits.compile_timeout_s},
                      {"memory", request.limits.memory_bytes}};
    const std::string line = req.dump(-1, ' ', false, json::error_handler_t::replace) + "\n";
    std::uint64_t n = 0;
    std::string text;
    if (!writeAll(to_server_, line.data(), line.size()) || !readAll(from_server_, &n, sizeof n) ||
        n > (64u << 20)) {
        *error = "the render process stopped answering";
        return false;
    }
    text.resize(n);
    if (!readAll(from_server_, text.data(), n)) {
        *error = "the render process stopped answering";
        return false;
    }
    return grader::reportFromJson(text, out, error);
}

void RenderService::shutdown() {
    if (pid_ > 0) kill(pid_, SIGKILL);
}

IsolatedRender RenderService::render(const RenderRequest& request) {
    const json req = {{"dir", request.shader_dir},        {"root", request.containment_root},
                      {"scene", request.scene},           {"yaw", request.orbit.yaw_deg},
                      {"pitch", request.orbit.pitch_deg}, {"zoom", request.orbit.zoom},
                      {"timeout", request.timeout_s},     {"debug", debugViewName(request.debug_view)}};
    const std::string line = req.dump(-1, ' ', false, json::error_handler_t::replace) + "\n";
    IsolatedRender out;
    if (!writeAll(to_server_, line.data(), line.size()) || !readAnswer(from_server_, &out)) {
        out = IsolatedRender();
        out.status = IsolatedStatus::Crashed;
        out.message = "the viewer's render process stopped answering; restart `shaderlab view`";
        out.render.status = RenderStatus::RenderError;
        out.render.message = out.message;
    }
    return out;
}

}  // namespace shaderlab::viewer
