// Temporary file, fsync, rename; see atomic_file.h.
#include "grader/base/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <vector>

namespace fs = std::filesystem;

namespace grader {

namespace {

std::string reason(const std::string& path, const std::string& what, int err) {
    return path + ": " + what + (err ? std::string(" (") + std::strerror(err) + ")" : std::string());
}

// A final name that may be replaced: absent, or a regular file. A link is refused even when it
// points at a regular file: rename() would replace the link, but whoever planted it meant the
// write to land elsewhere, and the person grading should hear about it.
bool checkTarget(const std::string& path, std::string* error) {
    struct stat st {};
    if (lstat(path.c_str(), &st) != 0) {
        if (errno == ENOENT) return true;
        if (error) *error = reason(path, "cannot inspect", errno);
        return false;
    }
    if (S_ISLNK(st.st_mode)) {
        if (error) *error = path + ": is a symbolic link, refused (reports never write through links)";
        return false;
    }
    if (!S_ISREG(st.st_mode)) {
        if (error) *error = path + ": exists and is not a regular file, refused";
        return false;
    }
    return true;
}

// Flushes a folder's entry list, so that a rename survives a power cut.
void syncFolder(const std::string& dir) {
    const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return;
    fsync(fd);
    close(fd);
}

std::string folderOf(const std::string& path) {
    const fs::path parent = fs::path(path).parent_path();
    return parent.empty() ? std::string(".") : parent.string();
}

}  // namespace

AtomicFile::~AtomicFile() { discard(); }

void AtomicFile::discard() {
    if (stream_) std::fclose(stream_);
    stream_ = nullptr;
    if (!temp_.empty()) unlink(temp_.c_str());
    temp_.clear();
}

bool AtomicFile::open(const std::string& path, std::string* error) {
    discard();
    if (!checkTarget(path, error)) return false;
    const fs::path p(path);
    std::string name = (fs::path(folderOf(path)) / ("." + p.filename().string() + ".XXXXXX.tmp")).string();
    std::vector<char> buf(name.begin(), name.end());
    buf.push_back('\0');
    // mkstemps opens with O_CREAT | O_EXCL: never an existing file, never through a link.
    const int fd = mkstemps(buf.data(), 4);
    if (fd < 0) {
        if (error) *error = reason(path, "cannot create a temporary file beside it", errno);
        return false;
    }
    fcntl(fd, F_SETFD, FD_CLOEXEC);
    fchmod(fd, 0644);  // mkstemp makes 0600; reports are meant to be read by others
    temp_ = buf.data();
    stream_ = fdopen(fd, "wb");
    if (!stream_) {
        const int err = errno;
        close(fd);
        unlink(temp_.c_str());
        temp_.clear();
        if (error) *error = reason(path, "cannot open a temporary file", err);
        return false;
    }
    path_ = path;
    return true;
}

bool AtomicFile::commit(std::string* error, bool sync) {
    if (!stream_) {
        if (error) *error = path_ + ": not open";
        return false;
    }
    bool ok = std::fflush(stream_) == 0 && !std::ferror(stream_);
    int err = ok ? 0 : errno;
    if (ok && sync && fsync(fileno(stream_)) != 0) {
        ok = false;
        err = errno;
    }
    if (std::fclose(stream_) != 0 && ok) {
        ok = false;
        err = errno;
    }
    stream_ = nullptr;
    if (!ok) {
        if (error) *error = reason(path_, "cannot write (disk full?)", err);
        discard();
        return false;
    }
    // The target may have been replaced by a link since open(): check again just before.
    if (!checkTarget(path_, error)) {
        discard();
        return false;
    }
    if (std::rename(temp_.c_str(), path_.c_str()) != 0) {
        err = errno;
        if (error) *error = reason(path_, "cannot rename the temporary file into place", err);
        discard();
        return false;
    }
    temp_.clear();
    if (sync) syncFolder(folderOf(path_));
    return true;
}

bool writeFileAtomically(const std::string& path, std::string_view bytes, std::string* error, bool sync) {
    AtomicFile file;
    if (!file.open(path, error)) return false;
    if (!bytes.empty() && std::fwrite(bytes.data(), 1, bytes.size(), file.stream()) != bytes.size()) {
        if (error) *error = reason(path, "cannot write (disk full?)", errno);
        return false;
    }
    return file.commit(error, sync);
}

bool createFoldersInside(const std::string& root, const std::string& relative, std::string* error) {
    struct stat st {};
    if (stat(root.c_str(), &st) != 0 || !S_ISDIR(st.st_mode)) {
        if (error) *error = root + ": output folder not found";
        return false;
    }
    fs::path at(root);
    for (const fs::path& part : fs::path(relative).lexically_normal()) {
        const std::string s = part.string();
        if (s.empty() || s == ".") continue;
        if (s == ".." || part.is_absolute()) {
            if (error) *error = (fs::path(root) / relative).string() + ": leaves the output folder, refused";
            return false;
        }
        at /= part;
        if (mkdir(at.c_str(), 0755) != 0 && errno != EEXIST) {
            if (error) *error = reason(at.string(), "cannot create folder", errno);
            return false;
        }
        if (lstat(at.c_str(), &st) != 0) {
            if (error) *error = reason(at.string(), "cannot inspect", errno);
            return false;
        }
        if (!S_ISDIR(st.st_mode)) {
            if (error)
                *error =
                    at.string() + (S_ISLNK(st.st_mode) ? ": is a symbolic link, refused" : ": not a folder");
            return false;
        }
    }
    return true;
}

}  // namespace grader
