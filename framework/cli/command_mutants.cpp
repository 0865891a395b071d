// `shaderlab mutants LAB...`: coverage by mutation. Every mutant of the reference solution's
// student files (mutants.h) is graded as a submission, against the stored goldens and with goal
// isolation, as a student's would be. A mutant that does not compile is left out (it is no
// variant of what the code computes); one that loses points is killed; one that passes every goal
// either computes the same thing (declared in the lab's cases.json "equivalent_mutants", with the
// reason) or shows an idea no scene witnesses: an undeclared survivor, which fails the run.
// Writes <out>/mutants.json. Exit 0 when no undeclared mutant survives, 1 when one does, 2 when a
// lab or its corpus cannot be read.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "commands.h"
#include "shaderlab/authoring/corpus_cases.h"
#include "shaderlab/authoring/mutants.h"
#include "shaderlab/base/paths.h"
#include "shaderlab/grading/grading.h"
#include "shaderlab/lab/lab_catalog.h"

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace shaderlab::cli {

using namespace authoring;

namespace {

struct MutantRun {
    Mutant mutant;        // without its text
    std::string verdict;  // "killed" | "survivor" | "equivalent" | "does_not_compile"
    std::string status;   // the lab's status
    double score = 0.0, max_score = 0.0;
    std::vector<std::string> goals_not_met;
    std::string reason;  // equivalent: the declared reason
};

// At most `max` of `all`, spread evenly over them (all when max is 0).
std::vector<const Mutant*> chosen(const std::vector<Mutant>& all, int max) {
    std::vector<const Mutant*> out;
    const std::size_t n = all.size();
    const std::size_t want = max <= 0 ? n : std::min<std::size_t>(n, static_cast<std::size_t>(max));
    for (std::size_t i = 0; i < want; ++i) out.push_back(&all[want == n ? i : i * n / want]);
    return out;
}

MutantRun gradeMutant(const LabSpec& spec, const fs::path& reference, const fs::path& scratch,
                      const Mutant& m, const GradeOptions& base) {
    std::error_code ec;
    fs::remove_all(scratch, ec);
    fs::create_directories(scratch / spec.id, ec);
    for (const std::string& f : spec.student_files) {
        fs::create_directories((scratch / spec.id / f).parent_path(), ec);
        fs::copy_file(reference / f, scratch / spec.id / f, fs::copy_options::overwrite_existing, ec);
    }
    std::ofstream(scratch / spec.id / m.file, std::ios::binary | std::ios::trunc) << m.text;
    const grader::Report report = gradeSubmission(scratch.string(), base);
    MutantRun run;
    run.mutant = m;
    run.mutant.text.clear();
    if (report.labs.empty()) {
        run.verdict = "killed";
        run.status = "crashed";
        return run;
    }
    const grader::ReportLab& lab = report.labs.front();
    run.status = lab.status;
    run.score = lab.score;
    run.max_score = lab.max_score;
    for (const grader::ReportGoal& g : lab.goals)
        if (!g.met) run.goals_not_met.push_back(g.id);
    if (lab.status == "compile_error" || lab.status == "link_error")
        run.verdict = "does_not_compile";
    else if (lab.score >= lab.max_score - 1e-9)
        run.verdict = "survivor";
    else
        run.verdict = "killed";
    return run;
}

struct LabTally {
    std::string id;
    int mutants = 0, made = 0, killed = 0, equivalent = 0, survivors = 0, not_compiling = 0;
    double seconds = 0.0;
    std::vector<MutantRun> runs;
    std::vector<std::string> stale;  // declared equivalents that are killed or no longer made
};

bool mutateLab(const MutantsArgs& args, const std::string& labs_root, const std::string& id,
               LabTally* tally) {
    const auto t0 = std::chrono::steady_clock::now();
    tally->id = id;
    const LabSpecResult parsed = parseLabSpec((fs::path(labs_root) / id).string());
    if (!parsed.ok) {
        for (const std::string& e : parsed.errors) std::cerr << e << "\n";
        return false;
    }
    const LabSpec& spec = parsed.spec;
    const fs::path reference_root = args.reference_root.empty()
                                        ? fs::path(labs_root).parent_path() / "reference_solutions"
                                        : fs::path(args.reference_root);
    const fs::path corpus = args.corpus_root.empty() ? fs::path(labs_root).parent_path() / "tests" / "corpus"
                                                     : fs::path(args.corpus_root);
    std::vector<EquivalentMutant> declared;
    std::vector<std::string> errors;
    std::error_code ec;
    if (fs::exists(corpus / id / "cases.json", ec) &&
        !loadEquivalentMutants(corpus / id / "cases.json", &declared, &errors)) {
        for (const std::string& e : errors) std::cerr << e << "\n";
        return false;
    }
    std::vector<Mutant> all;
    for (const std::string& f : spec.student_files) {
        const FileText t = readFile((reference_root / id / f).string(), 1u << 20);
        if (!t.ok) {
            std::cerr << "shaderlab: " << (reference_root / id / f).string() << ": " << t.error << "\n";
            return false;
        }
        std::vector<Mutant> mine = mutateFile(f, t.text);
        // Functions the starter gives as they are (a lighting helper, debug views) are the course's
        // code, not the student's work: no mistake of the lab is made there.
        const FileText starter = readFile((fs::path(spec.lab_dir) / f).string(), 1u << 20);
        const std::set<std::string> provided =
            starter.ok ? providedFunctions(t.text, starter.text) : std::set<std::string>{};
        const std::set<int> given = starter.ok ? providedLines(t.text, starter.text) : std::set<int>{};
        for (Mutant& m : mine) {
            const bool moved = m.op == "into-loop" || m.op == "out-of-loop";
            if (!provided.count(m.function) && (moved || !given.count(m.line))) all.push_back(std::move(m));
        }
    }
    tally->made = static_cast<int>(all.size());
    GradeOptions options;
    options.backend = chooseBackend(args.common.backend);
    options.labs_root = labs_root;
    options.labs = {id};
    options.isolation_root = reference_root.string();
    options.hints = false;
    options.limits.timeout_s = args.timeout_s;
    const fs::path scratch = fs::temp_directory_path() / ("shaderlab_mutants_" + std::to_string(::getpid()));
    std::printf("%s: %zu mutants of %s\n", id.c_str(), all.size(), (reference_root / id).string().c_str());
    std::fflush(stdout);
    for (const Mutant* m : chosen(all, args.max_per_lab)) {
        MutantRun run = gradeMutant(spec, reference_root / id, scratch, *m, options);
        ++tally->mutants;
        const auto eq = std::find_if(declared.begin(), declared.end(),
                                     [&](const EquivalentMutant& e) { return e.id == m->id; });
        if (run.verdict == "survivor" && eq != declared.end()) {
            run.verdict = "equivalent";
            run.reason = eq->reason;
        }
        if (run.verdict != "survivor" && run.verdict != "equivalent" && eq != declared.end())
            tally->stale.push_back(m->id + " is declared equivalent but is " +
                                   (run.verdict == "killed" ? std::string("killed") : "not compiling"));
        tally->killed += run.verdict == "killed";
        tally->equivalent += run.verdict == "equivalent";
        tally->survivors += run.verdict == "survivor";
        tally->not_compiling += run.verdict == "does_not_compile";
        if (run.verdict == "survivor")
            std::printf("  SURVIVES %-44s line %-4d %s\n", m->id.c_str(), m->line, m->change.c_str());
        tally->runs.push_back(std::move(run));
    }
    fs::remove_all(scratch, ec);
    for (const EquivalentMutant& e : declared)
        if (std::none_of(all.begin(), all.end(), [&](const Mutant& m) { return m.id == e.id; }))
            tally->stale.push_back(
                e.id + " is declared equivalent but no such mutant is made (the reference changed)");
    tally->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    for (const std::string& s : tally->stale)
        std::printf("  note     %s: remove it from cases.json\n", s.c_str());
    std::printf(
        "%s: %d mutants graded (of %d made), %d do not compile, %d killed, %d declared equivalent, %d "
        "undeclared survivors (%.1f s)\n",
        id.c_str(), tally->mutants, tally->made, tally->not_compiling, tally->killed, tally->equivalent,
        tally->survivors, tally->seconds);
    if (tally->survivors > 0)
        std::printf(
            "  each survivor changes what the code computes yet passes every goal: add a scene that "
            "shows it to the goal of its function, or declare it in %s (\"equivalent_mutants\": id and "
            "reason) when it computes the same thing\n",
            (corpus / id / "cases.json").string().c_str());
    std::fflush(stdout);
    return true;
}

json tallyJson(const LabTally& t) {
    json runs = json::array();
    for (const MutantRun& r : t.runs) {
        json j = {{"id", r.mutant.id},
                  {"file", r.mutant.file},
                  {"function", r.mutant.function},
                  {"operator", r.mutant.op},
                  {"line", r.mutant.line},
                  {"change", r.mutant.change},
                  {"verdict", r.verdict},
                  {"status", r.status},
                  {"score", r.score},
                  {"max_score", r.max_score},
                  {"goals_not_met", r.goals_not_met}};
        if (!r.reason.empty()) j["reason"] = r.reason;
        runs.push_back(std::move(j));
    }
    return {{"lab", t.id},
            {"mutants", t.mutants},
            {"made", t.made},
            {"does_not_compile", t.not_compiling},
            {"killed", t.killed},
            {"equivalent", t.equivalent},
            {"survivors", t.survivors},
            {"seconds", t.seconds},
            {"stale_declarations", t.stale},
            {"runs", runs}};
}

}  // namespace

int runMutants(const MutantsArgs& args) {
    std::string labs_root;
    if (!resolveLabsRoot(args.common, &labs_root)) return 2;
    std::vector<std::string> ids = args.common.labs;
    if (ids.empty()) ids = listLabIds(labs_root);
    const fs::path out =
        args.out_dir.empty() ? fs::path(labs_root).parent_path() / "out" / "mutants" : fs::path(args.out_dir);
    std::error_code ec;
    fs::create_directories(out, ec);
    if (ec) {
        std::cerr << "shaderlab: " << out.string() << ": cannot create the output folder\n";
        return 2;
    }
    json labs = json::array();
    bool readable = true;
    int survivors = 0;
    for (const std::string& id : ids) {
        LabTally tally;
        if (!mutateLab(args, labs_root, id, &tally)) {
            readable = false;
            continue;
        }
        survivors += tally.survivors;
        labs.push_back(tallyJson(tally));
        std::ofstream(out / "mutants.json") << json{{"labs", labs}}.dump(2) << "\n";
    }
    std::printf("mutants: %s\n", fs::absolute(out / "mutants.json").string().c_str());
    if (!readable) return 2;
    return survivors > 0 ? 1 : 0;
}

}  // namespace shaderlab::cli
