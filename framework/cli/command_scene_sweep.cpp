// `shaderlab scene-sweep LAB --scene NAME --vary PATH=VALUES ...`: which variant of a scene shows
// each goal's idea best, from evidence. The base scene's variants (scene_sweep.h) become the scenes
// of a temporary copy of the lab, every goal judging every variant; the reference solution draws
// them once (its goldens), then every mistake and alternative of the lab's corpus is graded on
// them as `corpus` grades it, one case after another (each render uses every core through
// llvmpipe), and each variant is scored per goal by how far its mistakes fail and its alternatives
// pass (scene_sweep_score.h). Prints the ranking and the best variants as lab.json scenes; writes
// <out>/sweep.json and each variant's reference pictures in <out>/pictures/. It changes nothing
// of the lab. Exit 0 when the best variant separates every goal it is judged under without failing
// another goal's mistakes, 1 when none does, 2 when the sweep cannot run (bad input, a variant
// that is not a valid scene, a reference that does not draw one).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "commands.h"
#include "grader/reports/report.h"
#include "shaderlab/authoring/corpus_cases.h"
#include "shaderlab/authoring/scene_sweep.h"
#include "shaderlab/authoring/scene_sweep_score.h"
#include "shaderlab/base/json_messages.h"
#include "shaderlab/base/paths.h"
#include "shaderlab/grading/grading.h"
#include "shaderlab/lab/lab_spec.h"

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace shaderlab::cli {

using namespace authoring;

namespace {

using sweep::Candidate;
using sweep::CaseResult;
using sweep::ojson;

// Candidates drawn by one render of the swept lab: more per render saves starting and compiling,
// fewer keeps each render's time limit and memory modest.
constexpr std::size_t kCandidatesPerLab = 32;

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

void refuse(const std::string& message) { std::cerr << "shaderlab scene-sweep: " << message << "\n"; }

// What one sweep reads and where it works.
struct SweepPlan {
    std::string labs_root;
    LabSpec spec;
    ojson lab_doc;  // lab.json as written
    ojson base;     // the base scene's object in it
    std::string base_name;
    std::vector<std::string> goals;
    std::vector<sweep::Variation> vary;
    std::vector<sweep::Patch> patches;
    std::vector<Case> cases;         // the corpus's mistakes and alternatives
    std::set<std::string> required;  // --mistake: the only mistakes candidates must catch; empty: all
    fs::path corpus, reference_root, out, work;
    std::vector<Candidate> candidates;
    Backend backend = Backend::OSMesa;
};

// "lights[0].direction=[1,-1,0], uniforms.u_shininess=8", or the label of a listed candidate.
std::string candidateText(const Candidate& c, const std::vector<sweep::Variation>& vary) {
    if (c.base) return "the scene as lab.json has it";
    if (!c.label.empty()) return c.label;
    std::string out;
    for (const sweep::Variation& v : vary)
        out += (out.empty() ? "" : ", ") + v.path + "=" + sweep::getPath(c.scene, v.path).dump();
    return out;
}

// The words of every shader the lab may compile, for a uniform name no shader mentions.
std::set<std::string> shaderWords(const SweepPlan& plan) {
    std::set<std::string> words;
    const std::set<std::string> exts = {".vert", ".frag", ".glsl", ".geom", ".comp", ".tesc", ".tese"};
    const std::regex word("[A-Za-z_][A-Za-z0-9_]*");
    for (const fs::path& dir : {fs::path(plan.spec.lab_dir), plan.reference_root / plan.spec.id,
                                fs::path(plan.labs_root) / "shared"}) {
        std::error_code ec;
        for (auto it = fs::recursive_directory_iterator(dir, ec);
             !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
            if (!it->is_regular_file() || !exts.count(it->path().extension().string())) continue;
            const FileText t = readFile(it->path().string(), 1u << 20);
            for (auto m = std::sregex_iterator(t.text.begin(), t.text.end(), word);
                 m != std::sregex_iterator(); ++m)
                words.insert(m->str());
        }
    }
    return words;
}

// A uniform varied that no shader of the lab mentions is a typo, not a sweep.
bool checkUniformNames(const SweepPlan& plan) {
    std::vector<std::string> names;
    for (const sweep::Variation& v : plan.vary)
        if (v.path.rfind("uniforms.", 0) == 0)
            names.push_back(v.path.substr(9, v.path.find_first_of(".[", 9) - 9));
    for (const sweep::Patch& p : plan.patches)
        if (p.scene.contains("uniforms") && p.scene["uniforms"].is_object())
            for (auto it = p.scene["uniforms"].begin(); it != p.scene["uniforms"].end(); ++it)
                names.push_back(it.key());
    if (names.empty()) return true;
    const std::set<std::string> words = shaderWords(plan);
    const std::vector<std::string> known(words.begin(), words.end());
    bool ok = true;
    for (const std::string& n : names) {
        if (words.count(n)) continue;
        refuse("uniforms." + n + ": no shader of " + plan.spec.id + " mentions " + n + didYouMean(n, known));
        ok = false;
    }
    return ok;
}

// The base scene's object in lab.json, and the goals that judge it (or those asked for).
bool chooseSceneAndGoals(const SceneSweepArgs& args, const sweep::SweepFile& file, SweepPlan* plan) {
    if (!args.scene.empty() && !file.scene.empty() && args.scene != file.scene) {
        refuse("--scene " + args.scene + " and the sweep file's \"scene\": " + file.scene + " differ");
        return false;
    }
    plan->base_name = args.scene.empty() ? file.scene : args.scene;
    std::vector<std::string> names;
    for (const ojson& s : plan->lab_doc.value("scenes", ojson::array())) {
        names.push_back(s.value("name", ""));
        if (names.back() == plan->base_name) plan->base = s;
    }
    if (plan->base_name.empty() || plan->base.is_null()) {
        std::string all;
        for (const std::string& n : names) all += (all.empty() ? "" : ", ") + n;
        refuse(plan->base_name.empty() ? "which scene? Give --scene NAME, one of " + all
                                       : plan->spec.id + " has no scene " + quoteJson(plan->base_name) +
                                             didYouMean(plan->base_name, names) + "; its scenes: " + all);
        return false;
    }
    std::vector<std::string> asked = args.goals;
    if (asked.empty()) asked = file.goals;
    std::vector<std::string> ids;
    for (const GoalSpec& g : plan->spec.goals) ids.push_back(g.id);
    if (std::find(asked.begin(), asked.end(), "all") != asked.end()) asked = ids;
    for (const std::string& g : asked) {
        if (std::find(ids.begin(), ids.end(), g) == ids.end()) {
            refuse("--goal " + g + ": " + plan->spec.id + " has no such goal" + didYouMean(g, ids) +
                   " (\"all\" judges under every goal)");
            return false;
        }
        if (std::find(plan->goals.begin(), plan->goals.end(), g) == plan->goals.end())
            plan->goals.push_back(g);
    }
    if (plan->goals.empty())
        for (const GoalSpec& g : plan->spec.goals)
            for (const SceneSpec& s : plan->spec.scenes)
                if (s.base_name == plan->base_name &&
                    std::find(g.scenes.begin(), g.scenes.end(), s.name) != g.scenes.end() &&
                    std::find(plan->goals.begin(), plan->goals.end(), g.id) == plan->goals.end())
                    plan->goals.push_back(g.id);
    return true;
}

// --mistake: corpus mistakes of the goals judged, the only ones a candidate must catch.
bool chooseMistakes(const std::vector<std::string>& names, SweepPlan* plan) {
    std::vector<std::string> mistakes;
    for (const Case& c : plan->cases)
        if (c.kind == "mistake") mistakes.push_back(c.name);
    for (const std::string& n : names) {
        const auto c = std::find_if(plan->cases.begin(), plan->cases.end(),
                                    [&](const Case& k) { return k.kind == "mistake" && k.name == n; });
        if (c == plan->cases.end()) {
            refuse("--mistake " + n + ": the corpus of " + plan->spec.id + " has no such mistake" +
                   didYouMean(n, mistakes));
            return false;
        }
        const bool judged = std::any_of(c->fails.begin(), c->fails.end(), [&](const std::string& g) {
            return std::find(plan->goals.begin(), plan->goals.end(), g) != plan->goals.end();
        });
        if (!judged) {
            std::string fails;
            for (const std::string& g : c->fails) fails += (fails.empty() ? "" : ", ") + g;
            refuse("--mistake " + n + " fails goal " + fails +
                   ", which the candidates are not judged under: add --goal " + c->fails.front());
            return false;
        }
        plan->required.insert(n);
    }
    return true;
}

// Everything the sweep reads, checked before anything is drawn. False: refused, said why.
bool readInputs(const SceneSweepArgs& args, SweepPlan* plan) {
    LabSpecResult parsed;
    if (!loadCommandLab(args.common, args.lab, &plan->labs_root, &parsed)) return false;
    plan->spec = parsed.spec;
    const fs::path parent = fs::path(plan->labs_root).parent_path();
    plan->corpus = args.corpus_root.empty() ? parent / "tests" / "corpus" : fs::path(args.corpus_root);
    plan->reference_root =
        args.reference_root.empty() ? parent / "reference_solutions" : fs::path(args.reference_root);
    plan->out = args.out_dir.empty() ? parent / "out" / "scene-sweep" / args.lab : fs::path(args.out_dir);
    plan->work = plan->out / "work";
    plan->lab_doc =
        ojson::parse(readFile((fs::path(plan->spec.lab_dir) / "lab.json").string()).text, nullptr, false);
    sweep::SweepFile file;
    std::vector<std::string> errors;
    if (!args.sweep_file.empty()) sweep::readSweepFile(args.sweep_file, &file, &errors);
    plan->vary = file.vary;
    plan->patches = file.patches;
    for (const std::string& text : args.vary) {
        sweep::Variation v;
        std::string error;
        if (sweep::parseVary(text, &v, &error))
            plan->vary.push_back(std::move(v));
        else
            errors.push_back("--vary " + error);
    }
    for (const std::string& e : errors) refuse(e);
    if (!errors.empty() || !chooseSceneAndGoals(args, file, plan) || !checkUniformNames(*plan)) return false;
    std::vector<Case> cases;
    if (!loadCases(plan->corpus / args.lab / "cases.json", plan->spec, &cases, &errors)) {
        for (const std::string& e : errors) refuse(e);
        return false;
    }
    for (const Case& c : cases)
        if (c.kind == "mistake" || c.kind == "alternative") plan->cases.push_back(c);
    if (!chooseMistakes(args.mistakes.empty() ? file.mistakes : args.mistakes, plan)) return false;
    if (plan->cases.empty()) {
        refuse((plan->corpus / args.lab / "cases.json").string() +
               " has no mistake or alternative: there is nothing to separate (`shaderlab corpus add-case`)");
        return false;
    }
    std::size_t dropped = 0;
    std::string error;
    if (!sweep::makeCandidates(plan->base, plan->vary, plan->patches, args.max_candidates, &plan->candidates,
                               &dropped, &error)) {
        refuse(error);
        return false;
    }
    if (dropped > 0)
        std::printf("(%zu candidate%s left out: the same scene as an earlier one, c00 included)\n", dropped,
                    dropped == 1 ? "" : "s");
    return true;
}

// A copy of the labs folder's shared parts and of the lab (without its goldens and hints) under
// <work>/labs, and one submission folder per case under <work>/submissions.
bool prepareWork(const SweepPlan& plan, std::string* error) {
    std::error_code ec;
    fs::remove_all(plan.work, ec);
    const fs::path labs = plan.work / "labs";
    fs::create_directories(labs / plan.spec.id, ec);
    for (const auto& entry : fs::directory_iterator(plan.labs_root, ec)) {
        if (!entry.is_directory() || fs::exists(entry.path() / "lab.json")) continue;
        fs::copy(entry.path(), labs / entry.path().filename(), fs::copy_options::recursive, ec);
        if (ec) {
            *error = entry.path().string() + ": " + ec.message();
            return false;
        }
    }
    for (const auto& entry : fs::directory_iterator(plan.spec.lab_dir, ec)) {
        const std::string name = entry.path().filename().string();
        if (name == "lab.json" || name == "golden" || name == "hints") continue;
        fs::copy(entry.path(), labs / plan.spec.id / name, fs::copy_options::recursive, ec);
        if (ec) {
            *error = entry.path().string() + ": " + ec.message();
            return false;
        }
    }
    for (const Case& c : plan.cases)
        if (!materialise(plan.spec, plan.reference_root / plan.spec.id, plan.corpus / plan.spec.id / c.name,
                         c, plan.work / "submissions" / c.name, error))
            return false;
    return true;
}

// lab.json with candidates [first, first + count) as its only scenes, every goal judging each.
ojson chunkLab(const SweepPlan& plan, std::size_t first, std::size_t count) {
    ojson doc = plan.lab_doc;
    ojson scenes = ojson::array(), names = ojson::array();
    for (std::size_t i = first; i < first + count; ++i) {
        scenes.push_back(plan.candidates[i].scene);
        names.push_back(plan.candidates[i].id);
    }
    ojson goals = ojson::array();
    bool implicit = false;
    for (const GoalSpec& g : plan.spec.goals) {
        ojson goal = {
            {"id", g.id}, {"title", g.title}, {"points", g.points}, {"scenes", names}, {"passes", g.passes}};
        if (!g.depends_on.empty()) goal["depends_on"] = g.depends_on;
        if (g.pipeline) goal["pipeline"] = true;
        goals.push_back(std::move(goal));
        implicit = implicit || g.implicit;
    }
    // A lab without goals shares grading.points over its scenes; here it has explicit ones.
    if (implicit && doc.contains("grading")) doc["grading"].erase("points");
    doc["scenes"] = scenes;
    doc["goals"] = goals;
    return doc;
}

fs::path workLab(const SweepPlan& plan) { return plan.work / "labs" / plan.spec.id; }

// Messages about the swept lab, each "scenes[k]" named by its candidate.
std::vector<std::string> nameCandidates(const std::vector<std::string>& messages, const SweepPlan& plan,
                                        std::size_t first) {
    std::vector<std::string> out;
    const std::string file = (workLab(plan) / "lab.json").string() + ": ";
    const std::regex scene("scenes\\[([0-9]+)\\]");
    for (std::string m : messages) {
        for (std::size_t at; (at = m.find(file)) != std::string::npos;) m.erase(at, file.size());
        std::smatch k;
        if (std::regex_search(m, k, scene) && first + std::stoul(k[1].str()) < plan.candidates.size()) {
            const Candidate& c = plan.candidates[first + std::stoul(k[1].str())];
            m = "candidate " + c.id + " (" + candidateText(c, plan.vary) + "): " + m;
        }
        out.push_back(m);
    }
    return out;
}

// Every chunk of candidates parses as the lab's scenes; otherwise says which candidate fails how.
bool validateCandidates(const SweepPlan& plan) {
    std::vector<std::string> errors;
    for (std::size_t first = 0; first < plan.candidates.size(); first += kCandidatesPerLab) {
        const std::size_t count = std::min(kCandidatesPerLab, plan.candidates.size() - first);
        std::ofstream(workLab(plan) / "lab.json") << chunkLab(plan, first, count).dump(2) << "\n";
        const LabSpecResult parsed = parseLabSpec(workLab(plan).string());
        for (const std::string& e : nameCandidates(parsed.errors, plan, first))
            if (std::find(errors.begin(), errors.end(), e) == errors.end()) errors.push_back(e);
    }
    for (std::size_t i = 0; i < errors.size() && i < 8; ++i) refuse(errors[i]);
    if (errors.size() > 8) refuse("and " + std::to_string(errors.size() - 8) + " more problems");
    return errors.empty();
}

// One render's worth of candidates: the reference draws them into goldens, then every case is graded
// on them. False when the reference does not draw them.
bool sweepChunk(const SceneSweepArgs& args, const SweepPlan& plan, std::size_t first, std::size_t count,
                std::vector<CaseResult>* results, double* reference_s) {
    const std::vector<Candidate> chunk(plan.candidates.begin() + static_cast<long>(first),
                                       plan.candidates.begin() + static_cast<long>(first + count));
    const std::string range = chunk.front().id + (count > 1 ? "-" + chunk.back().id : "");
    std::ofstream(workLab(plan) / "lab.json") << chunkLab(plan, first, count).dump(2) << "\n";
    const fs::path goldens = plan.work / "goldens";
    const auto t0 = Clock::now();
    const std::vector<std::string> errors =
        writeGoldens(plan.reference_root.string(), (plan.work / "labs").string(), {plan.spec.id},
                     plan.backend, goldens.string());
    *reference_s += secondsSince(t0);
    if (!errors.empty()) {
        refuse("the reference solution does not draw " + range + ":");
        for (const std::string& e : nameCandidates(errors, plan, first)) refuse(e);
        return false;
    }
    std::printf("  %s: the reference drew them in %.1f s; the corpus on them:\n", range.c_str(),
                secondsSince(t0));
    std::error_code ec;
    fs::create_directories(plan.out / "pictures", ec);
    for (const auto& entry : fs::directory_iterator(goldens / plan.spec.id / "golden", ec)) {
        const std::string name = entry.path().filename().string();
        if (name.find(".coverage.") == std::string::npos && name != "renderer.txt")
            fs::copy_file(entry.path(), plan.out / "pictures" / name, fs::copy_options::overwrite_existing,
                          ec);
    }
    for (std::size_t i = 0; i < plan.cases.size(); ++i) {
        const Case& c = plan.cases[i];
        GradeOptions options;
        options.backend = plan.backend;
        options.labs_root = (plan.work / "labs").string();
        options.labs = {plan.spec.id};
        options.goldens_root = goldens.string();
        options.hints = false;
        options.limits.timeout_s = std::max(args.timeout_s, c.timeout_s) * static_cast<double>(count);
        const auto t1 = Clock::now();
        const grader::Report report = gradeSubmission((plan.work / "submissions" / c.name).string(), options);
        const json doc = json::parse(grader::reportToJson(report), nullptr, false);
        const json lab = doc.is_object() && !doc["labs"].empty() ? doc["labs"][0] : json::object();
        const std::string status = lab.value("status", "no report");
        CaseResult& r = (*results)[i];
        if (status != "passed" && status != "failed")
            r.problems.push_back(range + ": " + status + ": " + lab.value("message", ""));
        sweep::collectImages(lab, chunk, plan.spec.grading.thresholds, &r);
        std::printf("    %-32s %-11s %-13s %5.1f s\n", c.name.c_str(), c.kind.c_str(), status.c_str(),
                    secondsSince(t1));
    }
    return true;
}

// Goals with nothing to separate, and cases that did not draw.
void printNotes(const SweepPlan& plan, const std::vector<CaseResult>& results) {
    for (const std::string& g : plan.goals) {
        const bool any = std::any_of(plan.cases.begin(), plan.cases.end(), [&](const Case& c) {
            return std::find(c.fails.begin(), c.fails.end(), g) != c.fails.end();
        });
        if (!any)
            std::printf("note: no mistake of the corpus fails goal %s: only its alternatives judge it\n",
                        g.c_str());
    }
    for (const CaseResult& r : results)
        for (const std::string& p : r.problems)
            std::printf("note: %s did not draw on %s (left out there)\n", r.name.c_str(), p.c_str());
}

// The best `top` candidates as lab.json scenes, to paste.
void printBest(const SweepPlan& plan, const std::vector<sweep::CandidateScore>& ranked, std::size_t top) {
    if (top == 0 || ranked.empty()) return;
    std::string goals;
    for (const std::string& g : plan.goals) goals += (goals.empty() ? "" : ", ") + g;
    std::printf("\nthe best %zu as lab.json scenes (add the name to the \"scenes\" of goal%s %s):\n",
                std::min(top, ranked.size()), plan.goals.size() == 1 ? "" : "s", goals.c_str());
    for (std::size_t r = 0; r < ranked.size() && r < top; ++r) {
        const Candidate& c = plan.candidates[ranked[r].candidate];
        std::printf("  %s\n", sweep::compactJson(sweep::pasteableScene(c, plan.base_name)).c_str());
    }
}

// The picture of the candidate's final image the reference drew, relative to <out>; "" if none.
std::string pictureOf(const SweepPlan& plan, const std::string& id) {
    for (const std::string& name : {id + ".png", id + ".preview.png", id + "_t0.png", id + "_t0.preview.png"})
        if (fs::exists(plan.out / "pictures" / name)) return "pictures/" + name;
    return "";
}

}  // namespace

int runSceneSweep(const SceneSweepArgs& args) {
    const auto t0 = Clock::now();
    SweepPlan plan;
    if (!readInputs(args, &plan)) return 2;
    plan.backend = chooseBackend(args.common.backend);
    // The swept lab and the case folders go however the sweep ends, unless asked for.
    struct RemoveWork {
        const fs::path& work;
        bool keep;
        ~RemoveWork() {
            std::error_code ignored;
            if (!keep) fs::remove_all(work, ignored);
        }
    } remove_work{plan.work, args.keep};
    std::error_code ec;
    fs::create_directories(plan.out, ec);
    fs::remove_all(plan.out / "pictures", ec);  // an earlier sweep's results go, whatever this one gives
    fs::remove(plan.out / "sweep.json", ec);
    std::string error;
    if (!prepareWork(plan, &error)) {
        refuse(error);
        return 2;
    }
    if (!validateCandidates(plan)) return 2;

    std::size_t mistakes = 0;
    for (const Case& c : plan.cases) mistakes += c.kind == "mistake";
    std::string goals;
    for (const std::string& g : plan.goals) goals += (goals.empty() ? "" : ", ") + g;
    const std::size_t alternatives = plan.cases.size() - mistakes;
    std::printf(
        "%s: %zu candidates of scene '%s' (c00 is the scene as lab.json has it), judged under goal%s %s "
        "by %zu mistake%s and %zu alternative%s\n",
        plan.spec.id.c_str(), plan.candidates.size(), plan.base_name.c_str(),
        plan.goals.size() == 1 ? "" : "s", goals.c_str(), mistakes, mistakes == 1 ? "" : "s", alternatives,
        alternatives == 1 ? "" : "s");
    if (!plan.required.empty()) {
        std::string names;
        for (const std::string& n : plan.required) names += (names.empty() ? "" : ", ") + n;
        std::printf("(the candidates must catch %s; the goals' other mistakes may pass on them)\n",
                    names.c_str());
    }
    std::vector<CaseResult> results(plan.cases.size());
    for (std::size_t i = 0; i < plan.cases.size(); ++i) {
        results[i].name = plan.cases[i].name;
        results[i].kind = plan.cases[i].kind;
        results[i].fails = plan.cases[i].fails;
        results[i].may_fail = expectedFailures(plan.spec, plan.cases[i].fails);
        results[i].required = plan.required.empty() || plan.required.count(plan.cases[i].name) > 0;
    }
    double reference_s = 0.0;
    for (std::size_t first = 0; first < plan.candidates.size(); first += kCandidatesPerLab)
        if (!sweepChunk(args, plan, first, std::min(kCandidatesPerLab, plan.candidates.size() - first),
                        &results, &reference_s))
            return 2;

    const std::vector<sweep::CandidateScore> ranked =
        sweep::rankCandidates(plan.spec, plan.candidates, plan.goals, results);
    std::printf("\n");
    printNotes(plan, results);
    std::printf(
        "ranked: fewest problems (mistakes missed, alternatives failed, other goals' mistakes failing here), "
        "then "
        "score = min(mistakes, alternatives); factors as `corpus --margins` gives them, above 1 on the right "
        "side "
        "(* the base scene)\n");
    sweep::printRanking(plan.candidates, plan.vary, ranked);
    printBest(plan, ranked, args.top);

    const double seconds = secondsSince(t0);
    ojson ranking = sweep::rankingJson(plan.candidates, plan.vary, ranked, plan.base_name);
    for (ojson& entry : ranking) entry["picture"] = pictureOf(plan, entry["id"].get<std::string>());
    ojson variations = ojson::array();
    for (const sweep::Variation& v : plan.vary)
        variations.push_back({{"path", v.path}, {"values", v.values}});
    const ojson doc = {{"lab", plan.spec.id},
                       {"scene", plan.base_name},
                       {"goals", plan.goals},
                       {"mistakes", plan.required},
                       {"variations", variations},
                       {"cases", plan.cases.size()},
                       {"seconds", seconds},
                       {"reference_seconds", reference_s},
                       {"candidates_per_second", static_cast<double>(plan.candidates.size()) / seconds},
                       {"candidates", ranking}};
    std::ofstream(plan.out / "sweep.json") << doc.dump(2) << "\n";
    std::printf("\n%zu candidates x %zu cases in %.1f s (%.2f candidates/s; the reference %.1f s)\n",
                plan.candidates.size(), plan.cases.size(), seconds,
                static_cast<double>(plan.candidates.size()) / seconds, reference_s);
    std::printf("sweep: %s, reference pictures in %s\n",
                fs::absolute(plan.out / "sweep.json").string().c_str(),
                fs::absolute(plan.out / "pictures").string().c_str());
    return !ranked.empty() && ranked.front().problems == 0 ? 0 : 1;
}

}  // namespace shaderlab::cli
