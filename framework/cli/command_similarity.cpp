// `shaderlab similarity SUBMISSIONS --out DIR [--earlier FOLDER]...`: who copied. The submissions
// are found as `batch` finds them (folders and .zip files, unpacked here into a scratch folder
// with the batch library's limits, wrapping folders skipped); the report is the similarity
// library's (framework/similarity/, docs/instructors.md "Who copied").
#include <stdlib.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>

#include "commands.h"
#include "grader/base/untrusted_text.h"
#include "shaderlab/batch/batch.h"
#include "shaderlab/lab/lab_catalog.h"
#include "shaderlab/similarity/similarity.h"

namespace fs = std::filesystem;

namespace shaderlab::cli {

namespace {

// A folder for unpacked zips, removed with everything in it when the command ends.
class ScratchFolder {
  public:
    ScratchFolder() {
        std::error_code ec;
        std::string pattern = (fs::temp_directory_path(ec) / "shaderlab-similarity-XXXXXX").string();
        if (mkdtemp(pattern.data())) path_ = pattern;
    }
    ~ScratchFolder() {
        std::error_code ec;
        if (!path_.empty()) fs::remove_all(path_, ec);
    }
    ScratchFolder(const ScratchFolder&) = delete;
    ScratchFolder& operator=(const ScratchFolder&) = delete;
    const std::string& path() const { return path_; }

  private:
    std::string path_;
};

// The submissions below `dir`, of the cohort `cohort` ("" for the current class). A zip that
// cannot be unpacked safely is left out with a note. false when `dir` cannot be read.
bool gatherCohort(const std::string& dir, const std::string& cohort, const std::vector<std::string>& lab_ids,
                  const ScratchFolder& scratch, std::vector<similarity::SubmissionFolder>* out,
                  std::vector<std::string>* notes) {
    std::string error;
    const std::vector<batch::SubmissionSource> sources = batch::listSubmissions(dir, &error);
    if (!error.empty()) {
        std::cerr << "shaderlab: " << error << "\n";
        return false;
    }
    for (const batch::SubmissionSource& s : sources) {
        const std::string who = grader::printableText((cohort.empty() ? "" : cohort + "/") + s.student, 300);
        std::string root = s.path;
        if (s.is_zip) {
            if (scratch.path().empty()) {
                notes->push_back(who + ": no scratch folder to unpack the zip into, skipped");
                continue;
            }
            root = scratch.path() + "/" + std::to_string(out->size() + notes->size());
            const batch::ExtractResult x = batch::extractZip(s.path, root);
            if (x.status != "ok") {
                notes->push_back(who + ": " +
                                 grader::printableText(fs::path(s.path).filename().string(), 200) +
                                 " skipped (" + x.status + "): " + grader::printableText(x.message, 400));
                continue;
            }
        }
        out->push_back(
            similarity::SubmissionFolder{s.student, batch::unwrapSubmissionRoot(root, lab_ids), cohort});
    }
    return true;
}

// An earlier class's name: its folder's name, made unique.
std::string cohortName(const std::string& dir, std::map<std::string, int>* seen) {
    fs::path p = fs::path(dir).lexically_normal();
    if (p.filename().empty()) p = p.parent_path();
    std::string name = grader::printableText(p.filename().string(), 100);
    if (name.empty() || name == "." || name == "..") name = "earlier";
    const int n = ++(*seen)[name];
    return n == 1 ? name : name + "#" + std::to_string(n);
}

void printSummary(const similarity::SimilarityReport& report, std::size_t current, std::size_t earlier,
                  const std::string& out_dir, double seconds) {
    std::size_t documents = 0;
    for (const auto& s : report.labs) documents += s.documents;
    std::printf("similarity: %zu submission%s", current, current == 1 ? "" : "s");
    if (earlier) std::printf(" and %zu of earlier classes", earlier);
    std::printf(", %zu labs, %zu documents compared in %.1f s\n", report.labs.size(), documents, seconds);
    std::size_t unused = 0;
    for (const auto& s : report.labs) {
        if (s.documents == 0) {  // a lab no one handed in says nothing
            ++unused;
            continue;
        }
        std::size_t largest = 0;
        for (const auto& c : report.clusters)
            if (c.lab == s.lab) largest = std::max(largest, c.students.size());
        std::printf("  %-28s %4zu flagged pair%s, %3zu cluster%s", s.lab.c_str(), s.pairs_flagged,
                    s.pairs_flagged == 1 ? "" : "s", s.clusters, s.clusters == 1 ? "" : "s");
        if (largest) std::printf(" (largest: %zu students)", largest);
        std::printf("\n");
    }
    if (unused) std::printf("  (%zu labs no one handed in)\n", unused);
    if (!report.notes.empty()) {
        std::printf("%zu notes (files left out, zips skipped); the first:\n  %s\n", report.notes.size(),
                    report.notes.front().c_str());
    }
    std::printf("report: %s/index.html and %s/pairs.json\n", out_dir.c_str(), out_dir.c_str());
}

}  // namespace

int runSimilarity(const SimilarityArgs& args) {
    const auto start = std::chrono::steady_clock::now();
    std::string labs_root;
    if (!resolveLabsRoot(args.common, &labs_root)) return 2;
    const std::vector<std::string> all_ids = listLabIds(labs_root);
    const std::vector<std::string> ids = args.common.labs.empty() ? all_ids : args.common.labs;
    if (ids.empty()) {
        std::cerr << "shaderlab: no labs found in " << labs_root << "\n";
        return 2;
    }
    for (const std::string& id : ids) {
        if (std::find(all_ids.begin(), all_ids.end(), id) == all_ids.end()) {
            std::cerr << "shaderlab: --lab " << id << ": no such lab in " << labs_root << "\n";
            return 2;
        }
    }

    ScratchFolder scratch;
    std::vector<similarity::SubmissionFolder> submissions;
    std::vector<std::string> notes;
    if (!gatherCohort(args.submissions_dir, "", all_ids, scratch, &submissions, &notes)) return 2;
    const std::size_t current = submissions.size();
    std::map<std::string, int> cohorts;
    for (const std::string& dir : args.earlier)
        if (!gatherCohort(dir, cohortName(dir, &cohorts), all_ids, scratch, &submissions, &notes)) return 2;
    if (current == 0) {
        std::cerr << "shaderlab: " << args.submissions_dir
                  << ": no submissions (folders or .zip files) in it\n";
        return 2;
    }

    similarity::SimilarityOptions options;
    options.threshold = args.threshold;
    options.length_margin = args.length_margin;
    options.min_shared = args.min_shared;
    options.jobs = args.jobs;
    options.k = args.kgram;
    options.w = args.window;
    similarity::SimilarityReport report = similarity::analyseSimilarity(labs_root, ids, submissions, options);
    report.notes.insert(report.notes.begin(), notes.begin(), notes.end());

    std::string error;
    if (!similarity::writeSimilarityReport(report, args.out_dir, &error, args.max_views)) {
        std::cerr << "shaderlab: " << error << "\n";
        return 2;
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    printSummary(report, current, submissions.size() - current, args.out_dir, seconds);
    return 0;
}

}  // namespace shaderlab::cli
