// Submissions on disk, content hashes, atomic writes and the results-folder lock; see batch.h.
// Also readText() for the other sources of the library (batch_detail.h).
#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>
#include <xxhash.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>

#include "batch_detail.h"
#include "grader/base/atomic_file.h"
#include "shaderlab/batch/batch.h"

namespace fs = std::filesystem;

namespace shaderlab::batch {

namespace {

bool hidden(const std::string& name) { return name.empty() || name[0] == '.' || name == "__MACOSX"; }

bool endsWithZip(const std::string& name) {
    if (name.size() < 5) return false;
    std::string ext = name.substr(name.size() - 4);
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    return ext == ".zip";
}

// The length of the UTF-8 sequence starting at s[i] when it is valid, else 0.
std::size_t utf8Length(const std::string& s, std::size_t i) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    std::size_t n = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xE ? 3 : (c >> 3) == 0x1E ? 4 : 0;
    if (n == 0 || i + n > s.size()) return 0;
    for (std::size_t k = 1; k < n; ++k)
        if ((static_cast<unsigned char>(s[i + k]) & 0xC0) != 0x80) return 0;
    return n;
}

}  // namespace

std::string printable(const std::string& s, std::size_t max_bytes) {
    std::string out;
    for (std::size_t i = 0; i < s.size();) {
        if (out.size() >= max_bytes) {
            out += "...";
            break;
        }
        const unsigned char c = static_cast<unsigned char>(s[i]);
        const std::size_t n = utf8Length(s, i);
        if (n == 0 || c < 0x20 || c == 0x7F) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\x%02X", c);
            out += buf;
            ++i;
        } else {
            out.append(s, i, n);
            i += n;
        }
    }
    return out;
}

std::vector<SubmissionSource> listSubmissions(const std::string& dir, std::string* error) {
    std::vector<SubmissionSource> out;
    std::error_code ec;
    fs::directory_iterator it(dir, ec);
    if (ec) {
        *error = dir + ": cannot read the submissions folder: " + ec.message();
        return out;
    }
    for (const fs::directory_entry& e : it) {
        const std::string name = e.path().filename().string();
        if (hidden(name)) continue;
        SubmissionSource s;
        s.path = fs::absolute(e.path()).lexically_normal().string();
        // A symlinked submission is followed: the instructor made the submissions folder.
        if (e.is_directory(ec)) {
            s.student = name;
        } else if (e.is_regular_file(ec) && endsWithZip(name)) {
            s.student = name.substr(0, name.size() - 4);
            s.is_zip = true;
        } else {
            continue;
        }
        out.push_back(std::move(s));
    }
    std::sort(out.begin(), out.end(), [](const SubmissionSource& a, const SubmissionSource& b) {
        return a.student != b.student ? a.student < b.student : a.is_zip < b.is_zip;
    });
    // "alice/" and "alice.zip" side by side: the zip keeps its full name.
    for (std::size_t i = 0; i + 1 < out.size(); ++i)
        if (out[i].student == out[i + 1].student && out[i + 1].is_zip) out[i + 1].student += ".zip";
    return out;
}

std::string unwrapSubmissionRoot(const std::string& dir, const std::vector<std::string>& lab_ids) {
    fs::path root = dir;
    std::error_code ec;
    for (int depth = 0; depth < 8; ++depth) {
        for (const std::string& id : lab_ids)
            if (fs::is_directory(root / id, ec)) return root.string();
        std::vector<fs::directory_entry> entries;
        for (const fs::directory_entry& e : fs::directory_iterator(root, ec))
            if (!hidden(e.path().filename().string())) entries.push_back(e);
        if (entries.size() != 1 || entries[0].is_symlink(ec) || !entries[0].is_directory(ec)) break;
        root = entries[0].path();
    }
    return root.string();
}

std::string describeFolder(const std::string& dir, std::size_t max_names) {
    std::vector<std::string> names;
    std::error_code ec;
    for (const fs::directory_entry& e : fs::directory_iterator(dir, ec))
        names.push_back(e.path().filename().string() + (e.is_directory(ec) ? "/" : ""));
    if (names.empty()) return "nothing";
    std::sort(names.begin(), names.end());
    std::string out;
    for (std::size_t i = 0; i < names.size() && i < max_names; ++i)
        out += (i ? ", " : "") + printable(names[i], 80);
    if (names.size() > max_names) out += ", ... (" + std::to_string(names.size()) + " entries)";
    return out;
}

// ---- Hasher -------------------------------------------------------------------------------------

Hasher::Hasher() : state_(XXH3_createState()) { XXH3_64bits_reset(static_cast<XXH3_state_t*>(state_)); }
Hasher::~Hasher() { XXH3_freeState(static_cast<XXH3_state_t*>(state_)); }

void Hasher::add(const void* data, std::size_t n) {
    XXH3_64bits_update(static_cast<XXH3_state_t*>(state_), data, n);
}

void Hasher::addNumber(std::uint64_t v) {
    unsigned char b[8];
    for (int i = 0; i < 8; ++i) b[i] = static_cast<unsigned char>(v >> (8 * i));
    add(b, sizeof b);
}

void Hasher::add(const std::string& s) {
    addNumber(s.size());
    add(s.data(), s.size());
}

