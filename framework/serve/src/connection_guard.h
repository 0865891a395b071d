// Keeps the workbench's server answering whatever its clients do. cpp-httplib gives each
// connection a thread and reads until a request is whole; it does not bound how long a client may
// hold the connection, how slowly it may send or read, or how much it may send before a line ends.
// The guard looks at the server's own connections from outside the library: every 100 ms it lists
// the process's sockets (/proc/self/fd), keeps those connected to the server's port, reads the
// kernel's TCP_INFO of each (bytes received, time since the client last sent anything), and shuts
// down a connection that
//   - has sent more than a request can be (headers and body),
//   - has been open longer than any request and response take, or
//   - has sent nothing for a while: ten seconds, or one second once many connections are open
//     (thousands of idle connections then cost a second each, not a thread each for good).
// Shutting a socket down wakes the thread blocked on it, which closes it as usual. Long-lived
// event streams are exempted by their client's port while they run. Linux only, like the rest.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <map>
#include <mutex>
#include <set>
#include <thread>

namespace shaderlab::serve {

struct GuardLimits {
    std::uint64_t max_received = std::uint64_t(1) << 20;  // bytes a connection may send in all
    double max_age_s = 60.0;                              // a connection's whole life
    double idle_s = 10.0;                                 // silence allowed when few are open
    double busy_idle_s = 1.0;                             // ... and when many are
    int busy_connections = 32;                            // "many"
};

// Calls listen() again, with the system's largest queue, on this process's socket listening on
// `port`. False when there is none.
bool widenListenQueue(int port);

class ConnectionGuard {
  public:
    ConnectionGuard() = default;
    ~ConnectionGuard() { stop(); }
    ConnectionGuard(const ConnectionGuard&) = delete;
    ConnectionGuard& operator=(const ConnectionGuard&) = delete;

    void start(int server_port, const GuardLimits& limits);
    void stop();
    // A connection from this client port is a long-lived stream while `on`.
    void exempt(int client_port, bool on);
    std::uint64_t dropped() const { return dropped_.load(); }
    int open() const { return open_.load(); }

  private:
    void loop();
    void sweep();

    int port_ = 0;
    GuardLimits limits_;
    std::thread thread_;
    std::mutex m_;
    std::condition_variable cv_;
    bool stopping_ = false;
    std::multiset<int> exempt_;
    std::map<unsigned long, double> first_seen_;  // socket inode -> seconds since start
    std::atomic<std::uint64_t> dropped_{0};
    std::atomic<int> open_{0};
};

}  // namespace shaderlab::serve
