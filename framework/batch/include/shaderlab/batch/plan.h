// The plan of a batch: which labs and submissions it grades, and the jobs that do it. A job is one
// worker run, a lab's reference solution rendered into the reference cache or one lab of one
// submission folder, and its result lands in a folder named by a hash of everything it depends
// on (the content key), so that:
//   - the reference solution of a lab is rendered once, then taken from the cache;
//   - a lab folder that several students submitted unchanged (the starter code) is graded once,
//     also across the shards of a class when they share a cache (--cache): a result found there
//     is reused, and a job another batch is running is waited for (a lock file beside its
//     folder) rather than run twice;
//   - a batch killed half-way and run again grades only what is missing, and a submission whose
//     content and settings did not change since its report is skipped.
//
// Planning unpacks submitted zips and hashes folders. It starts no process (schedule.h runs the
// jobs) and writes no report (results.h). POSIX only.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "shaderlab/batch/batch.h"

namespace shaderlab::batch {

struct ResultsFolder;  // results.h

// What a batch is asked to do, settled before any submission is read.
struct BatchSettings {
    std::string tool_version;  // in every key and every report
    std::string exe;           // the program the workers run: `<exe> batch-worker ...`
    std::string labs_root;
    std::vector<std::string> all_lab_ids;  // every lab of labs_root (what a submission's root holds)
    // The labs were named (--lab): every submission is graded in each of them, handed in or not.
    // Otherwise each is graded in the labs it hands in (chooseClassLabs).
    bool labs_named = false;
    std::string backend = "auto";
    std::string renderer;              // what probeRenderer() saw (workers.h), in the reference key
    std::string reference_root;        // empty: grade against the labs' own goldens
    std::vector<std::string> formats;  // extra report formats: gradescope, junit
    double timeout_s = 60.0;           // drawing (IsolationLimits::timeout_s)
    double compile_timeout_s = 30.0;   // context, files, compile and link
    std::size_t memory = 0;            // bytes of resident memory of each render process
    std::uint64_t max_unpacked_mib = 64;
    int jobs_max = 1;    // worker processes at once
    SummaryShard shard;  // --shard K/N and the list it was cut from; count 0: not a shard
};

// One unit of work for a worker: a reference render into the cache, or one lab of one
// submission folder. Identical units are one job.
struct Job {
    enum Kind { Reference, Grade } kind = Grade;
    std::string lab;
    std::string final_dir;  // where its result lands (a rename of final_dir + ".tmp-<pid>")
    std::vector<std::string> argv;
    pid_t pid = -1;
    std::chrono::steady_clock::time_point started;
    double watchdog_s = 0.0;
    bool done = false, ok = false;
    std::string error;
    std::string log;                   // its stdout and stderr
    std::vector<std::size_t> waiting;  // submissions
    // Another batch sharing the cache runs this job (its lock is held): tried again at
    // `retry_at`, and run here after all when it has waited longer than `watchdog_s`.
    int claim_fd = -1;  // the lock this batch holds while its worker runs
    bool deferred = false;
    std::chrono::steady_clock::time_point retry_at, deferred_since;
};

struct LabPlan {
    std::string id;
    std::string title;
    double max_score = 0.0;
    std::vector<std::string> student_files;  // lab.json's: what a submission hands in for it
    std::string key;           // hash of what its grading depends on, besides the student's files
    std::string goldens_root;  // reference cache entry; empty: the lab's own goldens
    std::size_t ref_job = SIZE_MAX;
};

struct Submission {
    SubmissionSource source;
    std::string folder_name;  // its report folder below the results
    std::string content_key;  // the program and the submission's files: names its unpacked zip
    std::string key;          // content + settings + the class's labs
    std::string root;         // the folder graded (unpacked and unwrapped)
    // The labs it hands in (a lab folder holding one of the lab's student files), in the order of
    // the batch's labs; the others' folders, when there, are said in `lab_notes`.
    std::vector<std::string> handed_in;
    std::vector<std::pair<std::string, std::string>> lab_notes;  // lab -> why it is not handed in
    std::string shown_root;  // what its report names: `root`, or inside the zip ("a.zip/dir")
    std::string status = "graded";
    std::string message;
    bool skipped = false;  // unchanged since its report
    bool finished = false;
    std::vector<std::size_t> jobs;  // per lab (SIZE_MAX: not graded)
    SummaryRow row;
};

struct Plan {
    std::vector<LabPlan> labs;
    std::vector<Job> jobs;  // references first, then grading jobs in submission order
    std::vector<Submission> subs;
};

// A size such as 4G, 2048M or 512K (a bare number is MiB; KiB, MiB, GiB also do) in bytes.
// false when it cannot be read or is below `minimum`.
bool parseMemory(const std::string& text, std::size_t* bytes, std::size_t minimum = std::size_t(64) << 20);

// "K/N" of --shard: every N-th submission from the K-th. Empty: 1/1.
bool parseShard(const std::string& text, int* k, int* n);

// The labs `ids` of `labs_root` read from their lab.json (id, title, points). The parser's
// messages go to `errors`; false at the first lab that does not parse.
bool readLabs(const std::string& labs_root, const std::vector<std::string>& ids, std::vector<LabPlan>* labs,
              std::vector<std::string>* errors);

// The submissions below `dir` that shard K of N grades: every N-th of the sorted list, from the
// K-th, so that the shards of a job array take their share without talking. `out_dir`, when it
// lies in `dir`, is not a submission. `whole` (optional) gets the count and a hash of the names
// of the whole list, which every shard records for `merge`. false, with the message, when `dir`
// cannot be listed.
bool selectSubmissions(const std::string& dir, const std::string& out_dir, int shard_k, int shard_n,
                       std::vector<SubmissionSource>* sources, std::string* error,
                       SummaryShard* whole = nullptr);

// The submissions into `plan->subs`: their files hashed, zips unpacked under the state folder
// (once per content), wrapping folders skipped, and the labs of `plan->labs` each hands in.
void surveySubmissions(const BatchSettings& settings, const ResultsFolder& folder,
                       const std::vector<SubmissionSource>& sources, Plan* plan);

// After surveySubmissions(): the labs the class was asked for, left in `plan->labs`. Those named
// (--lab), or else those that at least one submission hands in, in the course's order: a class
// handing in three labs of twelve is graded, and totalled, over three.
void chooseClassLabs(const BatchSettings& settings, Plan* plan);

// Each lab's key in `plan->labs`, and a job for each reference solution that the cache does
// not hold yet.
void planLabs(const BatchSettings& settings, const ResultsFolder& folder, Plan* plan);

// After planLabs(): each submission's key; unchanged ones skipped; every lab it hands in (every
// lab, when they were named) hashed into a grading job (shared by identical folders) unless its
// result is already there. A lab of the class it does not hand in gets no job.
void planSubmissions(const BatchSettings& settings, const ResultsFolder& folder, Plan* plan);

// Removes the zips unpacked for earlier versions of the submissions: `subs` must be every
// submission of the results folder.
void removeStaleWork(const ResultsFolder& folder, const std::vector<Submission>& subs);

}  // namespace shaderlab::batch
