// analyseSimilarity(): per lab, the starter, the students' documents and their pairs, labs in
// parallel; see similarity.h.
#include "shaderlab/similarity/similarity.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <thread>

#include "documents.h"
#include "grader/base/untrusted_text.h"
#include "pairs.h"
#include "shaderlab/base/paths.h"
#include "shaderlab/base/student_files.h"
#include "shaderlab/lab/lab_spec.h"

namespace fs = std::filesystem;

namespace shaderlab::similarity {

std::string sourceKey(const std::string& lab, const StudentRef& who) {
    return lab + '\n' + who.cohort + '\n' + who.student;
}

double flagBar(const SimilarityOptions& options, std::size_t fingerprints) {
    const double n = double(std::max<std::size_t>(1, fingerprints));
    return std::min(1.0, options.threshold + options.length_margin / std::sqrt(n));
}

std::string pairVerdict(const PairResult& p, const SimilarityOptions& options) {
    const std::size_t n = std::min(p.a_fingerprints, p.b_fingerprints);
    const auto pct = [](double x) { return std::to_string(int(std::floor(x * 100.0 + 1e-9))) + " %"; };
    const std::string shares = "shares " + std::to_string(p.shared) + " of the " + std::to_string(n) +
                               " fingerprints of the smaller document (" + pct(p.score) + ")";
    const std::string bar = "the bar for documents of " + std::to_string(n) + " fingerprints is " +
                            pct(p.bar) + " (" + pct(options.threshold) + ", more for short ones)";
    if (p.shared < options.min_shared)
        return "not flagged: " + shares + ", fewer than " + std::to_string(options.min_shared) + " in all";
    if (!p.flagged) return "not flagged: " + shares + "; " + bar;
    return "flagged: " + shares + "; " + bar +
           (p.strong ? "; strong (" + pct((p.bar + 1.0) / 2.0) + " or more): it joins a cluster"
                     : "; below " + pct((p.bar + 1.0) / 2.0) + ", so it joins no cluster");
}

namespace {

using detail::Document;
using detail::LabResult;

bool isShaderFile(const fs::path& p) {
    static const char* const kExtensions[] = {".vert", ".frag", ".glsl", ".geom", ".comp", ".tesc", ".tese"};
    const std::string ext = p.extension().string();
    return std::find(std::begin(kExtensions), std::end(kExtensions), ext) != std::end(kExtensions);
}

// The code the course gives: every shader file of the lab's folder and of the shared folder
// (the instructor's files, trusted), starter files of the student files included.
void loadStarter(const std::string& labs_root, const std::string& lab, std::size_t k,
                 detail::StarterKgrams* starter, std::vector<std::string>* notes) {
    for (const std::string& dir : {labs_root + "/" + lab, sharedFolder(labs_root)}) {
        std::error_code ec;
        fs::recursive_directory_iterator it(dir, ec);
        if (ec) continue;
        for (; it != fs::recursive_directory_iterator(); it.increment(ec)) {
            if (ec) break;
            if (!it->is_regular_file(ec) || !isShaderFile(it->path())) continue;
            const FileText f = readFile(it->path().string(), 4u << 20);
            if (!f.ok) {
                notes->push_back(lab + ": starter file left out: " + f.error);
                continue;
            }
            detail::addStarterText(f.text, k, starter);
        }
    }
}

// One student's document for `lab`, or false when the submission has no folder for the lab.
bool readDocument(const SubmissionFolder& sub, const std::string& lab, const LabSpec& spec,
                  const detail::StarterKgrams& starter, const SimilarityOptions& options, Document* doc,
                  std::vector<std::string>* notes) {
    std::error_code ec;
    if (!fs::exists(fs::symlink_status(fs::path(sub.root) / lab, ec))) return false;
    doc->who = StudentRef{grader::printableText(sub.student, 200), grader::printableText(sub.cohort, 200)};
    doc->current = sub.cohort.empty();
    const std::string who = (sub.cohort.empty() ? "" : sub.cohort + "/") + sub.student;
    for (const std::string& name : spec.student_files) {
        const std::string relative = lab + "/" + name;
        // Not handed in: nothing to compare, and nothing to say (the grade says it). A file named
        // but for its case is graded (student_files.h), so it is compared too, with a note.
        std::string case_note;
        if (!fs::exists(fs::symlink_status(fs::path(sub.root) / relative, ec)) &&
            findIgnoringCase(sub.root, relative).empty())
            continue;
        const FileText f = readStudentFile(sub.root, relative, relative, options.max_file_bytes, &case_note);
        if (!case_note.empty()) notes->push_back(grader::printableText(who + ": " + case_note, 600));
        std::string why = f.ok ? detail::refuseText(f.text) : f.error;
        if (!why.empty()) {
            notes->push_back(grader::printableText(who + ": " + relative + " left out: " + why, 600));
            continue;
        }
        detail::addStudentFile(relative, f.text, starter, options.k, options.w, doc);
    }
    detail::finishDocument(doc);
    return true;
}

LabResult analyseLab(const std::string& labs_root, const std::string& lab, const LabSpecResult& parsed,
                     const std::vector<SubmissionFolder>& submissions, const SimilarityOptions& options) {
    LabResult out;
    out.stats.lab = lab;
    if (!parsed.ok) {
        out.notes.push_back(lab + ": lab.json cannot be read, lab skipped: " +
                            (parsed.errors.empty() ? std::string("unknown error") : parsed.errors.front()));
        return out;
    }
    detail::StarterKgrams starter;
    loadStarter(labs_root, lab, options.k, &starter, &out.notes);
    std::vector<Document> docs;
    for (const SubmissionFolder& sub : submissions) {
        Document doc;
        if (readDocument(sub, lab, parsed.spec, starter, options, &doc, &out.notes))
            docs.push_back(std::move(doc));
    }
    detail::comparePairs(lab, docs, options, &out);
    return out;
}

}  // namespace

SimilarityReport analyseSimilarity(const std::string& labs_root, const std::vector<std::string>& lab_ids,
                                   const std::vector<SubmissionFolder>& submissions,
                                   const SimilarityOptions& options) {
    // The lab.json files first, one after the other: the lab library is not asked to be
    // thread-safe. Then the labs, which are independent.
    std::vector<LabSpecResult> specs;
    for (const std::string& lab : lab_ids) specs.push_back(parseLabSpec(labs_root + "/" + lab));
    std::vector<LabResult> results(lab_ids.size());
    // Each thread takes the next lab until none is left.
    std::size_t jobs = options.jobs > 0 ? std::size_t(options.jobs) : std::thread::hardware_concurrency();
    jobs = std::max<std::size_t>(1, std::min(jobs, lab_ids.size()));
    std::atomic<std::size_t> next{0};
    auto work = [&]() {
        for (std::size_t i = next++; i < lab_ids.size(); i = next++)
            results[i] = analyseLab(labs_root, lab_ids[i], specs[i], submissions, options);
    };
    std::vector<std::thread> threads;
    for (std::size_t t = 1; t < jobs; ++t) threads.emplace_back(work);
    work();
    for (std::thread& t : threads) t.join();

    SimilarityReport report;
    report.options = options;
    for (LabResult& r : results) {
        report.labs.push_back(r.stats);
        std::move(r.pairs.begin(), r.pairs.end(), std::back_inserter(report.pairs));
        std::move(r.clusters.begin(), r.clusters.end(), std::back_inserter(report.clusters));
        std::move(r.notes.begin(), r.notes.end(), std::back_inserter(report.notes));
        report.sources.merge(r.sources);
    }
    return report;
}

}  // namespace shaderlab::similarity
