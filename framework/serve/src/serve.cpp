// The workbench's HTTP server: routes (routes.h) to the workbench (workbench.h), with the limits
// that keep one page, or a hostile client, from stalling it (connection_guard.h, docs/students.md).
#include "shaderlab/serve/serve.h"

#include <httplib.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <pthread.h>
#include <signal.h>
#include <sys/socket.h>

#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <memory>
#include <mutex>
#include <thread>

#include "connection_guard.h"
#include "shaderlab/render/debug_view.h"
#include "shaderlab/serve/routes.h"

using json = nlohmann::json;

namespace shaderlab::serve {

namespace {

// One thread per connection, at most `max` at once: the accept loop waits for a free one, so a
// flood of connections queues in the kernel instead of in memory. (cpp-httplib's own pool holds
// a fixed number of threads and an unbounded queue: eight idle clients would stall it.)
class ConnectionThreads : public httplib::TaskQueue {
  public:
    explicit ConnectionThreads(int max) : max_(max) {}
#if SHADERLAB_HTTPLIB_ENQUEUE_BOOL
    bool enqueue(std::function<void()> fn) override {
        run(std::move(fn));
        return true;
    }
#else
    void enqueue(std::function<void()> fn) override { run(std::move(fn)); }
#endif
    void shutdown() override {
        std::unique_lock<std::mutex> lock(m_);
        cv_.wait(lock, [this] { return running_ == 0; });
    }

  private:
    void run(std::function<void()> fn) {
        {
            std::unique_lock<std::mutex> lock(m_);
            cv_.wait(lock, [this] { return running_ < max_; });
            ++running_;
        }
        std::thread([this, fn = std::move(fn)] {
            fn();
            std::lock_guard<std::mutex> lock(m_);
            --running_;
            cv_.notify_all();
        }).detach();
    }

    int max_;
    int running_ = 0;
    std::mutex m_;
    std::condition_variable cv_;
};

bool loopback(const std::string& host) { return host == "127.0.0.1" || host == "localhost" || host == "::1"; }

void sendJson(httplib::Response& res, const json& j) {
    res.set_header("Cache-Control", "no-store");
    res.set_content(j.dump(-1, ' ', false, json::error_handler_t::replace), "application/json");
}

void sendError(httplib::Response& res, int status, const std::string& message) {
    res.status = status;
    sendJson(res, {{"error", message}});
}

struct Server {
    const ServeOptions& opt;
    Workbench& bench;
    ConnectionGuard& guard;
    httplib::Server http;
    std::mutex streams_m;
    int streams = 0;
    std::atomic<bool> stopping{false};

