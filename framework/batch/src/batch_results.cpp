// The results folder of a batch: opened and locked, one report folder per submission swapped in
// whole, and the summary; see results.h. Merging shards is in batch_merge.cpp.
#include <unistd.h>

#include <chrono>
#include <filesystem>

#include "batch_detail.h"
#include "grader/reports/report.h"
#include "shaderlab/base/student_files.h"
#include "shaderlab/batch/batch.h"
#include "shaderlab/batch/plan.h"
#include "shaderlab/batch/results.h"

namespace fs = std::filesystem;

namespace shaderlab::batch {

namespace {

// Replaces every occurrence of `from` in `s` by `to`.
void replaceAll(std::string* s, const std::string& from, const std::string& to) {
    if (from.empty()) return;
    for (std::size_t at = s->find(from); at != std::string::npos; at = s->find(from, at + to.size()))
        s->replace(at, from.size(), to);
}

// Removes what an interrupted run left half-made under the state folder.
void removeLeftovers(const fs::path& state) {
    std::error_code ec;
    fs::remove_all(state / "tmp", ec);
    for (const char* sub : {"labs", "references", "work"}) {
        std::vector<fs::path> stale;
        for (fs::recursive_directory_iterator it(state / sub, ec), end; !ec && it != end; it.increment(ec)) {
            if (it->path().filename().string().find(".tmp-") != std::string::npos) {
                stale.push_back(it->path());
                it.disable_recursion_pending();
            } else if (it.depth() >= 1) {
                it.disable_recursion_pending();
            }
        }
        for (const fs::path& p : stale) fs::remove_all(p, ec);
    }
    fs::create_directories(state / "tmp", ec);
}

// What a worker left half-made in a shared cache (`cache` and `cache`/labs/<lab>/) when it died
// more than a day ago: another batch's worker may be writing the younger ones right now.
void removeStaleCacheLeftovers(const fs::path& cache) {
    std::error_code ec;
    const auto old = fs::file_time_type::clock::now() - std::chrono::hours(24);
    std::vector<fs::path> dirs = {cache};
    for (const fs::directory_entry& e : fs::directory_iterator(cache / "labs", ec))
        if (e.is_directory(ec) && !e.is_symlink(ec)) dirs.push_back(e.path());
    std::vector<fs::path> stale;
    for (const fs::path& dir : dirs)
        for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
            std::error_code e2;
            if (e.path().filename().string().find(".tmp-") != std::string::npos &&
                fs::last_write_time(e.path(), e2) < old && !e2)
                stale.push_back(e.path());
        }
    for (const fs::path& p : stale) fs::remove_all(p, ec);
}

// The report of one submission, from its labs' results.
grader::Report assembleReport(const Submission& sub, const std::vector<LabPlan>& labs,
                              const std::vector<Job>& jobs, const BatchSettings& settings) {
    grader::Report report;
    report.tool_version = settings.tool_version;
    report.submission = sub.source.path;
    report.backend = settings.backend;
    for (std::size_t i = 0; i < labs.size(); ++i) {
        grader::ReportLab lab;
        lab.id = labs[i].id;
        lab.title = labs[i].title;
        lab.max_score = labs[i].max_score;
        const std::size_t j = sub.jobs.empty() ? SIZE_MAX : sub.jobs[i];
        if (j == SIZE_MAX) {
            lab.status = "missing";
            lab.message = sub.message;
            for (const auto& [id, why] : sub.lab_notes)
                if (id == lab.id) lab.message = why;
            lab.folder = (fs::path(sub.shown_root) / lab.id).lexically_normal().string();
        } else if (!jobs[j].ok) {
            lab.status = "crashed";
            lab.message = "the grading process stopped (" + jobs[j].error +
                          "): not the submission's fault; the next run of the batch grades it again (a "
                          "--memory too small for the program itself?)";
        } else {
            grader::Report one;
            std::string err;
            if (!grader::reportFromJson(batch_detail::readText(fs::path(jobs[j].final_dir) / "report.json"),
                                        &one, &err) ||
                one.labs.size() != 1) {
                lab.status = "crashed";
                lab.message = "the lab's result cannot be read: " + err;
            } else {
                lab = one.labs[0];
                if (!one.renderer.empty()) report.renderer = one.renderer;
                // The lab was graded in the folder of the first submission that had it, perhaps
                // by another shard: say this one.
                replaceAll(&lab.message, one.submission, sub.shown_root);
                for (grader::ReportDiagnostic& d : lab.diagnostics)
                    replaceAll(&d.message, one.submission, sub.shown_root);
                lab.folder = (fs::path(sub.shown_root) / lab.id).lexically_normal().string();
            }
        }
        report.score += lab.score;
        report.max_score += lab.max_score;
        report.labs.push_back(std::move(lab));
    }
    return report;
}

// What summary.csv says of a graded submission: for each lab that did not render, its message,
// and the files found only by their case (student_files.h), "<lab>: <message>" joined.
std::string labsMessage(const grader::Report& report) {
    std::string out;
    auto add = [&](const std::string& lab, const std::string& text) {
        if (text.empty()) return;
        out +=
            (out.empty() ? "" : "; ") + lab + ": " + (text.size() > 300 ? text.substr(0, 300) + "..." : text);
    };
    for (const grader::ReportLab& lab : report.labs) {
        if (lab.status != "passed" && lab.status != "failed") add(lab.id, lab.message);
        for (const grader::ReportDiagnostic& d : lab.diagnostics)
            if (isCaseNote(d.message)) add(lab.id, d.message);
    }
    return out;
}

SummaryRow rowOf(const Submission& sub, const grader::Report& report) {
    SummaryRow row;
    row.student = sub.source.student;
    row.source = sub.source.path;
    row.status = sub.status;
    row.message = sub.status == "graded" ? labsMessage(report) : sub.message;
    row.total = report.score;
    row.max_total = report.max_score;
    row.report = sub.folder_name + "/report.json";
    for (const grader::ReportLab& lab : report.labs)
        row.labs.push_back({lab.id, lab.score, lab.max_score, sub.status == "graded" ? lab.status : ""});
    return row;
}

// Writes the submission's report folder: built beside, then swapped in with renames.
bool writeSubmission(Submission* sub, const grader::Report& report, const std::vector<LabPlan>& labs,
                     const std::vector<Job>& jobs, const fs::path& out, const fs::path& state,
                     const std::vector<std::string>& formats, std::string* error) {
    const fs::path tmp = state / "tmp" / (sub->folder_name + ".new-" + std::to_string(getpid()));
    std::error_code ec;
    fs::remove_all(tmp, ec);
    fs::create_directories(tmp, ec);
    if (ec) {
        *error = tmp.string() + ": " + ec.message();
        return false;
    }
    for (std::size_t i = 0; i < labs.size() && !sub->jobs.empty(); ++i) {
        const std::size_t j = sub->jobs[i];
        if (j == SIZE_MAX || !jobs[j].ok) continue;
        const fs::path images = fs::path(jobs[j].final_dir) / labs[i].id;
        if (fs::is_directory(images, ec) && !linkTree(images.string(), (tmp / labs[i].id).string(), error))
            return false;
    }
    bool ok = writeFileAtomically((tmp / "report.json").string(), grader::reportToJson(report), error) &&
              writeFileAtomically((tmp / "report.html").string(),
                                  grader::reportToHtml(report, {tmp.string(), 20u << 20}), error);
    for (const std::string& f : formats) {
        if (ok && f == "gradescope")
            ok = writeFileAtomically((tmp / "results.json").string(),
                                     grader::reportToGradescope(report, {tmp.string(), 2u << 20}), error);
        if (ok && f == "junit")
            ok = writeFileAtomically((tmp / "report.junit.xml").string(), grader::reportToJunit(report),
                                     error);
    }
    sub->row = rowOf(*sub, report);
    // batch.json last: a report folder without it is redone on the next run, and so is one where a
    // worker failed (our fault, perhaps passing: the next run tries again).
    bool complete = true;
    for (std::size_t j : sub->jobs)
        complete = complete && (j == SIZE_MAX || jobs[j].ok);  // MAX: not handed in
    ok = ok && (!complete ||
                writeFileAtomically(
                    (tmp / "batch.json").string(),
                    "{\"key\": \"" + sub->key + "\", \"row\": " + summaryRowToJson(sub->row) + "}\n", error));
    if (!ok) return false;
    const fs::path dest = out / sub->folder_name;
    const fs::path old = state / "tmp" / (sub->folder_name + ".old-" + std::to_string(getpid()));
    fs::remove_all(old, ec);
    if (fs::exists(fs::symlink_status(dest, ec))) {
        fs::rename(dest, old, ec);  // a symlink planted there is moved away, never followed
        if (ec) {
            *error = dest.string() + ": cannot replace it: " + ec.message();
            return false;
        }
    }
    fs::rename(tmp, dest, ec);
    if (ec) {
        *error = dest.string() + ": " + ec.message();
        return false;
    }
    fs::remove_all(old, ec);
    return true;
}

}  // namespace

