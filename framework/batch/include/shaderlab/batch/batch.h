// The building blocks of `shaderlab batch` (grading many submissions): finding submissions in a
// folder, unpacking a submitted .zip safely, content hashes (xxHash) for resuming and for grading
// identical work once, files written atomically, an exclusive lock on the results folder, and the
// summary (summary.json, summary.csv) with its reader for `shaderlab merge`.
//
// It does not grade or render: the batch command runs `gradeSubmission` in worker processes
// (plan.h, schedule.h, workers.h and results.h build the batch on these blocks).
// POSIX only.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace shaderlab::batch {

// ---- submissions -------------------------------------------------------------------------------

// One submission below the submissions folder: a folder, or a .zip file. Hidden entries (".x")
// and anything else (loose files) are not submissions.
struct SubmissionSource {
    std::string student;  // the folder's name, or the zip's without ".zip" (collisions get the full name)
    std::string path;     // absolute
    bool is_zip = false;
};
std::vector<SubmissionSource> listSubmissions(const std::string& dir, std::string* error);

// The submission's own root: descends through single top folders (an LMS export wraps every
// submission in one or two folders; "__MACOSX" and hidden entries do not count) until a folder
// holds one of `lab_ids`, or more than one entry, or a file.
std::string unwrapSubmissionRoot(const std::string& dir, const std::vector<std::string>& lab_ids);

// What a submission folder holds at its top, for a message when it holds no lab: at most
// `max_names` names, comma-separated, control characters escaped.
std::string describeFolder(const std::string& dir, std::size_t max_names = 6);

// ---- zip archives ------------------------------------------------------------------------------

// Limits against zip bombs. The ratio is the unpacked bytes over the size of the .zip file.
struct ArchiveLimits {
    std::uint64_t max_total_bytes = std::uint64_t(64) << 20;
    std::uint64_t max_entry_bytes = std::uint64_t(16) << 20;
    std::uint64_t max_entries = 5000;
    double max_ratio = 200.0;
};

// Statuses of a submission that could not be graded because of its archive, beside "graded".
//   empty: no lab folder in it (also an empty zip); bad_archive: not a readable zip;
//   unsafe_archive: an entry that would land outside (absolute path, "..", a symlink out) or is not
//   a file, folder or symlink; too_large: past ArchiveLimits.
struct ExtractResult {
    std::string status;  // "ok", "bad_archive", "unsafe_archive", "too_large" ("empty" is decided later)
    std::string message;
    std::size_t files = 0;
    std::uint64_t bytes = 0;
};

// Unpacks `zip_path` into `dest_dir` (which must not exist yet; it is created). Symlinks are
// made last, and only those whose target stays inside. On failure `dest_dir` may hold a part.
ExtractResult extractZip(const std::string& zip_path, const std::string& dest_dir,
                         const ArchiveLimits& limits = {});

// One file of a zip to write: its name inside, and its bytes (`data`) or the file they come from.
struct ZipItem {
    std::string name;
    std::string source_path;  // empty: `data`
    std::string data;
    bool executable = false;  // mode 0755 instead of 0644
};

// Writes a zip (deflate) of `items`, atomically (a temporary file renamed over `zip_path`).
bool writeZip(const std::string& zip_path, const std::vector<ZipItem>& items, std::string* error);

// ---- hashing -----------------------------------------------------------------------------------

// xxHash XXH3 (64 bit), streaming.
class Hasher {
  public:
    Hasher();
    ~Hasher();
    Hasher(const Hasher&) = delete;
    Hasher& operator=(const Hasher&) = delete;
    void add(const void* data, std::size_t n);
    void add(const std::string& s);  // with its length, so that ("ab","c") != ("a","bc")
    void addNumber(std::uint64_t v);
    // Every entry below `dir` in name order: its relative path, kind and content. A symlink is
    // hashed as what it points to when that is a file inside `root`, else as its target text;
    // symlinked folders are not entered. Returns false when `dir` cannot be read.
    bool addTree(const std::string& dir, const std::string& root,
                 const std::vector<std::string>& skip_names = {});
    bool addFile(const std::string& path);
    std::uint64_t digest() const;
    std::string hex() const;  // 16 hex digits

  private:
    void* state_;
};

// ---- files -------------------------------------------------------------------------------------

// Writes `data` to a new temporary file beside `path` (never following a symlink) and renames it
// over `path`: a reader sees the old file or the whole new one, never a part, whatever happens.
bool writeFileAtomically(const std::string& path, const std::string& data, std::string* error);

// Copies the tree `from` into `to` (created), hard-linking files where the file system allows.
bool linkTree(const std::string& from, const std::string& to, std::string* error);

// An exclusive advisory lock (flock) on `path`, held while the object lives.
class FolderLock {
  public:
    FolderLock() = default;
    ~FolderLock();
    FolderLock(const FolderLock&) = delete;
    FolderLock& operator=(const FolderLock&) = delete;
    // false, with the reason, when another process holds it or the file cannot be made.
    bool acquire(const std::string& path, std::string* error);

  private:
    int fd_ = -1;
};

// ---- summary -----------------------------------------------------------------------------------

struct SummaryLab {
    std::string id;
    double score = 0.0, max_score = 0.0;
    std::string status;  // the report's lab status; empty when the submission was not graded
};

struct SummaryRow {
    std::string student;
    std::string source;  // the folder or zip it came from
    std::string status;  // graded | empty | bad_archive | unsafe_archive | too_large
    std::string message;
    double total = 0.0, max_total = 0.0;
    std::vector<SummaryLab> labs;
    std::string report;  // report.json, relative to the results folder (empty when none)
};

// What a shard of a batch (--shard K/N) was cut from, recorded in its summary.json so that
// `merge` can tell a complete set of shards from an incomplete one.
struct SummaryShard {
    int index = 0;                // K, from 1
    int count = 0;                // N; 0: not a shard (the summary of a whole batch, or of a merge)
    std::size_t submissions = 0;  // in the whole submissions folder, every shard's together
    std::string list;             // hash of the whole folder's sorted submission names
};

struct Summary {
    std::string tool_version;
    std::vector<std::string> labs;  // the lab columns, in order: the labs the class was asked for
    // The labs were named (--lab), rather than taken from what the class handed in. false in a
    // summary written before it was recorded, whose columns were every lab of the course.
    bool labs_named = false;
    std::vector<SummaryRow> rows;  // by student
    SummaryShard shard;            // written only when shard.count > 0
};

std::string summaryToJson(const Summary& summary);
bool summaryFromJson(const std::string& text, Summary* out, std::string* error);
std::string summaryRowToJson(const SummaryRow& row);
bool summaryRowFromJson(const std::string& text, SummaryRow* out);
// One line per student: student, status, total, max_total, then each lab's score and status, then
// the message. Fields are quoted per RFC 4180, and a text field a spreadsheet would take for a
// formula (=, +, -, @) gets a leading apostrophe.
std::string summaryToCsv(const Summary& summary);

// A string from a student's file names or files, made safe to print and to store: control
// characters (ANSI escapes included) as \xNN, invalid UTF-8 bytes as \xNN, at most `max_bytes`.
std::string printable(const std::string& s, std::size_t max_bytes = 400);

}  // namespace shaderlab::batch
