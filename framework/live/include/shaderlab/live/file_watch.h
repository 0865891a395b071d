// Notices when the files of a folder change, however an editor saves them: in place, truncate
// then write, or write a temporary file and rename it over the old one. It polls every file's
// size, modification time and (when those move) a hash of its contents, and reports a change
// once the folder has stayed the same for a settle time, so a half-written file is never read.
// Polling rather than inotify: a rename replaces the inode an inotify watch on the file follows,
// and polling behaves the same on every system a student has. Hidden files and editor backups
// (".name", "name~", "#name#") are ignored. Not thread-safe; no GLFW and no GL here.
#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace shaderlab::viewer {

struct FileState {
    std::uintmax_t size = 0;
    std::int64_t mtime_ns = 0;
    std::uint64_t hash = 0;
};

class FolderWatch {
  public:
    explicit FolderWatch(std::string folder,
                         std::chrono::milliseconds settle = std::chrono::milliseconds(60));

    // Call every few tens of milliseconds. True once for each settled change of contents (a file
    // added, removed, or its bytes changed); touching a file without changing it is no change.
    bool poll();
    // The files (relative to the folder) of the last change poll() reported.
    const std::vector<std::string>& changedFiles() const { return changed_; }
    // The newest modification time among them, in nanoseconds since the epoch (0: a removal only).
    std::int64_t changedMtimeNs() const { return changed_mtime_ns_; }
    // The files saved again with the same contents since the last call (an editor saving a buffer
    // it did not change): no change for poll(), but a student who saves wants a sign that it was
    // seen. Each settled save is handed out once.
    std::vector<std::string> takeSavedUnchanged();

  private:
    std::map<std::string, FileState> snapshot();

    std::string folder_;
    std::chrono::milliseconds settle_;
    std::map<std::string, FileState> seen_;       // the last snapshot
    std::map<std::string, FileState> committed_;  // the contents last reported (or the first)
    std::chrono::steady_clock::time_point last_move_{};
    bool pending_ = false;
    std::vector<std::string> changed_;
    std::int64_t changed_mtime_ns_ = 0;
    std::vector<std::string> saved_unchanged_;
};

}  // namespace shaderlab::viewer