bool openResultsFolder(const std::string& out_dir, const std::string& cache_dir, ResultsFolder* folder,
                       std::string* error) {
    std::error_code ec;
    const fs::path out = fs::absolute(out_dir, ec).lexically_normal();
    fs::create_directories(out, ec);
    std::string write_error;
    if (!fs::is_directory(out, ec) ||
        !writeFileAtomically((out / ".shaderlab-write-test").string(), "ok\n", &write_error)) {
        *error = out.string() + ": cannot write the results there" +
                 (write_error.empty() ? "" : ": " + write_error);
        return false;
    }
    fs::remove(out / ".shaderlab-write-test", ec);
    if (!batch_detail::lockStateFolder(out, &folder->lock, error)) return false;
    const fs::path state = out / batch_detail::kStateDir;
    removeLeftovers(state);
    folder->out = out;
    folder->state = state;
    folder->cache = cache_dir.empty() ? state / "references" : fs::absolute(cache_dir, ec).lexically_normal();
    folder->graded = cache_dir.empty() ? state / "labs" : folder->cache / "labs";
    fs::create_directories(folder->graded, ec);
    if (ec || !fs::is_directory(folder->graded, ec)) {
        *error = folder->graded.string() + ": cannot make the cache there" + (ec ? ": " + ec.message() : "");
        return false;
    }
    if (!cache_dir.empty()) removeStaleCacheLeftovers(folder->cache);
    fs::create_directories(state / "work", ec);
    fs::create_directories(state / "logs", ec);
    return true;
}

