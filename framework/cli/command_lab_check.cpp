// `shaderlab lab-check ID`: everything CI asks of one lab, for the instructor writing it, in the
// time that lab takes rather than the whole suite's: lab.json parses and validates; the starter
// and reference files are there; the course index links the lab; the README's generated tables
// are lab.json's (`--fix` rewrites them; a README without markers is left alone, with a note);
// the corpus has the course's minimum of cases; the goldens equal a fresh render of the reference
// (what the Goldens test asks); every corpus verdict holds and the hints are fresh (`shaderlab
// corpus --lab ID`, run in-process). One line per check, with its time and the file at fault.
// Exit 0 when every check passes, 1 when one fails, 2 when there is no such lab.
#include <fcntl.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <system_error>
#include <vector>

#include "commands.h"
#include "grader/base/atomic_file.h"
#include "shaderlab/authoring/corpus_cases.h"
#include "shaderlab/authoring/readme_tables.h"
#include "shaderlab/base/json_messages.h"
#include "shaderlab/base/paths.h"
#include "shaderlab/glsl/glsl_compose.h"
#include "shaderlab/grading/grading.h"
#include "shaderlab/lab/lab_catalog.h"
#include "shaderlab/lab/lab_spec.h"

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace shaderlab::cli {

using namespace authoring;

namespace {

// The course's minimum corpus (tests/corpus_test.cpp, LabCorpus.HasEnoughMistakesAndAlternatives).
constexpr int kMinMistakes = 6;
constexpr int kMinAlternatives = 3;

// "1 pass", "7 passes".
std::string count(std::size_t n, const std::string& one, const std::string& many) {
    return std::to_string(n) + " " + (n == 1 ? one : many);
}

// One check's verdict: "ok", "FAIL", "note" (passes, with something to know), "fixed" (passes
// after --fix rewrote something) or "skip" (could not run: counts as failed).
struct Verdict {
    std::string status = "ok";
    std::string detail;
    std::vector<std::string> more;  // further lines: every error, every failing case
};

Verdict fail(const std::string& detail, std::vector<std::string> more = {}) {
    return {"FAIL", detail, std::move(more)};
}

// Every message but the first, which a verdict's line shows.
std::vector<std::string> rest(const std::vector<std::string>& messages) {
    return messages.size() > 1 ? std::vector<std::string>(messages.begin() + 1, messages.end())
                               : std::vector<std::string>{};
}

// Where one lab-check run reads and writes.
struct LabCheckPlaces {
    std::string labs_root, course;
    fs::path lab, reference, corpus, out;
    std::string id;
    LabSpecResult parsed;
};

// "labs/ID/x.frag" for a path inside the course, else the path as it is.
std::string shown(const fs::path& p, const LabCheckPlaces& at) {
    const fs::path rel = p.lexically_relative(at.course);
    return rel.empty() || *rel.begin() == ".." ? p.string() : rel.string();
}

Verdict checkLabJson(const LabCheckPlaces& at) {
    const LabSpecResult& r = at.parsed;
    if (!r.ok) return fail(r.errors.empty() ? "does not parse" : r.errors.front(), rest(r.errors));
    const LabSpec& s = r.spec;
    return {"ok",
            shown(at.lab / "lab.json", at) + " valid (docs/lab.schema.json and the validator): " +
                count(s.passes.size(), "pass", "passes") + ", " + count(s.scenes.size(), "scene", "scenes") +
                ", " + count(s.goals.size(), "goal", "goals") + ", " + formatNumber(s.grading.points) +
                " points",
            {}};
}

Verdict checkStarter(const LabCheckPlaces& at) {
    const LabSpec& spec = at.parsed.spec;
    bool marked = false;
    for (const std::string& f : spec.student_files) {
        const FileText t = readFile((at.lab / f).string());
        if (!t.ok) return fail(shown(at.lab / f, at) + ": " + t.error);
        marked = marked || t.text.find("TODO(student)") != std::string::npos;
    }
    if (!marked)
        return fail("no student file in " + shown(at.lab, at) +
                    "/ marks what to write with TODO(student) (docs/authoring.md, step 3)");
    return {
        "ok",
        count(spec.student_files.size(), "student file", "student files") + " in " + shown(at.lab, at) + "/",
        {}};
}

Verdict checkReference(const LabCheckPlaces& at) {
    const LabSpec& spec = at.parsed.spec;
    std::error_code ec;
    for (const std::string& f : spec.student_files)
        if (!fs::is_regular_file(at.reference / f, ec))
            return fail(shown(at.reference / f, at) +
                        " is missing: the reference solution holds every student file");
    // Every goal's work taken from the reference and composed with the reference gives the
    // reference back: its functions are there, with the starter's signatures.
    std::vector<std::string> problems;
    int functions = 0;
    for (const GoalSpec& g : spec.goals) {
        std::map<std::string, std::vector<std::string>> take;
        for (const GoalWork& w : g.work)
            if (!w.function.empty()) take[w.file].push_back(w.function);
        for (const auto& [file, names] : take) {
            const std::string reference = readFile((at.reference / file).string()).text;
            const std::string starter = readFile((at.lab / file).string()).text;
            glsl::ComposeInput in{file, reference, reference, "", names, {}};
            const glsl::Composed alone = glsl::composeFunctions(in);
            if (!alone.ok || alone.text != reference)
                problems.push_back("goal " + g.id + ": " +
                                   (alone.ok ? "composing it changes the reference" : alone.note));
            // The starter's functions as the student gets them: the reference must take the same.
            glsl::ComposeInput with_starter{file, reference, starter, "", names, {}};
            const glsl::Composed started = glsl::composeFunctions(with_starter);
            if (!started.ok) problems.push_back("goal " + g.id + ": the starter's " + started.note);
            functions += static_cast<int>(names.size());
        }
    }
    if (!problems.empty())
        return fail(
            "the reference cannot be composed with the goals' work (docs/grading.md, \"Goal isolation\")",
            problems);
    return {"ok",
            count(spec.student_files.size(), "student file", "student files") + " in " +
                shown(at.reference, at) + "/" +
                (functions ? ", " + count(functions, "function", "functions") + " of the goals' work in each"
                           : ""),
            {}};
}

Verdict checkCourseIndex(const LabCheckPlaces& at) {
    const fs::path index = fs::path(at.labs_root) / "README.md";
    const FileText t = readFile(index.string());
    if (!t.ok) return fail(shown(index, at) + ": " + t.error);
    if (t.text.find(courseIndexLink(at.id)) == std::string::npos)
        return fail(shown(index, at) + " has no row linking " + courseIndexLink(at.id) +
                    " (the CourseIndex test asks for one)");
    std::error_code ec;
    if (!fs::is_regular_file(at.lab / "README.md", ec))
        return fail(shown(at.lab / "README.md", at) + " is missing: the index links it");
    return {"ok", shown(index, at) + " links " + courseIndexLink(at.id), {}};
}

Verdict checkReadme(const LabCheckPlaces& at, bool fix) {
    const fs::path readme = at.lab / "README.md";
    const FileText t = readFile(readme.string());
    if (!t.ok) return fail(shown(readme, at) + ": " + t.error);
    const ReadmeTablesCheck r = checkReadmeTables(t.text, at.parsed.spec);
    if (!r.errors.empty()) return fail(shown(readme, at) + ": " + r.errors.front(), rest(r.errors));
    if (r.sections.empty())
        return {"note",
                shown(readme, at) +
                    " has no generated tables (no \"<!-- generated by shaderlab lab-check --fix: ... -->\" "
                    "markers): written by hand, left alone",
                {}};
    std::string stale;
    for (const std::string& s : r.stale) stale += (stale.empty() ? "" : " and ") + s;
    if (stale.empty()) return {"ok", shown(readme, at) + ": its tables are lab.json's", {}};
    if (!fix)
        return fail(shown(readme, at) + ": the " + stale +
                    " table is not what lab.json says: run `shaderlab lab-check " + at.id + " --fix`");
    std::string error;
    if (!grader::writeFileAtomically(readme.string(), r.fixed, &error, false)) return fail(error);
    return {"fixed", shown(readme, at) + ": rewrote the " + stale + " table from lab.json", {}};
}

Verdict checkMinimumCorpus(const LabCheckPlaces& at) {
    const fs::path file = at.corpus / "cases.json";
    std::error_code ec;
    if (!fs::exists(file, ec))
        return fail(shown(file, at) +
                    " is missing (`shaderlab new-lab` writes it; `shaderlab corpus add-case` fills it)");
    std::vector<Case> cases;
    std::vector<std::string> errors;
    if (!loadCases(file, at.parsed.spec, &cases, &errors))
        return fail(errors.empty() ? shown(file, at) + " cannot be read" : errors.front(), rest(errors));
    int mistakes = 0, alternatives = 0;
    for (const Case& c : cases) {
        mistakes += c.kind == "mistake";
        alternatives += c.kind == "alternative";
    }
    const std::string counts = std::to_string(mistakes) + " mistakes (at least " +
                               std::to_string(kMinMistakes) + "), " + std::to_string(alternatives) +
                               " alternatives (at least " + std::to_string(kMinAlternatives) + ")";
    if (mistakes < kMinMistakes || alternatives < kMinAlternatives)
        return fail(shown(file, at) + ": " + counts + ": add them with `shaderlab corpus add-case " + at.id +
                    " ...`");
    return {"ok", shown(file, at) + ": " + counts, {}};
}

std::set<std::string> filesIn(const fs::path& dir) {
    std::set<std::string> names;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir, ec)) names.insert(e.path().filename().string());
    return names;
}

