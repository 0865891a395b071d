// Polling folder watch; see file_watch.h.
#include "shaderlab/live/file_watch.h"

#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;

namespace shaderlab::viewer {

namespace {

constexpr std::size_t kMaxFiles = 512;
constexpr int kMaxDepth = 3;
constexpr std::uintmax_t kMaxHashedBytes = 8u << 20;

bool ignored(const std::string& name) {
    return name.empty() || name[0] == '.' || name.back() == '~' || name[0] == '#';
}

// FNV-1a over the file's bytes (its first 8 MB): enough to tell a new save from a touch.
std::uint64_t hashFile(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::uint64_t h = 1469598103934665603ull;
    char buf[65536];
    std::uintmax_t total = 0;
    while (in && total < kMaxHashedBytes) {
        in.read(buf, sizeof buf);
        const std::streamsize n = in.gcount();
        for (std::streamsize i = 0; i < n; ++i) {
            h ^= static_cast<unsigned char>(buf[i]);
            h *= 1099511628211ull;
        }
        total += static_cast<std::uintmax_t>(n);
    }
    return h;
}

}  // namespace

FolderWatch::FolderWatch(std::string folder, std::chrono::milliseconds settle)
    : folder_(std::move(folder)), settle_(settle) {
    seen_ = snapshot();
    committed_ = seen_;
}

std::map<std::string, FileState> FolderWatch::snapshot() {
    std::map<std::string, FileState> out;
    std::error_code ec;
    fs::recursive_directory_iterator it(folder_, fs::directory_options::skip_permission_denied, ec), end;
    for (; !ec && it != end && out.size() < kMaxFiles; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (ignored(name)) {
            if (it->is_directory(ec)) it.disable_recursion_pending();
            continue;
        }
        if (it->is_directory(ec)) {
            if (it.depth() + 1 >= kMaxDepth) it.disable_recursion_pending();
            continue;
        }
        // A symlink is followed for its contents: the renderer refuses one that leaves the
        // submission, and says so.
        if (!it->is_regular_file(ec)) continue;
        FileState st;
        st.size = it->file_size(ec);
        if (ec) continue;
        // stat() for the time: file_time_type's epoch is not the Unix one in C++17, and the
        // viewer compares the save time with the system clock.
        struct stat info {};
        if (::stat(it->path().c_str(), &info) != 0) continue;
        st.mtime_ns = static_cast<std::int64_t>(info.st_mtim.tv_sec) * 1000000000 + info.st_mtim.tv_nsec;
        const std::string rel = fs::relative(it->path(), folder_, ec).generic_string();
        // Hash only what moved since the last look.
        const auto prev = seen_.find(rel);
        if (prev != seen_.end() && prev->second.size == st.size && prev->second.mtime_ns == st.mtime_ns)
            st.hash = prev->second.hash;
        else
            st.hash = hashFile(it->path());
        out.emplace(rel, st);
    }
    return out;
}

bool FolderWatch::poll() {
    std::map<std::string, FileState> now = snapshot();
    const auto same_stat = [](const std::map<std::string, FileState>& a,
                              const std::map<std::string, FileState>& b) {
        if (a.size() != b.size()) return false;
        for (auto i = a.begin(), j = b.begin(); i != a.end(); ++i, ++j)
            if (i->first != j->first || i->second.size != j->second.size ||
                i->second.mtime_ns != j->second.mtime_ns || i->second.hash != j->second.hash)
                return false;
        return true;
    };
    const auto clock_now = std::chrono::steady_clock::now();
    if (!same_stat(now, seen_)) {
        seen_ = std::move(now);
        last_move_ = clock_now;
        pending_ = true;
        return false;
    }
    if (!pending_ || clock_now - last_move_ < settle_) return false;
    pending_ = false;
    std::vector<std::string> changed;
    std::int64_t newest = 0;
    for (const auto& [name, st] : seen_) {
        const auto old = committed_.find(name);
        if (old == committed_.end() || old->second.hash != st.hash || old->second.size != st.size) {
            changed.push_back(name);
            newest = std::max(newest, st.mtime_ns);
        }
    }
    for (const auto& [name, st] : committed_)
        if (!seen_.count(name)) changed.push_back(name);
    if (changed.empty()) {  // saved again as it was: only the times moved
        for (const auto& [name, st] : seen_) {
            const auto old = committed_.find(name);
            if (old != committed_.end() && old->second.mtime_ns != st.mtime_ns &&
                std::find(saved_unchanged_.begin(), saved_unchanged_.end(), name) == saved_unchanged_.end())
                saved_unchanged_.push_back(name);
        }
    }
    committed_ = seen_;
    if (changed.empty()) return false;
    changed_ = std::move(changed);
    changed_mtime_ns_ = newest;
    return true;
}

std::vector<std::string> FolderWatch::takeSavedUnchanged() {
    std::vector<std::string> out;
    out.swap(saved_unchanged_);
    return out;
}

}  // namespace shaderlab::viewer