bool unchangedSince(const fs::path& folder, const std::string& key, SummaryRow* row) {
    std::error_code ec;
    if (fs::is_symlink(folder, ec) || !fs::is_regular_file(folder / "report.json", ec)) return false;
    const std::string text = batch_detail::readText(folder / "batch.json", 1u << 20);
    const std::string marker = "{\"key\": \"" + key + "\", \"row\": ";
    if (text.compare(0, marker.size(), marker) != 0 || text.size() < marker.size() + 2) return false;
    std::string rest = text.substr(marker.size());
    while (!rest.empty() && (rest.back() == '\n' || rest.back() == ' ')) rest.pop_back();
    if (rest.empty() || rest.back() != '}') return false;
    rest.pop_back();
    return summaryRowFromJson(rest, row);
}

bool writeSubmissionResults(Submission* sub, const std::vector<LabPlan>& labs, const std::vector<Job>& jobs,
                            const ResultsFolder& folder, const BatchSettings& settings, std::string* error) {
    const grader::Report report = assembleReport(*sub, labs, jobs, settings);
    return writeSubmission(sub, report, labs, jobs, folder.out, folder.state, settings.formats, error);
}

bool writeSummary(const fs::path& out, const Summary& summary, std::string* error) {
    return writeFileAtomically((out / "summary.json").string(), summaryToJson(summary), error) &&
           writeFileAtomically((out / "summary.csv").string(), summaryToCsv(summary), error);
}

}  // namespace shaderlab::batch

namespace shaderlab::batch_detail {

bool lockStateFolder(const fs::path& out, batch::FolderLock* lock, std::string* error) {
    std::error_code ec;
    const fs::path state = out / kStateDir;
    if (fs::is_symlink(state, ec)) {  // everything of ours goes in there: it must be ours
        *error = state.string() + " is a symlink; remove it";
        return false;
    }
    fs::create_directories(state, ec);
    std::string lock_error;
    if (!lock->acquire((state / "lock").string(), &lock_error)) {
        *error = out.string() + ": " + lock_error;
        return false;
    }
    return true;
}

}  // namespace shaderlab::batch_detail