// What tests/goldens_test.cpp asks of every lab: a fresh render of the reference equals the stored
// goldens to the bit, or, drawn by another renderer than the stored ones, the reference scores
// full marks against them.
Verdict checkGoldens(const LabCheckPlaces& at, const std::string& backend) {
    const fs::path stored = at.lab / "golden";
    const std::string rerun = " (run `shaderlab goldens --lab " + at.id + "`)";
    std::error_code ec;
    if (!fs::is_directory(stored, ec)) return fail(shown(stored, at) + "/ is missing" + rerun);
    const fs::path fresh_root = at.out / "goldens";
    fs::remove_all(fresh_root, ec);
    const Backend chosen = chooseBackend(backend);
    const std::vector<std::string> errors =
        writeGoldens(at.reference.parent_path().string(), at.labs_root, {at.id}, chosen, fresh_root.string());
    if (!errors.empty())
        return fail("the reference solution does not render: " + errors.front(), rest(errors));
    const fs::path made = fresh_root / at.id / "golden";
    const std::set<std::string> want = filesIn(made), have = filesIn(stored);
    for (const std::string& n : want)
        if (!have.count(n)) return fail(shown(stored / n, at) + " is missing" + rerun);
    for (const std::string& n : have)
        if (!want.count(n)) return fail(shown(stored / n, at) + " is not drawn any more" + rerun);
    const std::string stored_renderer = readFile((stored / "renderer.txt").string()).text;
    const std::string renderer = readFile((made / "renderer.txt").string()).text;
    if (!stored_renderer.empty() && stored_renderer != renderer) {
        GradeOptions options;
        options.backend = chosen;
        options.labs_root = at.labs_root;
        options.labs = {at.id};
        options.hints = false;
        const grader::Report report = gradeSubmission(at.reference.parent_path().string(), options);
        const bool full = !report.labs.empty() && report.labs.front().status == "passed" &&
                          report.labs.front().score >= report.labs.front().max_score - 1e-9;
        if (!full)
            return fail(shown(stored, at) +
                        "/ drawn by another renderer, and the reference does not score full "
                        "marks against it" +
                        rerun);
        return {"ok",
                std::to_string(have.size()) + " files in " + shown(stored, at) +
                    "/: drawn by another renderer; the reference scores full marks against them",
                {}};
    }
    for (const std::string& n : want)
        if (readFile((stored / n).string()).text != readFile((made / n).string()).text)
            return fail(shown(stored / n, at) + " is stale: not what the reference draws now" + rerun);
    return {"ok",
            std::to_string(have.size()) + " files in " + shown(stored, at) +
                "/ equal a fresh render of the reference",
            {}};
}

