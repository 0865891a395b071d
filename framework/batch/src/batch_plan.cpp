// Planning a batch: the labs' keys and reference jobs, the submissions' keys, unpacking and
// grading jobs; see plan.h. Starts no process and writes no report.
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>

#include "shaderlab/base/student_files.h"
#include "shaderlab/batch/batch.h"
#include "shaderlab/batch/plan.h"
#include "shaderlab/batch/reference_cache.h"
#include "shaderlab/batch/results.h"
#include "shaderlab/lab/lab_spec.h"

namespace fs = std::filesystem;

namespace shaderlab::batch {

namespace {

bool reservedName(const std::string& name) { return name == "summary.csv" || name == "summary.json"; }

// Seconds as the workers' command line and the keys have them.
std::string secondsText(double seconds) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", seconds);
    return text;
}

// The program and the submission's files: what its unpacked zip and its report rest on.
std::string contentKey(const BatchSettings& settings, const SubmissionSource& source) {
    Hasher key;
    key.add(settings.tool_version);
    if (source.is_zip)
        key.addFile(source.path);
    else
        key.addTree(source.path, source.path);
    return key.hex();
}

// What a submission's report depends on: its content, the class's labs and their keys, the formats.
std::string submissionKey(const BatchSettings& settings, const std::vector<LabPlan>& labs,
                          const Submission& sub) {
    Hasher key;
    key.add(sub.content_key);
    key.addNumber(settings.labs_named ? 1 : 0);
    for (const LabPlan& lab : labs) key.add(lab.key);
    for (const std::string& f : settings.formats) key.add(f);
    return key.hex();
}

// A submitted zip unpacked under the state folder (once per content), or the reason it cannot be.
void unpackZip(const BatchSettings& settings, const ResultsFolder& folder, Submission* sub) {
    std::error_code ec;
    const fs::path into = folder.state / "work" / (sub->folder_name + "-" + sub->content_key);
    if (!fs::is_directory(into, ec)) {
        const fs::path tmp = into.string() + ".tmp-" + std::to_string(getpid());
        fs::remove_all(tmp, ec);
        ArchiveLimits limits;
        limits.max_total_bytes = settings.max_unpacked_mib << 20;
        const ExtractResult x = extractZip(sub->source.path, tmp.string(), limits);
        if (x.status != "ok") {
            sub->status = x.status;
            sub->message = fs::path(sub->source.path).filename().string() + ": " + x.message;
            fs::remove_all(tmp, ec);
        } else {
            fs::rename(tmp, into, ec);
        }
    }
    sub->root = into.string();
}

// Whether the lab folder `dir` holds one of `files` (found without regard to case, as grading
// finds them); when not, `why` says so, naming what the folder holds.
bool handsIn(const fs::path& dir, const std::string& lab, const std::vector<std::string>& files,
             std::string* why) {
    std::error_code ec;
    if (!fs::exists(fs::symlink_status(dir, ec))) {
        *why = "not handed in: the submission has no " + lab + "/ folder";
        return false;
    }
    // A lab folder that is a link is not entered here (it may lead anywhere): grading refuses what
    // of it lies outside the submission, and says so.
    if (fs::is_symlink(dir, ec)) return true;
    for (const std::string& f : files)
        if (fs::exists(fs::symlink_status(dir / f, ec)) || !findIgnoringCase(dir.string(), f).empty())
            return true;
    std::string names;
    for (const std::string& f : files) names += (names.empty() ? "" : ", ") + f;
    *why = "not handed in: " + lab + "/ holds none of the lab's files (" + names + "); it holds " +
           describeFolder(dir.string());
    return false;
}

// The submission's own root below its wrapping folders, and the labs it hands in; "empty" when
// it holds no lab folder.
void findLabs(const BatchSettings& settings, const std::vector<LabPlan>& labs, Submission* sub) {
    std::error_code ec;
    const std::vector<std::string>& all_ids = settings.all_lab_ids;
    const std::string unpacked = sub->root;
    sub->root = unwrapSubmissionRoot(sub->root, all_ids);
    // A zip's report names its files inside the zip ("alice.zip/Assignment 1/01-phong"), never
    // the folder it was unpacked into, which is this results folder's own (a shard's, say).
    sub->shown_root = sub->root;
    if (sub->source.is_zip) {
        const fs::path inside = fs::path(sub->root).lexically_relative(unpacked);
        sub->shown_root = (fs::path(sub->source.path) / inside).lexically_normal().string();
        while (sub->shown_root.size() > 1 && sub->shown_root.back() == '/') sub->shown_root.pop_back();
    }
    bool any = false;
    for (const std::string& id : all_ids) any = any || fs::is_directory(fs::path(sub->root) / id, ec);
    if (!any) {
        sub->status = "empty";
        sub->message = "no lab folder (such as " + all_ids.front() + "/) in the submission; it holds " +
                       describeFolder(sub->root);
        return;
    }
    for (const LabPlan& lab : labs) {
        std::string why;
        if (handsIn(fs::path(sub->root) / lab.id, lab.id, lab.student_files, &why))
            sub->handed_in.push_back(lab.id);
        else
            sub->lab_notes.emplace_back(lab.id, why);
    }
}

// The grading job of each lab of `sub` (the `index`-th submission): one per lab folder content,
// shared with the submissions before it that have the same (`job_of`: lab/hash -> job).
void planGradingJobs(const BatchSettings& settings, const ResultsFolder& folder, std::size_t index,
                     Submission* sub, Plan* plan, std::map<std::string, std::size_t>* job_of) {
    std::error_code ec;
    const std::string timeout_text = secondsText(settings.timeout_s);
    const std::string compile_timeout_text = secondsText(settings.compile_timeout_s);
    std::vector<Job>& jobs = plan->jobs;
    for (std::size_t i = 0; i < plan->labs.size(); ++i) {
        const LabPlan& lab = plan->labs[i];
        if (!settings.labs_named &&
            std::find(sub->handed_in.begin(), sub->handed_in.end(), lab.id) == sub->handed_in.end()) {
            sub->jobs.push_back(SIZE_MAX);  // not handed in: nothing to grade (lab_notes says why)
            continue;
        }
        const fs::path lab_folder = fs::path(sub->root) / lab.id;
        Hasher h;
        h.add(lab.key);
        // A symlinked lab folder is not entered (it may point anywhere); the render decides
        // what of it lies inside the submission.
        if (fs::is_symlink(lab_folder, ec))
            h.add("link " + fs::read_symlink(lab_folder, ec).string());
        else if (fs::is_directory(lab_folder, ec))
            h.addTree(lab_folder.string(), sub->root);
        else
            h.add("absent");
        const std::string id = lab.id + "/" + h.hex();
        auto it = job_of->find(id);
        if (it == job_of->end()) {
            Job job;
            job.lab = lab.id;
            job.final_dir = (folder.graded / lab.id / h.hex()).string();
            job.watchdog_s = 2.0 * settings.timeout_s + 300.0;
            job.argv = {settings.exe,
                        "batch-worker",
                        "--mode",
                        "grade",
                        "--labs",
                        settings.labs_root,
                        "--lab",
                        lab.id,
                        "--submission",
                        sub->root,
                        "--out",
                        job.final_dir,
                        "--backend",
                        settings.backend,
                        "--timeout",
                        timeout_text,
                        "--compile-timeout",
                        compile_timeout_text,
                        "--memory",
                        std::to_string(settings.memory >> 20) + "M"};
            if (!lab.goldens_root.empty()) {
                job.argv.push_back("--goldens");
                job.argv.push_back(lab.goldens_root);
            }
            // Goal isolation composes the student's work with the reference's sources.
            if (!settings.reference_root.empty()) {
                job.argv.push_back("--reference");
                job.argv.push_back(settings.reference_root);
            }
            if (fs::is_regular_file(fs::path(job.final_dir) / "report.json", ec)) job.done = job.ok = true;
            it = job_of->emplace(id, jobs.size()).first;
            jobs.push_back(job);
        }
        jobs[it->second].waiting.push_back(index);
        sub->jobs.push_back(it->second);
    }
}

}  // namespace