    void handle(const httplib::Request& req, httplib::Response& res);
    void events(const httplib::Request& req, httplib::Response& res);
    void view(const httplib::Request& req, httplib::Response& res);
};

void Server::handle(const httplib::Request& req, httplib::Response& res) {
    // No page of ours is meant to be framed or sniffed into another type.
    res.set_header("X-Content-Type-Options", "nosniff");
    res.set_header("X-Frame-Options", "DENY");
    if (req.headers.size() > 64) return sendError(res, 431, "too many header fields");
    const Route route = routeRequest(req.method, req.path);
    switch (route.kind) {
        case RouteKind::NotFound:
            return sendError(res, 404, "no such page");
        case RouteKind::MethodNotAllowed:
            return sendError(res, 405, "method not allowed here");
        case RouteKind::Page:
        case RouteKind::Asset: {
            const Asset* a = findAsset(route.kind == RouteKind::Page ? "index.html" : route.asset);
            if (!a) return sendError(res, 404, "no such page");
            res.set_header("Cache-Control", "no-cache");
            res.set_header("Content-Security-Policy",
                           "default-src 'self'; img-src 'self' blob:; style-src 'self'; script-src 'self'");
            res.set_content(std::string(reinterpret_cast<const char*>(a->data), a->size), a->content_type);
            return;
        }
        case RouteKind::State:
            return sendJson(res, bench.state());
        case RouteKind::Events:
            return events(req, res);
        case RouteKind::View:
            return view(req, res);
        case RouteKind::Picture: {
            const PictureKind kind = route.picture == "student"     ? PictureKind::Student
                                     : route.picture == "reference" ? PictureKind::Reference
                                     : route.picture == "diff"      ? PictureKind::Diff
                                     : route.picture == "debug"     ? PictureKind::Debug
                                                                    : PictureKind::File;
            std::string png;
            if (!bench.picture(route.seq, kind, route.index, &png))
                return sendError(res, 404, "no such picture (an older one: ask /api/state again)");
            // A picture's number never names other pixels: it may be cached for good.
            res.set_header("Cache-Control",
                           kind == PictureKind::File ? "no-cache" : "max-age=3600, immutable");
            res.set_content(png, "image/png");
            return;
        }
        case RouteKind::Pixel: {
            json out;
            if (!bench.pixel(route.seq, route.index, route.x, route.y, &out))
                return sendError(res, 404, "no such pixel");
            return sendJson(res, out);
        }
    }
}

// Server-Sent Events (HTML Living Standard, "Server-sent events"): one "state" event carrying the
// whole state (one line of JSON) whenever it changes, so a page needs no second request to follow,
// and a comment every 15 s so that proxies keep the stream open.
void Server::events(const httplib::Request& req, httplib::Response& res) {
    {
        std::lock_guard<std::mutex> lock(streams_m);
        if (streams >= opt.max_event_streams) return sendError(res, 503, "too many pages are open");
        ++streams;
    }
    const int client_port = req.remote_port;
    guard.exempt(client_port, true);
    auto seen = std::make_shared<std::uint64_t>(0);
    res.set_header("Cache-Control", "no-store");
    res.set_chunked_content_provider(
        "text/event-stream",
        [this, seen](std::size_t, httplib::DataSink& sink) {
            if (stopping) return false;
            const std::uint64_t v =
                *seen == 0 ? bench.version() : bench.waitForChange(*seen, std::chrono::seconds(15));
            if (stopping) return false;
            std::string msg = ": still here\n\n";
            if (v != *seen) {
                const json state = bench.state();
                msg = "event: state\ndata: " + state.dump(-1, ' ', false, json::error_handler_t::replace) +
                      "\n\n";
                *seen = state.value("version", v);
            }
            return sink.write(msg.data(), msg.size());
        },
        [this, client_port](bool) {
            guard.exempt(client_port, false);
            std::lock_guard<std::mutex> lock(streams_m);
            --streams;
        });
}

void Server::view(const httplib::Request& req, httplib::Response& res) {
    const json body = json::parse(req.body, nullptr, false);
    if (!body.is_object()) return sendError(res, 400, "the view is a JSON object");
    CameraOrbit orbit;
    std::string scene, debug_name;
    try {
        scene = body.value("scene", std::string());
        debug_name = body.value("debug", std::string("off"));
        orbit.yaw_deg = body.value("yaw", 0.0f);
        orbit.pitch_deg = std::clamp(body.value("pitch", 0.0f), -89.0f, 89.0f);
        orbit.zoom = std::clamp(body.value("zoom", 1.0f), 0.1f, 10.0f);
    } catch (const json::exception&) {
        return sendError(res, 400, "scene and debug are strings; yaw, pitch and zoom are numbers");
    }
    DebugView debug = DebugView::Off;
    if (!parseDebugView(debug_name, &debug))
        return sendError(res, 400, "debug is one of " + debugViewNames(", "));
    if (!std::isfinite(orbit.yaw_deg)) orbit.yaw_deg = 0.0f;
    std::string error;
    if (!bench.setView(scene, orbit, debug, &error)) return sendError(res, 400, error);
    sendJson(res, {{"ok", true}, {"version", bench.version()}});
}

}  // namespace

int runServe(const ServeOptions& given) {
    ServeOptions options = given;
    // The terminal follows the page as `view`'s does: saves, pictures, errors, grades.
    auto said = std::make_shared<std::mutex>();
    if (!options.workbench.say)
        options.workbench.say = [said](const std::string& message) {
            std::lock_guard<std::mutex> lock(*said);
            std::string out;
            std::size_t start = 0;
            for (std::size_t end; start <= message.size(); start = end + 1) {
                end = message.find('\n', start);
                if (end == std::string::npos) end = message.size();
                out += (start == 0 ? "serve: " : "       ") + message.substr(start, end - start) + "\n";
            }
            std::fputs(out.c_str(), stdout);
            std::fflush(stdout);
        };
    std::string error;
    // The render server is forked first, before this process has any thread.
    std::unique_ptr<Workbench> bench = Workbench::create(options.workbench, &error);
    if (!bench) {
        std::fprintf(stderr, "shaderlab serve: cannot start the render process: %s\n", error.c_str());
        return 2;
    }
    // SIGINT and SIGTERM are taken by one thread (sigwait), never by a thread inside the server.
    sigset_t stop_signals;
    sigemptyset(&stop_signals);
    sigaddset(&stop_signals, SIGINT);
    sigaddset(&stop_signals, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &stop_signals, nullptr);
    signal(SIGPIPE, SIG_IGN);

    ConnectionGuard guard;
    Server server{options, *bench, guard, {}, {}, 0, {false}};
    httplib::Server& http = server.http;
    http.new_task_queue = [&options] { return new ConnectionThreads(options.max_connections); };
    http.set_read_timeout(5, 0);
    http.set_write_timeout(5, 0);
    http.set_keep_alive_timeout(5);
    http.set_keep_alive_max_count(50);
    http.set_payload_max_length(options.max_body);
    auto handler = [&server](const httplib::Request& req, httplib::Response& res) {
        server.handle(req, res);
    };
    http.Get(".*", handler);
    http.Post(".*", handler);
    http.Put(".*", handler);
    http.Delete(".*", handler);
    http.Options(".*", handler);
    http.Patch(".*", handler);

    // cpp-httplib's own socket options add SO_REUSEPORT, with which a second `shaderlab serve` binds
    // the same port and takes half the requests: SO_REUSEADDR only. TCP_USER_TIMEOUT (accepted
    // sockets inherit it from the listening one) lets the kernel give up on a client that has taken
    // nothing it was sent for 10 s, even after the server closed the socket with the rest queued.
    http.set_socket_options([](socket_t sock) {
        int yes = 1;
        setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
        unsigned int stalled_ms = 10000;
        setsockopt(sock, IPPROTO_TCP, TCP_USER_TIMEOUT, &stalled_ms, sizeof stalled_ms);
    });
    const int port = options.port == 0 ? http.bind_to_any_port(options.host)
                                       : (http.bind_to_port(options.host, options.port) ? options.port : -1);
    if (port <= 0) {
        std::fprintf(stderr,
                     "shaderlab serve: cannot listen on %s port %d (is another `shaderlab serve` using it? "
                     "--port picks another, --port 0 any free one)\n",
                     options.host.c_str(), options.port);
        return 2;
    }
    // The library listens with a queue of 5: a burst of connections (a page's pictures, a flood)
    // would lose some for a second. Linux resizes the queue of a socket already listening.
    widenListenQueue(port);
    const std::string shown_host =
        options.host.find(':') != std::string::npos ? "[" + options.host + "]" : options.host;
    std::printf("shaderlab serve: lab %s, your files in %s/%s\n", options.workbench.spec.id.c_str(),
                options.workbench.submission_root.c_str(), options.workbench.spec.id.c_str());
    if (!loopback(options.host))
        std::printf(
            "shaderlab serve: WARNING: listening on %s, not only on this machine: anyone who can reach it on "
            "port "
            "%d sees your lab and can make it render. Prefer the default (127.0.0.1) with SSH port "
            "forwarding "
            "(docs/students.md).\n",
            options.host.c_str(), port);
    // An address that means "every interface" is no address to open: this machine reaches it on
    // its loopback (and a container's published port lands there too).
    const bool any_address = options.host == "0.0.0.0" || options.host == "::" || options.host == "[::]";
    std::printf("shaderlab serve: open http://%s:%d/ in your browser (Ctrl-C stops)\n",
                loopback(options.host) || any_address ? "127.0.0.1" : shown_host.c_str(), port);
    if (any_address)
        std::printf("shaderlab serve: from another machine: http://<this machine's name or address>:%d/\n",
                    port);
    std::fflush(stdout);

    guard.start(port, GuardLimits());
    bench->start();
    std::thread stopper([&] {
        int sig = 0;
        sigwait(&stop_signals, &sig);
        server.stopping = true;
        bench->stop();  // wakes the event streams
        http.stop();
    });
    const bool listened = http.listen_after_bind();
    if (!server.stopping) {  // the server stopped on its own: let the stopper go
        server.stopping = true;
        pthread_kill(stopper.native_handle(), SIGTERM);
    }
    stopper.join();
    guard.stop();
    bench->stop();
    std::printf("shaderlab serve: stopped\n");
    return listened ? 0 : 2;
}

}  // namespace shaderlab::serve