// runCorpus and runMutants print a line per case; they go to a log here, so that lab-check prints
// one line per check, and what fails is read back from corpus.json or mutants.json.
int runLogged(const std::function<int()>& command, const fs::path& log) {
    std::fflush(stdout);
    std::cout.flush();
    const int saved = ::dup(STDOUT_FILENO);
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (saved < 0 || fd < 0) {
        if (saved >= 0) ::close(saved);
        if (fd >= 0) ::close(fd);
        return command();
    }
    ::dup2(fd, STDOUT_FILENO);
    ::close(fd);
    const int rc = command();
    std::fflush(stdout);
    std::cout.flush();
    ::dup2(saved, STDOUT_FILENO);
    ::close(saved);
    return rc;
}

Verdict checkCorpusVerdicts(const LabCheckPlaces& at, const LabCheckArgs& args) {
    const fs::path cases = at.corpus / "cases.json";
    std::error_code ec;
    if (!fs::exists(cases, ec)) return fail(shown(cases, at) + " is missing");
    CorpusArgs corpus;
    corpus.common.backend = args.common.backend;
    corpus.common.labs_root = at.labs_root;
    corpus.common.labs = {at.id};
    corpus.corpus_root = at.corpus.parent_path().string();
    corpus.reference_root = at.reference.parent_path().string();
    corpus.out_dir = (at.out / "corpus").string();
    corpus.timeout_s = args.timeout_s;
    fs::remove_all(corpus.out_dir, ec);
    fs::create_directories(corpus.out_dir, ec);
    const fs::path log = fs::path(corpus.out_dir) / "corpus.log";
    const int rc = runLogged([&] { return runCorpus(corpus); }, log);
    const json summary =
        json::parse(readFile((fs::path(corpus.out_dir) / "corpus.json").string()).text, nullptr, false);
    if (rc == 2 || !summary.is_array())
        return fail(shown(cases, at) + ": the corpus cannot be graded (log: " + shown(log, at) + ")");
    int ok = 0, graded = 0;
    std::vector<std::string> failing;
    for (const json& o : summary) {
        if (o.value("kind", "") != "hints") ++graded;
        if (o.value("ok", false)) {
            ++ok;
            continue;
        }
        failing.push_back(o.value("case", "?") + " (" + o.value("kind", "?") +
                          "): " + o.value("expected", "") +
                          (o.value("goals_not_met", json::array()).empty()
                               ? ""
                               : "; goals not met: " + o["goals_not_met"].dump()));
    }
    if (rc != 0 || !failing.empty())
        return fail(std::to_string(failing.size()) + " of " + std::to_string(summary.size()) +
                        " verdicts of " + shown(at.corpus, at) +
                        "/ not as expected (reports: " + shown(corpus.out_dir, at) + ")",
                    failing);
    return {"ok",
            std::to_string(graded) + " submissions of " + shown(at.corpus, at) +
                "/ as expected (reference, starter and every case); hints in " + shown(at.lab / "hints", at) +
                "/ fresh",
            {}};
}

