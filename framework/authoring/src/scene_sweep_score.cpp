// How well each candidate scene separates each goal's mistakes from the alternatives; see
// scene_sweep_score.h.
#include "shaderlab/authoring/scene_sweep_score.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace shaderlab::authoring::sweep {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Above 1: passes by that factor; below 1: fails (0: on something no threshold measures).
double passFactor(const VerdictMargin& v) {
    if (v.passed) return v.margin;
    return std::isnan(v.margin) ? 0.0 : 1.0 / v.margin;
}

// The case's smallest pass factor over the goal's images on the candidate, each image taken as
// the grader takes it for that goal; NaN when the case drew none of them.
double casePassFactor(const CaseResult& c, const std::string& candidate, const GoalSpec& goal) {
    const auto it = c.images.find(candidate);
    if (it == c.images.end()) return kNaN;
    double smallest = kNaN;
    for (const ImageResult& im : it->second) {
        if (std::find(goal.passes.begin(), goal.passes.end(), im.pass) == goal.passes.end()) continue;
        const double f = passFactor(im.has_isolated && !goal.pipeline ? im.isolated : im.pipeline);
        if (std::isnan(smallest) || f < smallest) smallest = f;
    }
    return smallest;
}

std::string joined(const std::vector<std::string>& items, const char* separator = ", ") {
    std::string out;
    for (const std::string& s : items) out += (out.empty() ? "" : separator) + s;
    return out;
}

double smallestFactor(const std::vector<CaseOnGoal>& cases) {
    double out = kInf;
    for (const CaseOnGoal& c : cases) out = std::min(out, c.factor);
    return out;
}

GoalScore scoreGoal(const GoalSpec& goal, const std::string& candidate,
                    const std::vector<CaseResult>& cases) {
    GoalScore gs;
    gs.goal = goal.id;
    for (const CaseResult& c : cases) {
        const double pf = casePassFactor(c, candidate, goal);
        if (std::isnan(pf)) continue;  // not drawn: said once, with the case's problems
        const bool mistake = c.kind == "mistake";
        if (mistake && std::find(c.fails.begin(), c.fails.end(), goal.id) != c.fails.end()) {
            if (c.required)
                gs.mistakes.push_back({c.name, joined(c.fails), pf == 0.0 ? kInf : 1.0 / pf, pf < 1.0});
        } else if (!mistake)
            gs.alternatives.push_back({c.name, "", pf, pf >= 1.0});
        else if (!c.may_fail.count(goal.id))  // a mistake of a goal this one rests on may do either
            gs.others.push_back({c.name, joined(c.fails), pf, pf >= 1.0});
    }
    gs.mistake_factor = smallestFactor(gs.mistakes);
    gs.alternative_factor = smallestFactor(gs.alternatives);
    gs.isolation_factor = smallestFactor(gs.others);
    const auto wrong = [](const std::vector<CaseOnGoal>& list) {
        return static_cast<int>(
            std::count_if(list.begin(), list.end(), [](const CaseOnGoal& c) { return !c.as_wanted; }));
    };
    const int missed = wrong(gs.mistakes), failed = wrong(gs.alternatives), also = wrong(gs.others);
    gs.separates = missed == 0 && failed == 0;
    gs.isolates = also == 0;
    gs.problems = missed + failed + also;
    gs.score = std::min(gs.mistake_factor, gs.alternative_factor);
    gs.caught_factor = kInf;
    for (const CaseOnGoal& m : gs.mistakes)
        if (m.as_wanted) gs.caught_factor = std::min(gs.caught_factor, m.factor);
    return gs;
}

// factorText, but "same" for 0: a mistake that draws the reference's very image.
std::string factorCell(double f) { return f == 0.0 ? "same" : factorText(f); }

// The cases of `list` that are (or are not) as wanted: their names, or with their factor
// ("name (0.52x)"), or with their goal ("name (goal tone)").
enum class Shown { Name, Factor, Goal };
std::vector<std::string> namesWhere(const std::vector<CaseOnGoal>& list, bool as_wanted, Shown shown) {
    std::vector<std::string> out;
    for (const CaseOnGoal& c : list) {
        if (c.as_wanted != as_wanted) continue;
        out.push_back(shown == Shown::Name     ? c.name
                      : shown == Shown::Factor ? c.name + " (" + factorCell(c.factor) + ")"
                                               : c.name + " (goal " + c.goal + ")");
    }
    return out;
}

// A cell no wider than `width`: longer text is cut with "...".
std::string cell(const std::string& text, std::size_t width) {
    return text.size() <= width ? text : text.substr(0, width - 3) + "...";
}

