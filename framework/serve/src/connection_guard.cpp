#include "connection_guard.h"

#include <arpa/inet.h>
#include <dirent.h>
#include <linux/tcp.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace shaderlab::serve {

namespace {

double nowSeconds() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// The socket inode an fd refers to ("socket:[1234]"), or 0.
unsigned long socketInode(int fd) {
    char link[64];
    const std::string path = "/proc/self/fd/" + std::to_string(fd);
    const ssize_t n = readlink(path.c_str(), link, sizeof link - 1);
    if (n <= 0) return 0;
    link[n] = '\0';
    if (std::strncmp(link, "socket:[", 8) != 0) return 0;
    return std::strtoul(link + 8, nullptr, 10);
}

int portOf(const sockaddr_storage& a) {
    if (a.ss_family == AF_INET) return ntohs(reinterpret_cast<const sockaddr_in&>(a).sin_port);
    if (a.ss_family == AF_INET6) return ntohs(reinterpret_cast<const sockaddr_in6&>(a).sin6_port);
    return -1;
}

}  // namespace

bool widenListenQueue(int port) {
    DIR* dir = opendir("/proc/self/fd");
    if (!dir) return false;
    bool done = false;
    while (const dirent* e = readdir(dir)) {
        if (e->d_name[0] < '0' || e->d_name[0] > '9') continue;
        const int fd = std::atoi(e->d_name);
        int listening = 0;
        socklen_t len = sizeof listening;
        sockaddr_storage local{};
        socklen_t local_len = sizeof local;
        if (fd == dirfd(dir) || getsockopt(fd, SOL_SOCKET, SO_ACCEPTCONN, &listening, &len) != 0 ||
            !listening || getsockname(fd, reinterpret_cast<sockaddr*>(&local), &local_len) != 0 ||
            portOf(local) != port)
            continue;
        done = listen(fd, SOMAXCONN) == 0 || done;
    }
    closedir(dir);
    return done;
}

void ConnectionGuard::start(int server_port, const GuardLimits& limits) {
    port_ = server_port;
    limits_ = limits;
    thread_ = std::thread([this] { loop(); });
}

void ConnectionGuard::stop() {
    {
        std::lock_guard<std::mutex> lock(m_);
        stopping_ = true;
    }
    cv_.notify_all();
    if (thread_.joinable()) thread_.join();
}

void ConnectionGuard::exempt(int client_port, bool on) {
    std::lock_guard<std::mutex> lock(m_);
    if (on) {
        exempt_.insert(client_port);
    } else {
        const auto it = exempt_.find(client_port);
        if (it != exempt_.end()) exempt_.erase(it);
    }
}

void ConnectionGuard::loop() {
    for (;;) {
        {
            std::unique_lock<std::mutex> lock(m_);
            if (cv_.wait_for(lock, std::chrono::milliseconds(100), [this] { return stopping_; })) return;
        }
        sweep();
    }
}

void ConnectionGuard::sweep() {
    struct Conn {
        int fd;
        unsigned long inode;
        int client_port;
        tcp_info info;
    };
    std::vector<Conn> conns;
    DIR* dir = opendir("/proc/self/fd");
    if (!dir) return;
    while (const dirent* e = readdir(dir)) {
        if (e->d_name[0] < '0' || e->d_name[0] > '9') continue;
        const int fd = std::atoi(e->d_name);
        if (fd == dirfd(dir)) continue;
        sockaddr_storage local{}, peer{};
        socklen_t local_len = sizeof local, peer_len = sizeof peer;
        if (getsockname(fd, reinterpret_cast<sockaddr*>(&local), &local_len) != 0 || portOf(local) != port_)
            continue;
        // The listening socket has no peer.
        if (getpeername(fd, reinterpret_cast<sockaddr*>(&peer), &peer_len) != 0) continue;
        Conn c{fd, socketInode(fd), portOf(peer), {}};
        socklen_t info_len = sizeof c.info;
        if (c.inode == 0 || getsockopt(fd, IPPROTO_TCP, TCP_INFO, &c.info, &info_len) != 0) continue;
        conns.push_back(c);
    }
    closedir(dir);
    open_ = static_cast<int>(conns.size());

    const double now = nowSeconds();
    const double idle_limit =
        static_cast<int>(conns.size()) > limits_.busy_connections ? limits_.busy_idle_s : limits_.idle_s;
    std::map<unsigned long, double> seen;
    std::lock_guard<std::mutex> lock(m_);
    for (const Conn& c : conns) {
        const auto it = first_seen_.find(c.inode);
        const double first = it == first_seen_.end() ? now : it->second;
        seen[c.inode] = first;
        if (exempt_.count(c.client_port)) continue;
        const bool too_much = c.info.tcpi_bytes_received > limits_.max_received;
        const bool too_old = now - first > limits_.max_age_s;
        const bool too_quiet = c.info.tcpi_last_data_recv / 1000.0 > idle_limit;
        // The fd may have been closed and reused since it was listed: shut it only when it is
        // still the same socket.
        if ((too_much || too_old || too_quiet) && socketInode(c.fd) == c.inode) {
            shutdown(c.fd, SHUT_RDWR);
            ++dropped_;
        }
    }
    first_seen_.swap(seen);
}

}  // namespace shaderlab::serve