// Coverage by mutation: no mutant of the reference that changes what it computes passes every goal
// unless cases.json declares it equivalent (command_mutants.cpp).
Verdict checkMutants(const LabCheckPlaces& at, const LabCheckArgs& args) {
    MutantsArgs mutants;
    mutants.common.backend = args.common.backend;
    mutants.common.labs_root = at.labs_root;
    mutants.common.labs = {at.id};
    mutants.corpus_root = at.corpus.parent_path().string();
    mutants.reference_root = at.reference.parent_path().string();
    mutants.out_dir = (at.out / "mutants").string();
    mutants.timeout_s = args.timeout_s;
    std::error_code ec;
    fs::create_directories(mutants.out_dir, ec);
    const fs::path log = fs::path(mutants.out_dir) / "mutants.log";
    const int rc = runLogged([&] { return runMutants(mutants); }, log);
    const json result =
        json::parse(readFile((fs::path(mutants.out_dir) / "mutants.json").string()).text, nullptr, false);
    if (rc == 2 || !result.is_object() || result["labs"].empty())
        return fail("the mutants cannot be graded (log: " + shown(log, at) + ")");
    const json& lab = result["labs"][0];
    std::vector<std::string> survivors;
    for (const json& r : lab["runs"])
        if (r.value("verdict", "") == "survivor")
            survivors.push_back(r.value("id", "?") + " (line " + std::to_string(r.value("line", 0)) +
                                "): " + r.value("change", ""));
    const std::string figures = std::to_string(lab.value("mutants", 0)) + " mutants, " +
                                std::to_string(lab.value("killed", 0)) + " killed, " +
                                std::to_string(lab.value("equivalent", 0)) + " declared equivalent, " +
                                std::to_string(lab.value("does_not_compile", 0)) + " not compiling";
    // Every line the starter's: the reference holds no work of the student's to mutate.
    if (lab.value("made", 0) == 0)
        return fail(
            "no mutants: the reference's student files are the starter's in every function "
            "(mutants leaves the starter's code alone), so no goal's work is tested");
    if (!survivors.empty())
        return fail(figures + ", " + std::to_string(survivors.size()) +
                        " undeclared survivors: show each in a scene, or declare it in " +
                        shown(at.corpus / "cases.json", at) + " (\"equivalent_mutants\") with the reason",
                    survivors);
    return {"ok", figures, {}};
}

