// `shaderlab corpus`: proves that each lab's grade follows its learning goals. For every lab with
// a corpus folder (tests/corpus/<lab>/cases.json), it grades the reference solution (full marks),
// the starter code (renders, fails), and every case: a mistake a student makes (must fail, with
// the goals it names not met), a correct solution written differently (must pass with full
// marks), or a broken submission (must end with the status it names). A case folder holds only
// the files that differ from the reference solution. Grading uses the stored goldens unless
// --reference is given. Exit 0 when every expectation holds, 1 when one does not, 2 when the
// corpus cannot be read.
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "commands.h"
#include "grader/metrics/metrics.h"
#include "grader/reports/report.h"
#include "shaderlab/authoring/corpus_cases.h"
#include "shaderlab/authoring/corpus_margins.h"
#include "shaderlab/authoring/corpus_verdict.h"
#include "shaderlab/base/paths.h"
#include "shaderlab/grading/grading.h"
#include "shaderlab/grading/mistake_hints.h"
#include "shaderlab/lab/lab_catalog.h"
#include "shaderlab/lab/lab_spec.h"

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace shaderlab::cli {

using namespace authoring;

namespace {

struct Outcome {
    std::string lab, name, kind, about;
    std::string status;
    double score = 0.0, max_score = 0.0;
    std::vector<std::string> goals_failed;
    bool ok = false;
    std::string why;  // when !ok: the expectation that did not hold
    std::string report;
    json margins;  // with --margins: the case's tightest margins (corpus_margins.h)
};

// A mistake graded into `out_dir`: where its pictures are.
struct MistakeRun {
    const Case* c = nullptr;
    grader::Report report;
    fs::path out_dir;
};

// Whether case `a` is the simpler explanation of a picture `b` draws too: it fails fewer goals, all
// among b's (b adds a second mistake to a's), or the same goals with a's work in its functions and
// b's inlined (b's goals judged on the whole shaders).
bool simplerCase(const Case& a, const Case& b) {
    const std::set<std::string> fa(a.fails.begin(), a.fails.end()), fb(b.fails.begin(), b.fails.end());
    if (!std::includes(fb.begin(), fb.end(), fa.begin(), fa.end())) return false;
    return fa.size() < fb.size() || (a.whole.empty() && !b.whole.empty());
}

// A picture that a mistake draws like a simpler one (simplerCase) is left to the simpler one: two
// mistakes at once, or one mistake inlined into main, would otherwise make the picture ambiguous
// and the one-mistake hint would be lost with it (dropAmbiguousHints).
void leaveToSimplerCases(LabHints* hints, const std::map<std::string, const Case*>& cases) {
    std::vector<bool> drop(hints->hints.size(), false);
    for (std::size_t i = 0; i < hints->hints.size(); ++i)
        for (std::size_t j = 0; j < hints->hints.size(); ++j) {
            const MistakeHint &a = hints->hints[i], &b = hints->hints[j];
            if (i == j || a.scene != b.scene || a.image != b.image || a.picture.width != b.picture.width ||
                a.picture.height != b.picture.height ||
                !simplerCase(*cases.at(a.mistake), *cases.at(b.mistake)))
                continue;
            const grader::PsnrResult p = grader::computePsnr(a.picture, b.picture);
            if (p.ok && p.psnr_db >= hints->min_psnr_db) drop[j] = true;
        }
    std::vector<MistakeHint> kept;
    for (std::size_t i = 0; i < hints->hints.size(); ++i)
        if (!drop[i]) kept.push_back(std::move(hints->hints[i]));
    hints->hints = std::move(kept);
}

// A lab's known-mistake hints from its graded mistakes: for every scene a mistake fails, its
// picture of the scene's first wrong image (as the report wrote it), made small, except the
// `unstable` ones; then the pictures two mistakes share are dropped, since they cannot tell the
// two apart.
LabHints collectHints(const std::vector<MistakeRun>& runs, const std::vector<std::string>& unstable,
                      std::vector<std::string>* errors, std::size_t* dropped = nullptr) {
    LabHints hints;
    hints.unstable = unstable;
    for (const MistakeRun& run : runs)
        if (hints.renderer.empty()) hints.renderer = run.report.renderer;
    for (const MistakeRun& run : runs) {
        if (run.report.labs.empty()) continue;
        for (const grader::ReportScene& scene : run.report.labs.front().scenes) {
            if (scene.status == "passed" || scene.first_failing_pass.empty()) continue;
            for (const grader::ReportPass& pass : scene.passes) {
                if (pass.name != scene.first_failing_pass || pass.student_image.empty()) continue;
                grader::Image picture;
                std::string error;
                if (!grader::readPng((run.out_dir / pass.student_image).string(), &picture, &error)) {
                    errors->push_back(error);
                    continue;
                }
                MistakeHint m;
                m.mistake = run.c->name;
                m.about = run.c->about;
                m.scene = scene.name;
                m.image = pass.name;
                m.file = run.c->name + "/" + scene.name + "." + pass.name + ".png";
                if (std::find(unstable.begin(), unstable.end(), m.file) != unstable.end()) continue;
                m.picture = hintPicture(picture, hints.factor);
                hints.hints.push_back(std::move(m));
            }
        }
    }
    const std::size_t all = hints.hints.size();
    std::map<std::string, const Case*> cases;
    for (const MistakeRun& run : runs) cases[run.c->name] = run.c;
    leaveToSimplerCases(&hints, cases);
    dropAmbiguousHints(&hints);
    if (dropped != nullptr) *dropped = all - hints.hints.size();
    return hints;
}

// Empty when the stored hints are what `fresh` would write; otherwise what differs. Drawn by the
// renderer that made the stored ones (or by an unknown one), every picture must be equal to the
// bit; by another renderer (a newer Mesa) within the PSNR that hints are matched with, so that a
// newer Mesa never fails a user's check of the course.
std::string compareHints(const LabHints& stored, const LabHints& fresh) {
    const bool same_renderer = stored.renderer.empty() || stored.renderer == fresh.renderer;
    // Another renderer may tell apart two mistakes' pictures that the stored one drew alike (and
    // left out), so there every stored picture must have its fresh twin, and more fresh ones are
    // no fault; on the same renderer the sets are equal.
    if (stored.factor != fresh.factor || (same_renderer && stored.hints.size() != fresh.hints.size()))
        return std::to_string(stored.hints.size()) + " stored pictures, " +
               std::to_string(fresh.hints.size()) + " fresh";
    for (std::size_t i = 0; i < stored.hints.size(); ++i) {
        const MistakeHint& a = stored.hints[i];
        const auto twin = std::find_if(fresh.hints.begin(), fresh.hints.end(),
                                       [&](const MistakeHint& h) { return h.file == a.file; });
        if (twin == fresh.hints.end()) return a.file + " is no longer drawn (no fresh picture of it)";
        const MistakeHint& b = same_renderer ? fresh.hints[i] : *twin;
        if (a.file != b.file || a.about != b.about || a.picture.width != b.picture.width ||
            a.picture.height != b.picture.height)
            return a.file + " differs from " + b.file;
        if (!same_renderer) {
            const grader::PsnrResult p = grader::computePsnr(a.picture, b.picture);
            if (!p.ok || p.psnr_db < stored.min_psnr_db)
                return a.file + " is not what the mistake draws now (PSNR " +
                       (p.ok ? std::to_string(p.psnr_db) : p.error) + " dB on " + fresh.renderer + ")";
            continue;
        }
        // Stored as 8-bit PNG and made the same way: equal to the last bit when fresh.
        for (int y = 0; y < a.picture.height; ++y)
            for (int x = 0; x < a.picture.width; ++x)
                for (int c = 0; c < 3; ++c)
                    if (a.picture.at(x, y, a.picture.channels >= 3 ? c : 0) != b.picture.at(x, y, c))
                        return a.file + " is not what the mistake draws now";
    }
    return {};
}

Outcome judge(const LabSpec& spec, const Case& c, const grader::Report& report, const std::string& where) {
    Outcome o;
    o.lab = spec.id;
    o.name = c.name;
    o.kind = c.kind;
    o.about = c.about;
    o.report = where;
    if (report.labs.empty()) {
        o.why = "no report";
        return o;
    }
    const grader::ReportLab& l = report.labs.front();
    o.status = l.status;
    o.score = l.score;
    o.max_score = l.max_score;
    for (const grader::ReportGoal& g : l.goals)
        if (!g.met) o.goals_failed.push_back(g.id);
    o.why = expectationsMissed(spec, c, l);
    o.ok = o.why.empty();
    return o;
}

// What every lab of a `corpus` run shares.
struct CorpusSetup {
    std::string labs_root;
    fs::path corpus, reference_root, out;
    GradeOptions base;
    bool margins = false;
};

// How the lab's known-mistake hints did on its mistakes, as they are graded.
struct HintTally {
    std::vector<MistakeRun> mistakes;
    int recognised = 0, taken_for_another = 0;
};

// The submissions a lab's corpus grades: the reference solution, the starter code, then every
// case as a folder of its own. A case that cannot be made is left out, `readable` false.
std::vector<std::pair<Case, fs::path>> labSubmissions(const CorpusSetup& setup, const std::string& id,
                                                      const LabSpec& spec, const std::vector<Case>& cases,
                                                      bool* readable) {
    std::vector<std::pair<Case, fs::path>> runs;
    Case reference;
    reference.name = "reference";
    reference.kind = "reference";
    reference.about = "the reference solution";
    runs.emplace_back(reference, setup.reference_root);
    Case starter;
    starter.name = "starter";
    starter.kind = "starter";
    starter.about = "the starter code in labs/";
    runs.emplace_back(starter, setup.labs_root);
    for (const Case& c : cases) {
        const fs::path submission = setup.out / id / "submissions" / c.name;
        std::string error;
        if (!materialise(spec, setup.reference_root / id, setup.corpus / id / c.name, c, submission,
                         &error)) {
            std::cerr << "shaderlab: " << error << "\n";
            *readable = false;
            continue;
        }
        runs.emplace_back(c, submission);
    }
    return runs;
}

// Grades one submission of the lab into <out>/<lab>/reports/<case>/, judges it and prints its
// line. A mistake's report goes to `tally` (which keeps a pointer to `c`).
Outcome gradeCase(const CorpusSetup& setup, const LabSpec& spec, const Case& c, const fs::path& submission,
                  HintTally* tally) {
    const std::string& id = spec.id;
    std::error_code ec;
    GradeOptions options = setup.base;
    options.labs = {id};
    options.out_dir = (setup.out / id / "reports" / c.name).string();
    if (c.timeout_s > 0) options.limits.timeout_s = c.timeout_s;
    fs::create_directories(options.out_dir, ec);
    grader::Report report = gradeSubmission(submission.string(), options);
    report.tool_version = SHADERLAB_VERSION;
    const fs::path report_file = fs::path(options.out_dir) / "report.json";
    std::ofstream(report_file) << grader::reportToJson(report);
    std::ofstream(fs::path(options.out_dir) / "report.html")
        << grader::reportToHtml(report, {options.out_dir, 20u << 20});
    Outcome o = judge(spec, c, report, report_file.string());
    if (c.kind == "mistake" && !report.labs.empty()) {
        bool own = false, other = false;
        for (const grader::ReportScene& s : report.labs.front().scenes) {
            own = own || s.hint.mistake == c.name;
            other = other || (!s.hint.mistake.empty() && s.hint.mistake != c.name);
        }
        tally->recognised += own;
        tally->taken_for_another += other;
        tally->mistakes.push_back({&c, report, options.out_dir});
    }
    std::string failed;
    for (const std::string& g : o.goals_failed) failed += (failed.empty() ? "" : ",") + g;
    std::printf("  %-4s %-30s %-11s %-13s %6.2f / %-6.2f %s\n", o.ok ? "ok" : "FAIL", c.name.c_str(),
                c.kind.c_str(), o.status.c_str(), o.score, o.max_score,
                failed.empty() ? "" : ("goals not met: " + failed).c_str());
    if (!o.ok) std::printf("       expected: %s (%s)\n", o.why.c_str(), c.about.c_str());
    return o;
}

// The stored hints must be what the mistakes draw now (`shaderlab goldens` writes them): prints
// the verdict, and adds a failed outcome when they are stale.
void checkHints(const std::string& id, const LabSpec& spec, const HintTally& tally,
                std::vector<Outcome>* outcomes) {
    std::vector<std::string> hint_errors;
    LabHints stored;
    std::string stored_error;
    const fs::path hints_dir = fs::path(spec.lab_dir) / "hints";
    const bool readable_hints = loadLabHints(hints_dir.string(), &stored, &stored_error);
    const LabHints fresh = collectHints(tally.mistakes, stored.unstable, &hint_errors);
    std::string stale = readable_hints ? compareHints(stored, fresh) : stored_error;
    if (!hint_errors.empty()) stale = hint_errors.front();
    std::printf(
        "  %-4s known-mistake hints: %zu pictures; %d of %zu mistakes recognised by them, %d also taken "
        "for another in some scene\n",
        stale.empty() ? "ok" : "FAIL", fresh.hints.size(), tally.recognised, tally.mistakes.size(),
        tally.taken_for_another);
    if (readable_hints && !stored.renderer.empty() && stored.renderer != fresh.renderer)
        std::printf("       compared within %.0f dB: drawn by %s, stored from %s\n", stored.min_psnr_db,
                    fresh.renderer.c_str(), stored.renderer.c_str());
    if (!stale.empty()) {
        std::printf("       %s: %s (run `shaderlab goldens` and commit)\n", hints_dir.string().c_str(),
                    stale.c_str());
        Outcome o;
        o.lab = id;
        o.name = "hints";
        o.kind = "hints";
        o.why = "labs/" + id + "/hints is stale: " + stale;
        outcomes->push_back(std::move(o));
    }
}

// The two figures that show the grade separates the two groups.
void printSeparation(const std::string& id, const std::vector<Outcome>& outcomes) {
    double worst_alternative = -1.0, best_mistake = -1.0, max_score = 0.0;
    for (const Outcome& o : outcomes) {
        if (o.lab != id) continue;
        // A stale-hints outcome carries no score: the lab's points come from the graded ones.
        if (o.kind == "hints") continue;
        max_score = std::max(max_score, o.max_score);
        if (o.kind == "alternative" || o.kind == "reference")
            worst_alternative = worst_alternative < 0 ? o.score : std::min(worst_alternative, o.score);
        if (o.kind == "mistake") best_mistake = std::max(best_mistake, o.score);
    }
    std::printf(
        "  worst correct solution %.2f / %.2f, best mistake %.2f / %.2f (passing needs every goal)\n\n",
        worst_alternative, max_score, std::max(best_mistake, 0.0), max_score);
}

// One lab's corpus: its reference, starter and cases graded and judged, its hints checked.
// `readable` turns false when the lab or its cases cannot be read.
void runLabCorpus(const CorpusSetup& setup, const std::string& id, std::vector<Outcome>* outcomes,
                  bool* readable) {
    const LabSpecResult parsed = parseLabSpec((fs::path(setup.labs_root) / id).string());
    if (!parsed.ok) {
        for (const std::string& e : parsed.errors) std::cerr << e << "\n";
        *readable = false;
        return;
    }
    std::vector<Case> cases;
    std::vector<std::string> errors;
    if (!loadCases(setup.corpus / id / "cases.json", parsed.spec, &cases, &errors)) {
        for (const std::string& e : errors) std::cerr << e << "\n";
        *readable = false;
        return;
    }
    std::printf("%s: %s\n", id.c_str(), parsed.spec.title.c_str());
    const std::vector<std::pair<Case, fs::path>> runs =
        labSubmissions(setup, id, parsed.spec, cases, readable);
    HintTally tally;
    for (const auto& [c, submission] : runs)
        outcomes->push_back(gradeCase(setup, parsed.spec, c, submission, &tally));
    checkHints(id, parsed.spec, tally, outcomes);
    printSeparation(id, *outcomes);
    if (!setup.margins) return;
    const std::map<std::string, json> margins = reportLabMargins(parsed.spec, cases, setup.out / id);
    for (Outcome& o : *outcomes)
        if (o.lab == id && margins.count(o.name)) o.margins = margins.at(o.name);
}

// corpus.json, one entry per outcome. Whether every outcome is as expected.
bool writeCorpusSummary(const fs::path& out, const std::vector<Outcome>& outcomes) {
    json summary = json::array();
    bool all_ok = true;
    for (const Outcome& o : outcomes) {
        all_ok = all_ok && o.ok;
        summary.push_back({{"lab", o.lab},
                           {"case", o.name},
                           {"kind", o.kind},
                           {"about", o.about},
                           {"status", o.status},
                           {"score", o.score},
                           {"max_score", o.max_score},
                           {"goals_not_met", o.goals_failed},
                           {"ok", o.ok},
                           {"expected", o.why},
                           {"report", o.report}});
        if (!o.margins.is_null()) summary.back()["margins"] = o.margins;
    }
    std::ofstream(out / "corpus.json") << summary.dump(2) << "\n";
    std::printf("corpus: %s\n", fs::absolute(out / "corpus.json").string().c_str());
    return all_ok;
}

}  // namespace

int runCorpus(const CorpusArgs& args) {
    CorpusSetup setup;
    if (!resolveLabsRoot(args.common, &setup.labs_root)) return 2;
    const std::string& labs_root = setup.labs_root;
    setup.corpus = args.corpus_root.empty() ? fs::path(labs_root).parent_path() / "tests" / "corpus"
                                            : fs::path(args.corpus_root);
    setup.reference_root = args.reference_root.empty()
                               ? fs::path(labs_root).parent_path() / "reference_solutions"
                               : fs::path(args.reference_root);
    std::vector<std::string> ids = args.common.labs;
    if (ids.empty())
        for (const std::string& id : listLabIds(labs_root))
            if (fs::exists(setup.corpus / id / "cases.json")) ids.push_back(id);
    if (ids.empty()) {
        std::cerr << "shaderlab: no lab has a corpus under " << setup.corpus.string() << "\n";
        return 2;
    }
    setup.out = args.out_dir;
    std::error_code ec;
    fs::create_directories(setup.out, ec);
    if (ec) {
        std::cerr << "shaderlab: " << setup.out.string() << ": cannot create the output folder\n";
        return 2;
    }
    setup.base.backend = chooseBackend(args.common.backend);
    setup.base.labs_root = labs_root;
    setup.base.limits.timeout_s = args.timeout_s;
    if (args.use_reference) setup.base.reference_root = setup.reference_root.string();
    // Goal isolation composes with the reference's sources even where the images are the goldens.
    setup.base.isolation_root = setup.reference_root.string();
    setup.margins = args.margins;

    std::vector<Outcome> outcomes;
    bool readable = true;
    for (const std::string& id : ids) runLabCorpus(setup, id, &outcomes, &readable);
    const bool all_ok = writeCorpusSummary(setup.out, outcomes);
    if (!readable) return 2;
    return all_ok ? 0 : 1;
}

std::vector<std::string> writeHints(const std::string& labs_root, const std::string& corpus_root,
                                    const std::string& reference_root, const std::vector<std::string>& labs,
                                    const std::string& backend, const std::string& stored_root) {
    std::vector<std::string> errors;
    std::vector<std::string> ids = labs;
    if (ids.empty()) ids = listLabIds(labs_root);
    std::error_code ec;
    const fs::path scratch = fs::temp_directory_path() / ("shaderlab_hints_" + std::to_string(::getpid()));
    for (const std::string& id : ids) {
        const LabSpecResult parsed = parseLabSpec((fs::path(labs_root) / id).string());
        if (!parsed.ok) {
            errors.insert(errors.end(), parsed.errors.begin(), parsed.errors.end());
            continue;
        }
        const fs::path hints_dir =
            (stored_root.empty() ? fs::path(parsed.spec.lab_dir) : fs::path(stored_root) / id) / "hints";
        const fs::path cases_file = fs::path(corpus_root) / id / "cases.json";
        std::vector<Case> cases;
        if (!fs::exists(cases_file, ec)) {
            fs::remove_all(hints_dir, ec);  // a lab without a corpus has no hints
            continue;
        }
        if (!loadCases(cases_file, parsed.spec, &cases, &errors)) continue;
        GradeOptions options;
        options.backend = chooseBackend(backend);
        options.labs_root = labs_root;
        options.labs = {id};
        options.goldens_root = stored_root;
        options.isolation_root = reference_root;
        options.hints = false;
        // Every mistake twice: a picture that differs between the two renders (a mistake that
        // reads memory nothing wrote) could not recognise anyone, nor be checked for staleness.
        std::vector<MistakeRun> runs[2];
        for (const Case& c : cases) {
            if (c.kind != "mistake") continue;
            const fs::path submission = scratch / id / "submissions" / c.name;
            std::string error;
            if (!materialise(parsed.spec, fs::path(reference_root) / id, fs::path(corpus_root) / id / c.name,
                             c, submission, &error)) {
                errors.push_back(error);
                continue;
            }
            for (int k = 0; k < 2; ++k) {
                options.out_dir = (scratch / id / ("reports" + std::to_string(k)) / c.name).string();
                fs::create_directories(options.out_dir, ec);
                runs[k].push_back({&c, gradeSubmission(submission.string(), options), options.out_dir});
            }
        }
        // One picture that differs makes all of that mistake's suspect: it reads undefined memory,
        // which may happen to hold the same garbage twice in a row and other garbage tomorrow.
        std::vector<std::string> unstable;
        {
            std::vector<std::string> ignored;
            const LabHints first = collectHints(runs[0], {}, &ignored),
                           second = collectHints(runs[1], {}, &ignored);
            std::set<std::string> unstable_mistakes;
            for (const MistakeHint& a : first.hints) {
                bool same = false;
                for (const MistakeHint& b : second.hints)
                    same = same || (b.file == a.file && b.picture.pixels == a.picture.pixels);
                if (!same) unstable_mistakes.insert(a.mistake);
            }
            for (const MistakeHint& a : first.hints)
                if (unstable_mistakes.count(a.mistake)) unstable.push_back(a.file);
        }
        std::size_t dropped = 0;
        const LabHints hints = collectHints(runs[0], unstable, &errors, &dropped);
        std::string error;
        if (!writeLabHints(hints_dir.string(), hints, &error)) errors.push_back(error);
        std::printf(
            "%s: %zu known-mistake pictures of %zu mistakes (left out: %zu drawn alike by two mistakes, %zu "
            "not "
            "drawn the same way twice)\n",
            id.c_str(), hints.hints.size(), runs[0].size(), dropped, unstable.size());
    }
    fs::remove_all(scratch, ec);
    return errors;
}

}  // namespace shaderlab::cli
