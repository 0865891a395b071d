// Step 4 of the lab.json parser, for grading: which passes are graded and which of their
// attachments, how they are compared, and the goals: one per scene when lab.json gives none,
// otherwise their references to scenes and graded passes, their points, and that every graded
// image counts toward some goal.
#include <algorithm>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "lab_spec_steps.h"

namespace shaderlab::lab_spec_detail {

void Validator::checkGraded() {
    for (std::size_t i = 0; i < spec_.passes.size(); ++i) {
        PassSpec& p = spec_.passes[i];
        const PassDraft& d = drafts_[i];
        const bool last = i + 1 == spec_.passes.size();
        // Whether a pass is graded does not depend on its target (only which images are).
        if (last || !d.graded_list.empty() || d.graded_flag.value_or(false)) graded_.push_back(p.name);
        if (last && d.graded_flag && !*d.graded_flag)
            diag_.error(joinKey(p.path, "graded"),
                        "the last pass is the lab's result and is always graded; leave \"graded\" out");
        const TargetSpec* t = spec_.findTarget(p.target);
        if (!t) continue;
        if (!d.graded_list.empty()) {
            for (const std::string& a : d.graded_list) {
                if (a == "depth") {
                    if (t->depth == DepthMode::None)
                        diag_.error(joinKey(p.path, "graded"),
                                    "target " + quoteJson(t->name) + " has no depth to grade");
                } else if (std::find(t->attachments.begin(), t->attachments.end(), a) ==
                           t->attachments.end()) {
                    diag_.error(joinKey(p.path, "graded"), "target " + quoteJson(t->name) +
                                                               " has no attachment " + quoteJson(a) +
                                                               didYouMean(a, t->attachments));
                }
            }
            p.graded = d.graded_list;
        } else if (last || d.graded_flag.value_or(false)) {  // "false" on the last pass is an error
            p.graded = t->attachments;
        }
        if (t->type == TargetType::Cube && !p.graded.empty() &&
            std::find(p.graded.begin(), p.graded.end(), "depth") != p.graded.end())
            diag_.error(joinKey(p.path, "graded"), "a cube target's depth cannot be graded");
        p.compare = d.compare.value_or(
            !p.graded.empty() && isFloatFormat(t->format) && !last ? CompareMode::Hdr : CompareMode::Display);
    }
    for (std::size_t i = 0; i < spec_.passes.size(); ++i) checkIsolation(i);
}

// A pass run on the reference's inputs must be graded, outside a repeat group, and read at least
// one image that a graded pass before it drew (else there is nothing to stand in for).
void Validator::checkIsolation(std::size_t index) {
    const PassSpec& p = spec_.passes[index];
    if (!p.isolate) return;
    const std::string key = joinKey(p.path, "isolate");
    if (p.graded.empty()) {
        diag_.error(key, "only a graded pass is judged on the reference's inputs; this one is not graded");
    } else if (p.loop >= 0) {
        diag_.error(key, "a pass in a repeat group reads its own previous run; it cannot be isolated");
    } else if (std::none_of(p.inputs.begin(), p.inputs.end(), [&](const PassInput& in) {
                   return standInSource(spec_, index, in).pass != nullptr;
               })) {
        diag_.error(key,
                    "the pass reads no image that a graded pass before it drew, so there is nothing "
                    "of the reference's to give it; leave \"isolate\" out");
    }
}

// A lab without goals: one goal per scene, sharing the lab's points.
void Validator::addImplicitGoals() {
    const std::vector<std::string>& graded = graded_;
    const float share =
        spec_.grading.points / static_cast<float>(std::max<std::size_t>(1, spec_.scenes.size()));
    for (const SceneSpec& s : spec_.scenes) {
        GoalSpec g;
        g.id = s.name;
        g.title = "scene " + s.name;
        g.points = share;
        g.scenes = {s.name};
        g.passes = graded;
        g.implicit = true;
        spec_.goals.push_back(std::move(g));
    }
}

void Validator::checkGoals() {
    const std::vector<std::string>& graded = graded_;
    if (spec_.goals.empty()) {
        addImplicitGoals();
        return;
    }
    std::set<std::string> ids, covered;
    float total = 0.0f;
    bool references_ok = true;  // else which images the goals check is unknown: no more messages
    for (std::size_t i = 0; i < spec_.goals.size(); ++i) {
        GoalSpec& g = spec_.goals[i];
        const std::string path = joinIndex("goals", i);
        total += g.points;
        if (!ids.insert(g.id).second)
            diag_.error(joinKey(path, "id"), "goal " + quoteJson(g.id) + " is listed twice");
        std::vector<std::string> scenes;
        if (g.scenes.empty()) {
            for (const SceneSpec& s : spec_.scenes) scenes.push_back(s.name);
        } else {
            for (std::size_t k = 0; k < g.scenes.size(); ++k) {
                const std::string& name = g.scenes[k];
                bool found = false;
                for (const SceneSpec& s : spec_.scenes) {
                    if (s.name == name || s.base_name == name) {
                        scenes.push_back(s.name);
                        found = true;
                    }
                }
                if (!found) {
                    std::vector<std::string> names;
                    for (const SceneSpec& s : spec_.scenes) names.push_back(s.base_name);
                    diag_.error(joinIndex(joinKey(path, "scenes"), k),
                                "no scene is called " + quoteJson(name) + didYouMean(name, names));
                    references_ok = false;
                }
            }
        }
        g.scenes = scenes;
        if (g.passes.empty()) {
            g.passes = graded;
        } else {
            for (std::size_t k = 0; k < g.passes.size(); ++k) {
                const std::string& name = g.passes[k];
                if (std::find(graded.begin(), graded.end(), name) == graded.end()) {
                    std::vector<std::string> all;
                    for (const PassSpec& p : spec_.passes) all.push_back(p.name);
                    diag_.error(joinIndex(joinKey(path, "passes"), k),
                                passIndex(name) < 0
                                    ? "no pass is called " + quoteJson(name) + didYouMean(name, all)
                                    : "pass " + quoteJson(name) +
                                          " is not graded; mark it \"graded\": true to grade a goal on it");
                    references_ok = false;
                }
            }
        }
        covered.insert(g.scenes.begin(), g.scenes.end());
    }
    spec_.grading.points = total;
    checkGoalDependencies(ids);
    if (!references_ok) return;
    checkGoalCoverage(covered);
}

// depends_on names other goals of the lab, and following it never comes back to where it began.
void Validator::checkGoalDependencies(const std::set<std::string>& ids) {
    const std::vector<std::string> all(ids.begin(), ids.end());
    bool known = true;
    for (std::size_t i = 0; i < spec_.goals.size(); ++i) {
        const GoalSpec& g = spec_.goals[i];
        for (std::size_t k = 0; k < g.depends_on.size(); ++k) {
            const std::string& dep = g.depends_on[k];
            const std::string path = joinIndex(joinKey(joinIndex("goals", i), "depends_on"), k);
            if (dep == g.id) {
                diag_.error(path, "a goal cannot depend on itself");
                known = false;
            } else if (!ids.count(dep)) {
                diag_.error(path, "no goal is called " + quoteJson(dep) + didYouMean(dep, all));
                known = false;
            }
        }
    }
    if (!known) return;
    // Depth-first from each goal; a goal met again on the current path closes a cycle.
    std::map<std::string, const GoalSpec*> by_id;
    for (const GoalSpec& g : spec_.goals) by_id[g.id] = &g;
    std::map<std::string, int> state;  // 1: on the path, 2: done
    std::vector<std::string> path;
    std::function<bool(const GoalSpec&)> visit = [&](const GoalSpec& g) {
        state[g.id] = 1;
        path.push_back(g.id);
        for (const std::string& dep : g.depends_on) {
            if (state[dep] == 1) {
                std::string cycle;
                for (auto it = std::find(path.begin(), path.end(), dep); it != path.end(); ++it)
                    cycle += *it + " -> ";
                diag_.error("goals", "the goals depend on each other in a circle: " + cycle + dep);
                return false;
            }
            if (state[dep] == 0 && !visit(*by_id[dep])) return false;
        }
        state[g.id] = 2;
        path.pop_back();
        return true;
    };
    for (const GoalSpec& g : spec_.goals)
        if (state[g.id] == 0 && !visit(g)) return;
}

// Every graded image counts toward some goal: otherwise a lab could fail with full marks.
// `covered` holds the scenes some goal names; run only once every goal's references resolved.
void Validator::checkGoalCoverage(const std::set<std::string>& covered) {
    const std::vector<std::string>& graded = graded_;
    for (const std::string& pass : graded) {
        std::vector<std::string> unchecked;
        for (const SceneSpec& s : spec_.scenes) {
            const bool checked = std::any_of(spec_.goals.begin(), spec_.goals.end(), [&](const GoalSpec& g) {
                return std::find(g.scenes.begin(), g.scenes.end(), s.name) != g.scenes.end() &&
                       std::find(g.passes.begin(), g.passes.end(), pass) != g.passes.end();
            });
            if (!checked && covered.count(s.name)) unchecked.push_back(s.name);
        }
        if (!unchecked.empty()) {
            std::string list;
            for (const std::string& n : unchecked) list += (list.empty() ? "" : ", ") + quoteJson(n);
            diag_.error(spec_.findPass(pass)->path + ".graded",
                        "pass " + quoteJson(pass) + " is graded, but no goal checks it in scene " + list +
                            "; add it to a goal's \"passes\" or stop grading it");
        }
    }
    std::set<std::string> reported;
    for (const SceneSpec& s : spec_.scenes) {
        const std::string base = s.path.substr(0, s.path.find(".times"));
        if (!covered.count(s.name) && reported.insert(base).second)
            diag_.error(base, "scene " + quoteJson(s.base_name) +
                                  " is in no goal's \"scenes\": every graded scene must test some goal");
    }
}

}  // namespace shaderlab::lab_spec_detail