ojson finite(double v) { return std::isfinite(v) ? ojson(v) : ojson(nullptr); }

ojson casesJson(const std::vector<CaseOnGoal>& list, const char* verdict, bool with_goal) {
    ojson out = ojson::array();
    for (const CaseOnGoal& c : list) {
        ojson j = {{"case", c.name}, {"factor", finite(c.factor)}, {verdict, c.as_wanted}};
        if (with_goal) j["goal"] = c.goal;
        out.push_back(std::move(j));
    }
    return out;
}

}  // namespace

void collectImages(const nlohmann::json& report_lab, const std::vector<Candidate>& candidates,
                   const GradingThresholds& lab, CaseResult* out) {
    for (const nlohmann::json& scene : report_lab.value("scenes", nlohmann::json::array())) {
        const std::string name = scene.value("name", "");
        const auto c = std::find_if(candidates.begin(), candidates.end(), [&](const Candidate& k) {
            return name == k.id || name.rfind(k.id + "_t", 0) == 0;
        });
        if (c == candidates.end()) continue;
        std::vector<ImageResult>& images = out->images[c->id];
        for (const nlohmann::json& pass : scene.value("passes", nlohmann::json::array())) {
            ImageResult im;
            im.pass = pass.value("pass", pass.value("name", ""));
            const nlohmann::json thresholds =
                pass.contains("thresholds") ? pass["thresholds"] : nlohmann::json();
            im.pipeline = verdictMargin(pass, thresholds, lab);
            if (pass.contains("on_reference_inputs") && pass["on_reference_inputs"].is_object()) {
                im.has_isolated = true;
                im.isolated = verdictMargin(pass["on_reference_inputs"], thresholds, lab);
            }
            images.push_back(std::move(im));
        }
    }
}

std::vector<CandidateScore> rankCandidates(const LabSpec& spec, const std::vector<Candidate>& candidates,
                                           const std::vector<std::string>& goals,
                                           const std::vector<CaseResult>& cases) {
    std::vector<CandidateScore> out;
    for (std::size_t i = 0; i < candidates.size(); ++i) {
        CandidateScore cs;
        cs.candidate = i;
        cs.score = kInf;
        cs.caught_factor = kInf;
        for (const std::string& id : goals) {
            const auto g = std::find_if(spec.goals.begin(), spec.goals.end(),
                                        [&](const GoalSpec& s) { return s.id == id; });
            if (g == spec.goals.end()) continue;
            cs.goals.push_back(scoreGoal(*g, candidates[i].id, cases));
            cs.problems += cs.goals.back().problems;
            cs.score = std::min(cs.score, cs.goals.back().score);
            cs.caught_factor = std::min(cs.caught_factor, cs.goals.back().caught_factor);
        }
        out.push_back(std::move(cs));
    }
    std::stable_sort(out.begin(), out.end(), [](const CandidateScore& a, const CandidateScore& b) {
        if (a.problems != b.problems) return a.problems < b.problems;
        if (a.score != b.score) return a.score > b.score;
        return a.caught_factor > b.caught_factor;
    });
    return out;
}

