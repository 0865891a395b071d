// The results folder of a batch: one report folder per submission (report.json, report.html,
// the other formats asked for, the images, and batch.json, which says it is complete), the
// summary beside them, and the state folder .shaderlab/ (lock, reference cache, graded labs,
// unpacked zips, worker logs) that makes a rerun cheap. Also `shaderlab merge`, which joins the
// results folders of several shards into one.
//
// Everything here is written atomically or swapped in with renames: a batch killed at any point
// leaves a folder the next run continues from. Grades nothing (schedule.h). POSIX only.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "shaderlab/batch/batch.h"
#include "shaderlab/batch/plan.h"

namespace shaderlab::batch {

// A results folder made, writable and ours alone (locked) before any work.
struct ResultsFolder {
    std::filesystem::path out;    // absolute
    std::filesystem::path state;  // <out>/.shaderlab
    std::filesystem::path cache;  // reference renders: <state>/references unless told otherwise
    // Graded labs, by content: <state>/labs, or <cache>/labs when the cache is given (--cache),
    // so that the shards and the reruns that share it grade a lab folder once.
    std::filesystem::path graded;
    FolderLock lock;
};

// Opens `out_dir` (made when missing) for a batch: locks it, removes what an interrupted run left
// half-made, and makes the state folder's parts. `cache_dir` empty: the state folder's own.
// false, with the message, when it cannot be written or another batch holds it.
bool openResultsFolder(const std::string& out_dir, const std::string& cache_dir, ResultsFolder* folder,
                       std::string* error);

// Whether the report folder `folder` is complete and was made for `key`; if so its summary row.
bool unchangedSince(const std::filesystem::path& folder, const std::string& key, SummaryRow* row);

// The report of a submission whose jobs are done, from its labs' results, written into its
// report folder (built beside, then swapped in with renames); sets `sub->row`. batch.json is
// written only when every lab was graded, so that the next run grades the rest again.
bool writeSubmissionResults(Submission* sub, const std::vector<LabPlan>& labs, const std::vector<Job>& jobs,
                            const ResultsFolder& folder, const BatchSettings& settings, std::string* error);

// summary.json, then summary.csv, into `out`.
bool writeSummary(const std::filesystem::path& out, const Summary& summary, std::string* error);

struct MergeResult {
    std::size_t submissions = 0;
    std::string summary_csv;  // the path written
};

// `shaderlab merge`: the summaries of the results folders `inputs` (shards of one batch: the
// same labs, each student in one only) in one, written into `out_dir` with the report folders
// (hard links where possible). false, with the message, at the first problem.
bool mergeResults(const std::vector<std::string>& inputs, const std::string& out_dir, MergeResult* result,
                  std::string* error);

}  // namespace shaderlab::batch