void printVerdict(const std::string& name, const Verdict& v, double seconds) {
    std::printf("  %-5s %-16s %7.2f s  %s\n", v.status.c_str(), name.c_str(), seconds, v.detail.c_str());
    const std::size_t shown_max = 12;
    for (std::size_t i = 0; i < v.more.size() && i < shown_max; ++i)
        std::printf("%31s%s\n", "", v.more[i].c_str());
    if (v.more.size() > shown_max) std::printf("%31s... and %zu more\n", "", v.more.size() - shown_max);
    std::fflush(stdout);
}

}  // namespace

int runLabCheck(const LabCheckArgs& args) {
    LabCheckPlaces at;
    if (!resolveLabsRoot(args.common, &at.labs_root)) return 2;
    at.course = fs::path(at.labs_root).parent_path().string();
    at.id = args.lab;
    at.lab = fs::path(at.labs_root) / args.lab;
    std::error_code ec;
    if (!isPlainName(args.lab) || !fs::is_directory(at.lab, ec)) {
        std::cerr << "shaderlab: lab-check: there is no lab \"" << args.lab << "\" in " << at.labs_root
                  << didYouMean(args.lab, listLabIds(at.labs_root)) << "\n";
        return 2;
    }
    at.reference = (args.reference_root.empty() ? fs::path(at.course) / "reference_solutions"
                                                : fs::path(args.reference_root)) /
                   args.lab;
    at.corpus =
        (args.corpus_root.empty() ? fs::path(at.course) / "tests" / "corpus" : fs::path(args.corpus_root)) /
        args.lab;
    at.out =
        args.out_dir.empty() ? fs::path(at.course) / "out" / "lab-check" / args.lab : fs::path(args.out_dir);
    fs::create_directories(at.out, ec);
    if (ec) {
        std::cerr << "shaderlab: lab-check: " << at.out.string() << ": cannot create the output folder\n";
        return 2;
    }

    std::printf("lab-check %s\n", args.lab.c_str());
    const auto start = std::chrono::steady_clock::now();
    int passed = 0, failed = 0, skipped = 0, notes = 0;
    auto run = [&](const std::string& name, bool needs_spec, const std::function<Verdict()>& check) {
        const auto t0 = std::chrono::steady_clock::now();
        const Verdict v =
            needs_spec && !at.parsed.ok ? Verdict{"skip", "needs a lab.json that parses", {}} : check();
        printVerdict(name, v, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        failed += v.status == "FAIL";
        skipped += v.status == "skip";
        passed += v.status != "FAIL" && v.status != "skip";
        notes += v.status == "note";
    };
    run("lab.json", false, [&] {
        at.parsed = parseLabSpec(at.lab.string());
        return checkLabJson(at);
    });
    run("starter", true, [&] { return checkStarter(at); });
    run("reference", true, [&] { return checkReference(at); });
    run("course index", false, [&] { return checkCourseIndex(at); });
    run("README tables", true, [&] { return checkReadme(at, args.fix); });
    run("minimum corpus", true, [&] { return checkMinimumCorpus(at); });
    run("goldens fresh", true, [&] { return checkGoldens(at, args.common.backend); });
    run("corpus verdicts", true, [&] { return checkCorpusVerdicts(at, args); });
    run("mutants", true, [&] { return checkMutants(at, args); });

    const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const std::string skips = skipped ? ", " + std::to_string(skipped) + " skipped" : "";
    std::printf("lab-check %s: %d of %d checks passed%s, %d failed%s (%.1f s)%s\n", args.lab.c_str(), passed,
                passed + failed + skipped,
                notes ? (" (" + std::to_string(notes) + " with a note)").c_str() : "", failed, skips.c_str(),
                total, failed + skipped ? "" : ": ready for CI");
    return failed + skipped ? 1 : 0;
}

}  // namespace shaderlab::cli