bool parseMemory(const std::string& text, std::size_t* bytes, std::size_t minimum) {
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (!end || end == text.c_str() || !(v > 0)) return false;
    std::string unit(end);
    double scale = 1.0;
    if (unit == "K" || unit == "KiB")
        scale = 1024.0;
    else if (unit == "M" || unit == "MiB" || unit.empty())
        scale = 1024.0 * 1024.0;
    else if (unit == "G" || unit == "GiB")
        scale = 1024.0 * 1024.0 * 1024.0;
    else
        return false;
    *bytes = static_cast<std::size_t>(v * scale);
    return *bytes >= minimum;
}

bool parseShard(const std::string& text, int* k, int* n) {
    if (text.empty()) {
        *k = 1;
        *n = 1;
        return true;
    }
    char extra = 0;
    return std::sscanf(text.c_str(), "%d/%d%c", k, n, &extra) == 2 && *n >= 1 && *k >= 1 && *k <= *n;
}

bool readLabs(const std::string& labs_root, const std::vector<std::string>& ids, std::vector<LabPlan>* labs,
              std::vector<std::string>* errors) {
    for (const std::string& id : ids) {
        const LabSpecResult parsed = parseLabSpec((fs::path(labs_root) / id).string());
        errors->insert(errors->end(), parsed.errors.begin(), parsed.errors.end());
        if (!parsed.ok) return false;
        LabPlan lab;
        lab.id = id;
        lab.title = parsed.spec.title;
        lab.max_score = parsed.spec.grading.points;
        lab.student_files = parsed.spec.student_files;
        labs->push_back(lab);
    }
    return true;
}

