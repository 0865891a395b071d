// Unpacking a submitted .zip with libarchive, distrusting every entry; see batch.h.
//
// Every entry name is checked before anything is written: no absolute path, no drive letter, no
// ".." component; only files, folders and symlinks whose target stays inside are accepted, and
// symlinks are made after every file, so no write ever goes through one. Files are created with
// O_EXCL | O_NOFOLLOW. Sizes are counted as the data comes (a zip's declared sizes may lie).
#include <archive.h>
#include <archive_entry.h>
#include <fcntl.h>
#include <locale.h>
#include <unistd.h>

#include <cerrno>
#include <clocale>
#include <cstring>
#include <filesystem>
#include <vector>

#include "shaderlab/batch/batch.h"

namespace fs = std::filesystem;

namespace shaderlab::batch {

namespace {

struct ArchiveCloser {
    archive* a;
    ~ArchiveCloser() { archive_read_free(a); }
};

// libarchive converts entry names through the locale's character set; under the "C" locale a
// UTF-8 name (any accent) has no conversion and no name. This thread reads them as UTF-8 while
// the object lives; the process's locale is left alone.
class Utf8Names {
  public:
    Utf8Names() : locale_(newlocale(LC_CTYPE_MASK, "C.UTF-8", static_cast<locale_t>(0))) {
        if (locale_) previous_ = uselocale(locale_);
    }
    ~Utf8Names() {
        if (!locale_) return;
        uselocale(previous_);
        freelocale(locale_);
    }
    Utf8Names(const Utf8Names&) = delete;
    Utf8Names& operator=(const Utf8Names&) = delete;