bool Hasher::addFile(const std::string& path) {
    // O_NONBLOCK: a FIFO planted where a file should be must not hang the hash.
    const int fd = open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
    if (fd < 0) return false;
    struct stat st {};
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        close(fd);
        return false;
    }
    addNumber(static_cast<std::uint64_t>(st.st_size));
    // Past 256 MiB (no shader is that long; the grader refuses it anyway) the size and the
    // modification time stand for the content, so that a huge file costs no time.
    if (st.st_size > (off_t(256) << 20)) {
        addNumber(static_cast<std::uint64_t>(st.st_mtim.tv_sec));
        addNumber(static_cast<std::uint64_t>(st.st_mtim.tv_nsec));
        close(fd);
        return true;
    }
    char buf[1 << 16];
    bool ok = true;
    for (;;) {
        const ssize_t n = read(fd, buf, sizeof buf);
        if (n == 0) break;
        if (n < 0) {
            if (errno == EINTR) continue;
            ok = false;
            break;
        }
        add(buf, static_cast<std::size_t>(n));
    }
    close(fd);
    return ok;
}

bool Hasher::addTree(const std::string& dir, const std::string& root,
                     const std::vector<std::string>& skip_names) {
    std::error_code ec;
    const fs::path canonical_root = fs::weakly_canonical(root, ec);
    std::map<std::string, fs::directory_entry> entries;  // generic relative path -> entry, sorted
    fs::recursive_directory_iterator it(dir, fs::directory_options::none, ec);
    if (ec) return false;
    for (; it != fs::recursive_directory_iterator(); it.increment(ec)) {
        if (ec) return false;
        const std::string name = it->path().filename().string();
        if (std::find(skip_names.begin(), skip_names.end(), name) != skip_names.end()) {
            if (it->is_directory(ec) && !it->is_symlink(ec)) it.disable_recursion_pending();
            continue;
        }
        entries.emplace(it->path().lexically_relative(dir).generic_string(), *it);
    }
    for (const auto& [rel, e] : entries) {
        add(rel);
        const fs::file_status st = e.symlink_status(ec);
        if (fs::is_symlink(st)) {
            const fs::path target = fs::read_symlink(e.path(), ec);
            const fs::path resolved = fs::weakly_canonical(e.path(), ec);
            const std::string r = resolved.generic_string(), c = canonical_root.generic_string() + "/";
            if (!ec && r.compare(0, c.size(), c) == 0 && fs::is_regular_file(resolved, ec)) {
                add("link-file");
                if (!addFile(resolved.string())) add("unreadable");
            } else {
                add("link");
                add(target.string());
            }
        } else if (fs::is_directory(st)) {
            add("dir");
        } else if (fs::is_regular_file(st)) {
            add("file");
            if (!addFile(e.path().string())) add("unreadable");
        } else {
            add("other");
        }
    }
    return true;
}

std::uint64_t Hasher::digest() const { return XXH3_64bits_digest(static_cast<XXH3_state_t*>(state_)); }

std::string Hasher::hex() const {
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(digest()));
    return buf;
}

// ---- files --------------------------------------------------------------------------------------

bool writeFileAtomically(const std::string& path, const std::string& data, std::string* error) {
    // The results folder is the batch's own: a link planted at one of its names is removed, then
    // the file is written as every report is (grader/atomic_file.h: temporary file, fsync,
    // rename; it refuses a link that reappears in between).
    struct stat st {};
    if (lstat(path.c_str(), &st) == 0 && S_ISLNK(st.st_mode) && unlink(path.c_str()) != 0) {
        *error = path + ": " + std::strerror(errno);
        return false;
    }
    return grader::writeFileAtomically(path, data, error);
}

bool linkTree(const std::string& from, const std::string& to, std::string* error) {
    std::error_code ec;
    fs::create_directories(to, ec);
    if (ec) {
        *error = to + ": " + ec.message();
        return false;
    }
    for (fs::recursive_directory_iterator it(from, ec), end; !ec && it != end; it.increment(ec)) {
        const fs::path dest = fs::path(to) / it->path().lexically_relative(from);
        const fs::file_status st = it->symlink_status(ec);
        if (fs::is_directory(st)) {
            fs::create_directories(dest, ec);
        } else if (fs::is_regular_file(st)) {
            fs::create_hard_link(it->path(), dest, ec);
            if (ec) {
                ec.clear();
                fs::copy_file(it->path(), dest, fs::copy_options::overwrite_existing, ec);
            }
        }  // nothing else is ours to carry over
        if (ec) {
            *error = dest.string() + ": " + ec.message();
            return false;
        }
    }
    if (ec) *error = from + ": " + ec.message();
    return !ec;
}

FolderLock::~FolderLock() {
    if (fd_ >= 0) close(fd_);  // closing releases the flock
}

bool FolderLock::acquire(const std::string& path, std::string* error) {
    fd_ = open(path.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd_ < 0) {
        *error = path + ": " + std::strerror(errno);
        return false;
    }
    if (flock(fd_, LOCK_EX | LOCK_NB) != 0) {
        char buf[32] = {};
        const ssize_t n = pread(fd_, buf, sizeof buf - 1, 0);
        *error = std::string("another batch is writing into this folder") +
                 (n > 0 ? " (process " + std::string(buf, static_cast<std::size_t>(n)) + ")" : "");
        close(fd_);
        fd_ = -1;
        return false;
    }
    const std::string pid = std::to_string(getpid());
    // The pid is only a courtesy for the message above: a failure to write it changes nothing.
    if (ftruncate(fd_, 0) == 0) {
        const ssize_t written = pwrite(fd_, pid.data(), pid.size(), 0);
        (void)written;
    }
    return true;
}

}  // namespace shaderlab::batch

namespace shaderlab::batch_detail {

std::string readText(const fs::path& p, std::size_t max_bytes) {
    std::ifstream in(p, std::ios::binary);
    if (!in) return {};
    std::string s;
    char buf[1 << 16];
    while (s.size() < max_bytes && in.read(buf, sizeof buf).gcount() > 0)
        s.append(buf, static_cast<std::size_t>(in.gcount()));
    if (s.size() > max_bytes) s.resize(max_bytes);
    return s;
}

}  // namespace shaderlab::batch_detail