bool selectSubmissions(const std::string& dir, const std::string& out_dir, int shard_k, int shard_n,
                       std::vector<SubmissionSource>* sources, std::string* error, SummaryShard* whole) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) {
        *error = dir + ": submissions folder not found";
        return false;
    }
    std::string list_error;
    std::vector<SubmissionSource> all = listSubmissions(dir, &list_error);
    if (!list_error.empty()) {
        *error = list_error;
        return false;
    }
    // The results folder, when it lies in the submissions folder, is not a submission.
    {
        const fs::path out_canonical = fs::weakly_canonical(out_dir, ec);
        all.erase(std::remove_if(all.begin(), all.end(),
                                 [&](const SubmissionSource& s) {
                                     std::error_code e;
                                     return fs::weakly_canonical(s.path, e) == out_canonical;
                                 }),
                  all.end());
    }
    if (whole) {
        // The names only, not the paths: the folder may be mounted elsewhere on another node.
        Hasher list;
        for (const SubmissionSource& s : all) list.add(fs::path(s.path).filename().string());
        whole->submissions = all.size();
        whole->list = list.hex();
    }
    // Every K-th of the sorted list: shards of a job array take their share without talking.
    for (std::size_t i = 0; i < all.size(); ++i)
        if (static_cast<int>(i % static_cast<std::size_t>(shard_n)) == shard_k - 1)
            sources->push_back(all[i]);
    return true;
}

void planLabs(const BatchSettings& settings, const ResultsFolder& folder, Plan* plan) {
    std::error_code ec;
    const std::string& labs_root = settings.labs_root;
    const std::string& reference_root = settings.reference_root;
    // Keys. A lab's: what its reference images depend on (reference_cache.h: the program, the
    // driver, the lab folder, the folders beside the labs, its reference solution), and the limits.
    for (LabPlan& lab : plan->labs) {
        const bool has_reference =
            !reference_root.empty() && fs::is_directory(fs::path(reference_root) / lab.id, ec);
        Hasher ref;
        addReferenceInputs(&ref, settings.tool_version, settings.exe, settings.backend, settings.renderer,
                           labs_root, lab.id, reference_root);
        if (has_reference) {
            lab.goldens_root = (folder.cache / (lab.id + "-" + ref.hex())).string();
            if (!fs::is_directory(lab.goldens_root, ec)) {
                Job job;
                job.kind = Job::Reference;
                job.lab = lab.id;
                job.final_dir = lab.goldens_root;
                job.watchdog_s = 1800.0;
                job.argv = {settings.exe, "batch-worker",   "--mode",    "reference",     "--labs",
                            labs_root,    "--lab",          lab.id,      "--reference",   reference_root,
                            "--out",      lab.goldens_root, "--backend", settings.backend};
                lab.ref_job = plan->jobs.size();
                plan->jobs.push_back(job);
            }
        }
        ref.add(secondsText(settings.timeout_s));
        ref.add(secondsText(settings.compile_timeout_s));
        ref.addNumber(settings.memory);
        lab.key = ref.hex();
    }
}

void surveySubmissions(const BatchSettings& settings, const ResultsFolder& folder,
                       const std::vector<SubmissionSource>& sources, Plan* plan) {
    for (const SubmissionSource& source : sources) {
        Submission sub;
        sub.source = source;
        sub.folder_name = reservedName(source.student) ? source.student + "-submission" : source.student;
        sub.content_key = contentKey(settings, source);
        sub.root = source.path;
        if (source.is_zip) unpackZip(settings, folder, &sub);
        if (sub.status == "graded") findLabs(settings, plan->labs, &sub);
        plan->subs.push_back(std::move(sub));
    }
}

void chooseClassLabs(const BatchSettings& settings, Plan* plan) {
    if (settings.labs_named) return;
    std::set<std::string> handed_in;
    for (const Submission& sub : plan->subs) handed_in.insert(sub.handed_in.begin(), sub.handed_in.end());
    plan->labs.erase(std::remove_if(plan->labs.begin(), plan->labs.end(),
                                    [&](const LabPlan& lab) { return handed_in.count(lab.id) == 0; }),
                     plan->labs.end());
}

void planSubmissions(const BatchSettings& settings, const ResultsFolder& folder, Plan* plan) {
    std::map<std::string, std::size_t> job_of;  // lab/hash -> job
    for (std::size_t i = 0; i < plan->subs.size(); ++i) {
        Submission& sub = plan->subs[i];
        sub.key = submissionKey(settings, plan->labs, sub);
        if (unchangedSince(folder.out / sub.folder_name, sub.key, &sub.row)) {
            sub.skipped = true;
            continue;
        }
        if (sub.status == "graded") planGradingJobs(settings, folder, i, &sub, plan, &job_of);
    }
}

void removeStaleWork(const ResultsFolder& folder, const std::vector<Submission>& subs) {
    // Zips unpacked for an earlier version of a submission are of no use any more (shards have
    // results folders of their own, so every submission of this folder is in this list).
    std::error_code ec;
    std::set<std::string> current;
    for (const Submission& sub : subs)
        if (sub.source.is_zip) current.insert(sub.folder_name + "-" + sub.content_key);
    std::vector<fs::path> stale;
    for (const fs::directory_entry& e : fs::directory_iterator(folder.state / "work", ec))
        if (!current.count(e.path().filename().string())) stale.push_back(e.path());
    for (const fs::path& p : stale) fs::remove_all(p, ec);
}

}  // namespace shaderlab::batch