  private:
    locale_t locale_;
    locale_t previous_ = static_cast<locale_t>(0);
};

// The entry's path split into components, or an error when it would leave the folder.
bool safeComponents(std::string name, std::vector<std::string>* parts, std::string* why) {
    for (char& c : name)
        if (c == '\\') c = '/';  // archives made on Windows
    if (name.empty()) {
        *why = "an entry has no name";
        return false;
    }
    if (name[0] == '/' || (name.size() > 1 && name[1] == ':')) {
        *why = "entry '" + printable(name) + "' has an absolute path";
        return false;
    }
    std::size_t start = 0;
    while (start <= name.size()) {
        std::size_t slash = name.find('/', start);
        if (slash == std::string::npos) slash = name.size();
        const std::string part = name.substr(start, slash - start);
        if (part == "..") {
            *why = "entry '" + printable(name) + "' climbs out of the submission with '..'";
            return false;
        }
        if (!part.empty() && part != ".") parts->push_back(part);
        start = slash + 1;
    }
    if (parts->empty()) *why = "entry '" + printable(name) + "' names no file";
    return !parts->empty();
}

fs::path join(const fs::path& root, const std::vector<std::string>& parts) {
    fs::path p = root;
    for (const std::string& part : parts) p /= part;
    return p;
}

// Whether a symlink at `link_parts` pointing to `target` stays inside the archive's folder.
bool symlinkStaysInside(const std::vector<std::string>& link_parts, const std::string& target) {
    if (target.empty() || target[0] == '/' || target.find('\\') != std::string::npos) return false;
    long depth = static_cast<long>(link_parts.size()) - 1;  // folders above the link, inside
    std::size_t start = 0;
    while (start <= target.size()) {
        std::size_t slash = target.find('/', start);
        if (slash == std::string::npos) slash = target.size();
        const std::string part = target.substr(start, slash - start);
        if (part == "..") {
            if (--depth < 0) return false;
        } else if (!part.empty() && part != ".") {
            ++depth;
        }
        start = slash + 1;
    }
    return true;
}

}  // namespace

ExtractResult extractZip(const std::string& zip_path, const std::string& dest_dir,
                         const ArchiveLimits& limits) {
    ExtractResult result;
    auto fail = [&](const std::string& status, const std::string& message) {
        result.status = status;
        result.message = message;
        return result;
    };
    std::error_code ec;
    const std::uint64_t zip_size = fs::file_size(zip_path, ec);
    if (ec) return fail("bad_archive", "cannot read the zip: " + ec.message());
    if (!fs::create_directory(dest_dir, ec) || ec)
        return fail("bad_archive", dest_dir + ": cannot create the folder to unpack into");
    if (zip_size == 0) {
        result.status = "ok";  // nothing in it: the caller finds no lab folder
        return result;
    }

    const Utf8Names utf8_names;
    archive* a = archive_read_new();
    ArchiveCloser closer{a};
    archive_read_support_format_zip(a);
    if (archive_read_open_filename(a, zip_path.c_str(), 1 << 16) != ARCHIVE_OK)
        return fail("bad_archive", "not a readable zip: " +
                                       printable(archive_error_string(a) ? archive_error_string(a) : "?"));

    const fs::path root = dest_dir;
    struct PendingLink {
        fs::path at;
        std::string target;
    };
    std::vector<PendingLink> links;
    std::vector<char> buf(1 << 16);
    for (;;) {
        archive_entry* entry = nullptr;
        const int r = archive_read_next_header(a, &entry);
        if (r == ARCHIVE_EOF) break;
        if (r < ARCHIVE_WARN) {
            const char* err = archive_error_string(a);
            return fail("bad_archive", result.files == 0 && zip_size < 22
                                           ? std::string("not a zip file (too short)")
                                           : "not a readable zip: " + printable(err ? err : "unknown error"));
        }
        if (++result.files > limits.max_entries)
            return fail("too_large", "more than " + std::to_string(limits.max_entries) + " entries");
        const char* utf8 = archive_entry_pathname_utf8(entry);
        const char* raw = utf8 ? utf8 : archive_entry_pathname(entry);
        std::vector<std::string> parts;
        std::string why;
        if (!raw || !safeComponents(raw, &parts, &why))
            return fail("unsafe_archive", why.empty() ? "an entry has no readable name" : why);
        const std::string shown = printable(raw);
        if (archive_entry_hardlink(entry))
            return fail("unsafe_archive", "entry '" + shown + "' is a hard link");
        const fs::path dest = join(root, parts);
        const mode_t type = archive_entry_filetype(entry);
        if (type == AE_IFDIR) {
            fs::create_directories(dest, ec);
            if (ec) return fail("unsafe_archive", "entry '" + shown + "': " + ec.message());
            continue;
        }
        if (type == AE_IFLNK) {
            const char* t8 = archive_entry_symlink_utf8(entry);
            const char* t = t8 ? t8 : archive_entry_symlink(entry);
            const std::string target = t ? t : "";
            if (!symlinkStaysInside(parts, target))
                return fail("unsafe_archive", "entry '" + shown + "' is a symlink to '" + printable(target) +
                                                  "', outside the submission");
            links.push_back({dest, target});
            continue;
        }
        if (type != AE_IFREG)
            return fail("unsafe_archive",
                        "entry '" + shown + "' is not a file, a folder or a symlink (a device?)");
        fs::create_directories(dest.parent_path(), ec);
        if (ec) return fail("unsafe_archive", "entry '" + shown + "': " + ec.message());
        // Permissions: read-write for the owner, and executable when the zip says so (a script of
        // a bundle); nothing else of the zip's mode (no set-uid, no world-writable).
        const mode_t perm = (archive_entry_perm(entry) & 0100) ? 0755 : 0644;
        const int fd = open(dest.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, perm);
        if (fd < 0)
            return fail(
                errno == EEXIST ? "unsafe_archive" : "bad_archive",
                "entry '" + shown + "': " + (errno == EEXIST ? "appears twice" : std::strerror(errno)));
        std::uint64_t entry_bytes = 0;
        for (;;) {
            const la_ssize_t n = archive_read_data(a, buf.data(), buf.size());
            if (n == 0) break;
            if (n < 0) {
                close(fd);
                const char* err = archive_error_string(a);
                return fail("bad_archive",
                            "entry '" + shown + "' cannot be read: " + printable(err ? err : "?"));
            }
            entry_bytes += static_cast<std::uint64_t>(n);
            result.bytes += static_cast<std::uint64_t>(n);
            if (entry_bytes > limits.max_entry_bytes || result.bytes > limits.max_total_bytes ||
                (result.bytes > (1u << 20) &&
                 static_cast<double>(result.bytes) > limits.max_ratio * static_cast<double>(zip_size))) {
                close(fd);
                char what[160];
                if (entry_bytes > limits.max_entry_bytes)
                    std::snprintf(what, sizeof what, "one file unpacks to more than %llu MiB",
                                  static_cast<unsigned long long>(limits.max_entry_bytes >> 20));
                else if (result.bytes > limits.max_total_bytes)
                    std::snprintf(what, sizeof what, "it unpacks to more than %llu MiB",
                                  static_cast<unsigned long long>(limits.max_total_bytes >> 20));
                else
                    std::snprintf(what, sizeof what,
                                  "it unpacks to more than %.0f times its size (a zip bomb?)",
                                  limits.max_ratio);
                return fail("too_large", std::string(what) + " (at entry '" + shown + "')");
            }
            for (la_ssize_t done = 0; done < n;) {
                const ssize_t w = write(fd, buf.data() + done, static_cast<std::size_t>(n - done));
                if (w < 0 && errno == EINTR) continue;
                if (w <= 0) {
                    close(fd);
                    return fail("bad_archive", "entry '" + shown + "': cannot write: " +
                                                   std::strerror(w < 0 ? errno : ENOSPC));
                }
                done += w;
            }
        }
        close(fd);
    }
    for (const PendingLink& l : links) {
        fs::create_directories(l.at.parent_path(), ec);
        fs::create_symlink(l.target, l.at, ec);
        if (ec) return fail("unsafe_archive", l.at.filename().string() + ": " + ec.message());
    }
    result.status = "ok";
    return result;
}

bool writeZip(const std::string& zip_path, const std::vector<ZipItem>& items, std::string* error) {
    const std::string tmp = zip_path + ".tmp-" + std::to_string(getpid());
    archive* a = archive_write_new();
    archive_write_set_format_zip(a);
    auto fail = [&](const std::string& why) {
        *error = zip_path + ": " + why;
        archive_write_free(a);
        unlink(tmp.c_str());
        return false;
    };
    if (archive_write_open_filename(a, tmp.c_str()) != ARCHIVE_OK) return fail(archive_error_string(a));
    for (const ZipItem& item : items) {
        std::string bytes = item.data;
        if (!item.source_path.empty()) {
            const int fd = open(item.source_path.c_str(), O_RDONLY | O_CLOEXEC);
            if (fd < 0) return fail(item.source_path + ": " + std::strerror(errno));
            char buf[1 << 16];
            ssize_t n;
            while ((n = read(fd, buf, sizeof buf)) > 0) bytes.append(buf, static_cast<std::size_t>(n));
            close(fd);
            if (n < 0) return fail(item.source_path + ": " + std::strerror(errno));
        }
        archive_entry* entry = archive_entry_new();
        // The name in UTF-8 and, where the locale can spell it, in the locale's form too: libarchive
        // 3.4 (Debian 11's, in the portable build) reads only the latter, and crashes without it.
        if (!archive_entry_update_pathname_utf8(entry, item.name.c_str()))
            archive_entry_set_pathname(entry, item.name.c_str());
        archive_entry_set_filetype(entry, AE_IFREG);
        archive_entry_set_perm(entry, item.executable ? 0755 : 0644);
        archive_entry_set_size(entry, static_cast<la_int64_t>(bytes.size()));
        archive_entry_set_mtime(entry, 315532800, 0);  // 1980-01-01: the same sources give the same zip
        const bool ok = archive_write_header(a, entry) == ARCHIVE_OK &&
                        (bytes.empty() || archive_write_data(a, bytes.data(), bytes.size()) ==
                                              static_cast<la_ssize_t>(bytes.size()));
        archive_entry_free(entry);
        if (!ok)
            return fail(item.name + ": " +
                        (archive_error_string(a) ? archive_error_string(a) : "write failed"));
    }
    if (archive_write_close(a) != ARCHIVE_OK) return fail(archive_error_string(a));
    archive_write_free(a);
    if (rename(tmp.c_str(), zip_path.c_str()) != 0) {
        *error = zip_path + ": " + std::strerror(errno);
        unlink(tmp.c_str());
        return false;
    }
    return true;
}

}  // namespace shaderlab::batch
