// Crash-safe file output for reports and pictures. A file is written to a temporary file in the
// same folder, flushed to disk and renamed over its final name, so a reader (or a rerun after
// SIGKILL, a full disk or a power cut) sees the old file or the complete new one, never half of
// one. Output folders may hold links planted by someone else: a final name that is a symbolic
// link, or a folder on the way that is one, is refused rather than written through.
//
// Does not: lock (two writers of one name each replace the file whole; the last rename wins),
// or keep the old file when the new one fails (it is simply left as it was).
#pragma once

#include <cstdio>
#include <string>
#include <string_view>

namespace grader {

// Writes `bytes` to `path` atomically: a temporary "<dir>/.<name>.XXXXXX.tmp" made with O_EXCL
// (so it cannot be a planted link), fsync'ed when `sync`, then renamed to `path`. Refuses a
// `path` that is a symbolic link or anything but a regular file. On failure returns false with
// "<path>: <reason>" in `error` and leaves no temporary file behind.
bool writeFileAtomically(const std::string& path, std::string_view bytes, std::string* error,
                         bool sync = true);

// The same for writers that need a FILE* (libpng): open(), write to stream(), then commit().
// Destroying an uncommitted AtomicFile removes its temporary file.
class AtomicFile {
  public:
    AtomicFile() = default;
    ~AtomicFile();
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    bool open(const std::string& path, std::string* error);
    std::FILE* stream() const { return stream_; }
    bool commit(std::string* error, bool sync = true);
    void discard();

  private:
    std::string path_;
    std::string temp_;
    std::FILE* stream_ = nullptr;
};

// Creates `root`/`relative` folder by folder (like mkdir -p) and refuses when any part of it
// below `root` is a symbolic link or not a folder, so that nothing is written outside `root`
// through a planted link. `root` itself must exist. Returns false with the reason in `error`.
bool createFoldersInside(const std::string& root, const std::string& relative, std::string* error);

}  // namespace grader