void printRanking(const std::vector<Candidate>& candidates, const std::vector<Variation>& vary,
                  const std::vector<CandidateScore>& ranked) {
    constexpr std::size_t kMaxCell = 30;
    std::vector<std::size_t> widths;
    for (const Variation& v : vary) {
        std::size_t w = v.path.size();
        for (const Candidate& c : candidates) w = std::max(w, getPath(c.scene, v.path).dump().size());
        widths.push_back(std::min(w, kMaxCell));
    }
    bool labels = false;
    std::size_t label_width = 9;
    for (const Candidate& c : candidates) {
        labels = labels || (!c.label.empty() && !c.base);
        label_width = std::max(label_width, std::min(c.label.size(), kMaxCell));
    }
    std::size_t goal_width = 4;
    for (const CandidateScore& cs : ranked)
        for (const GoalScore& g : cs.goals) goal_width = std::max(goal_width, g.goal.size());
    const std::size_t id_width = candidates.empty() ? 3 : candidates.front().id.size() + 1;

    std::string head = "  rank  " + cell("cand", id_width) + std::string(id_width + 2 - 4, ' ');
    for (std::size_t v = 0; v < vary.size(); ++v) {
        const std::string p = cell(vary[v].path, widths[v]);
        head += p + std::string(widths[v] + 2 - p.size(), ' ');
    }
    if (labels) head += "candidate" + std::string(label_width + 2 - 9, ' ');
    const std::size_t notes_indent = head.size();
    std::printf("%s%-*s  %-9s  %-8s  %-12s  %s\n", head.c_str(), static_cast<int>(goal_width), "goal",
                "separates", "mistakes", "alternatives", "score");
    for (std::size_t r = 0; r < ranked.size(); ++r) {
        const CandidateScore& cs = ranked[r];
        const Candidate& c = candidates[cs.candidate];
        std::string row = "  " + std::to_string(r + 1);
        row += std::string(8 - std::min<std::size_t>(row.size(), 7), ' ');
        row += c.id + (c.base ? "*" : "") + std::string(id_width + 2 - c.id.size() - (c.base ? 1 : 0), ' ');
        for (std::size_t v = 0; v < vary.size(); ++v) {
            const ojson value = getPath(c.scene, vary[v].path);
            const std::string text = cell(value.is_null() ? "-" : value.dump(), widths[v]);
            row += text + std::string(widths[v] + 2 - text.size(), ' ');
        }
        if (labels) {
            const std::string text = cell(c.label, label_width);
            row += text + std::string(label_width + 2 - text.size(), ' ');
        }
        for (std::size_t gi = 0; gi < cs.goals.size(); ++gi) {
            const GoalScore& g = cs.goals[gi];
            std::printf("%s%-*s  %-9s  %-8s  %-12s  %s\n",
                        gi == 0 ? row.c_str() : std::string(notes_indent, ' ').c_str(),
                        static_cast<int>(goal_width), g.goal.c_str(), g.separates ? "yes" : "no",
                        factorCell(g.mistake_factor).c_str(), factorCell(g.alternative_factor).c_str(),
                        factorCell(g.score).c_str());
            const std::string pad(notes_indent + 2, ' ');
            const std::vector<std::string> missed = namesWhere(g.mistakes, false, Shown::Factor),
                                           failed = namesWhere(g.alternatives, false, Shown::Factor),
                                           also = namesWhere(g.others, false, Shown::Goal);
            if (!missed.empty()) std::printf("%smisses: %s\n", pad.c_str(), joined(missed).c_str());
            if (!failed.empty())
                std::printf("%sfails alternative: %s\n", pad.c_str(), joined(failed).c_str());
            if (!also.empty()) std::printf("%salso fails: %s\n", pad.c_str(), joined(also).c_str());
        }
    }
}

ojson pasteableScene(const Candidate& c, const std::string& base_name) {
    ojson scene = c.scene;
    scene["name"] = base_name.substr(0, 64 - c.id.size() - 1) + "_" + c.id;
    return scene;
}

ojson rankingJson(const std::vector<Candidate>& candidates, const std::vector<Variation>& vary,
                  const std::vector<CandidateScore>& ranked, const std::string& base_name) {
    ojson out = ojson::array();
    for (std::size_t r = 0; r < ranked.size(); ++r) {
        const CandidateScore& cs = ranked[r];
        const Candidate& c = candidates[cs.candidate];
        ojson values = ojson::object();
        for (const Variation& v : vary) values[v.path] = getPath(c.scene, v.path);
        ojson goals = ojson::array();
        for (const GoalScore& g : cs.goals) {
            ojson also = ojson::array();
            for (const CaseOnGoal& o : g.others)
                if (!o.as_wanted) also.push_back({{"case", o.name}, {"goal", o.goal}});
            goals.push_back({{"goal", g.goal},
                             {"separates", g.separates},
                             {"isolates", g.isolates},
                             {"score", finite(g.score)},
                             {"mistake_factor", finite(g.mistake_factor)},
                             {"alternative_factor", finite(g.alternative_factor)},
                             {"isolation_factor", finite(g.isolation_factor)},
                             {"caught_factor", finite(g.caught_factor)},
                             {"missed", namesWhere(g.mistakes, false, Shown::Name)},
                             {"failed_alternatives", namesWhere(g.alternatives, false, Shown::Name)},
                             {"also_fails", also},
                             {"mistakes", casesJson(g.mistakes, "fails", false)},
                             {"alternatives", casesJson(g.alternatives, "passes", false)},
                             {"other_mistakes", casesJson(g.others, "passes", true)}});
        }
        out.push_back({{"rank", r + 1},
                       {"id", c.id},
                       {"base", c.base},
                       {"label", c.label},
                       {"values", values},
                       {"problems", cs.problems},
                       {"score", finite(cs.score)},
                       {"goals", goals},
                       {"scene", pasteableScene(c, base_name)}});
    }
    return out;
}

}  // namespace shaderlab::authoring::sweep
