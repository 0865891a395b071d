// Step 4 of the lab.json parser, between passes: unique names, repeat groups (from "repeat" and
// "from", which may neither overlap nor nest), the targets and attachments inputs read, reads that
// come before any draw (a cycle, unless inside a repeat group), "@<pass>" references in uniform
// values, and a bound on the passes one scene runs.
#include <set>
#include <string>
#include <vector>

#include "lab_spec_steps.h"

namespace shaderlab::lab_spec_detail {

namespace {

// Bounds on the work one scene may ask for: passes times repeats (cube targets count six).
constexpr long kMaxPassRunsPerScene = 20000;
constexpr long kMaxPassRunsPerLab = 200000;

}  // namespace

int Validator::passIndex(const std::string& name) const {
    for (std::size_t i = 0; i < spec_.passes.size(); ++i)
        if (spec_.passes[i].name == name) return static_cast<int>(i);
    return -1;
}

void Validator::buildLoops() {
    std::set<std::string> names;
    for (const PassSpec& p : spec_.passes) {
        if (p.name.empty()) continue;
        if (!names.insert(p.name).second)
            diag_.error(joinKey(p.path, "name"), "pass " + quoteJson(p.name) + " is listed twice");
    }
    for (std::size_t i = 0; i < spec_.passes.size(); ++i) {
        const PassDraft& d = drafts_[i];
        if (!d.repeat_count) continue;
        LoopSpec loop;
        loop.last = i;
        loop.first = i;
        loop.count = *d.repeat_count;
        loop.declared_by = spec_.passes[i].name;
        if (!d.repeat_from.empty()) {
            const int j = passIndex(d.repeat_from);
            if (j < 0 || static_cast<std::size_t>(j) > i) {
                std::vector<std::string> earlier;
                for (std::size_t k = 0; k <= i; ++k) earlier.push_back(spec_.passes[k].name);
                diag_.error(joinKey(joinKey(spec_.passes[i].path, "repeat"), "from"),
                            j < 0 ? "no pass is called " + quoteJson(d.repeat_from) +
                                        didYouMean(d.repeat_from, earlier)
                                  : quoteJson(d.repeat_from) +
                                        " comes after this pass; \"from\" names the first pass of the group, "
                                        "which ends at this pass");
            } else {
                loop.first = static_cast<std::size_t>(j);
            }
            // A bad "from" still leaves a repeated pass (alone), so its reads are judged as such.
        }
        bool overlap = false;
        for (std::size_t k = loop.first; k <= loop.last; ++k) {
            if (spec_.passes[k].loop >= 0) {
                diag_.error(
                    joinKey(spec_.passes[i].path, "repeat"),
                    "overlaps the repeat group of pass " +
                        quoteJson(spec_.loops[static_cast<std::size_t>(spec_.passes[k].loop)].declared_by) +
                        "; repeat groups cannot overlap or nest");
                overlap = true;
                break;
            }
        }
        if (overlap) continue;
        for (std::size_t k = loop.first; k <= loop.last; ++k)
            spec_.passes[k].loop = static_cast<int>(spec_.loops.size());
        spec_.loops.push_back(loop);
    }
}

void Validator::checkInputs() {
    for (std::size_t i = 0; i < spec_.passes.size(); ++i) {
        PassSpec& p = spec_.passes[i];
        std::set<std::string> uniform_names;
        for (const UniformSetting& u : p.uniforms) uniform_names.insert(u.name);
        for (const PassInput& in : p.inputs) {
            if (uniform_names.count(in.sampler))
                diag_.error(in.path,
                            quoteJson(in.sampler) +
                                " is both a sampler input and a uniform value of this pass; a sampler "
                                "gets a texture, not a value");
            if (in.source != InputSource::Target) continue;
            const TargetSpec* t = spec_.findTarget(in.target);
            if (!t) {
                std::vector<std::string> names;
                for (const TargetSpec& x : spec_.targets) names.push_back(x.name);
                diag_.error(in.path,
                            "no target is called " + quoteJson(in.target) + didYouMean(in.target, names));
                continue;
            }
            if (in.attachment == "depth") {
                if (in.target == p.target) {
                    diag_.error(in.path,
                                "reads the depth of the target this pass draws into; depth is not "
                                "ping-ponged, so draw the depth in an earlier pass");
                    continue;
                }
                if (t->depth != DepthMode::Texture)
                    diag_.error(in.path,
                                "reads the depth of target " + quoteJson(t->name) +
                                    ", which cannot be sampled: give the target \"depth\": \"texture\"");
            } else if (!in.attachment.empty() && std::find(t->attachments.begin(), t->attachments.end(),
                                                           in.attachment) == t->attachments.end()) {
                diag_.error(in.path, "target " + quoteJson(t->name) + " has no attachment " +
                                         quoteJson(in.attachment) +
                                         didYouMean(in.attachment, t->attachments));
            }
            checkReadOrder(i, in);
        }
    }
}

// "@<pass>.view_projection" and the like, anywhere in a uniform value of a pass or a scene:
// the pass must exist.
void Validator::checkPassReferences() {
    std::vector<std::string> names;
    for (const PassSpec& p : spec_.passes) names.push_back(p.name);
    const auto check = [&](const auto& self, const json& v, const std::string& path) -> void {
        if (v.is_string()) {
            const std::string s = v;
            const std::size_t dot = s.rfind('.');
            if (s.empty() || s[0] != '@' || dot == std::string::npos) return;
            const std::string pass = s.substr(1, dot - 1);
            if (passIndex(pass) < 0)
                diag_.error(path, "no pass is called " + quoteJson(pass) + didYouMean(pass, names));
        } else if (v.is_array()) {
            for (std::size_t k = 0; k < v.size(); ++k) self(self, v[k], joinIndex(path, k));
        } else if (v.is_object()) {
            for (const auto& item : v.items()) self(self, item.value(), joinKey(path, item.key()));
        }
    };
    for (const PassSpec& p : spec_.passes)
        for (const UniformSetting& u : p.uniforms) check(check, u.value, u.path);
    for (const SceneSpec& s : spec_.scenes)
        for (const UniformSetting& u : s.uniforms) check(check, u.value, u.path);
}

// A pass reads what earlier passes wrote. Inside a repeat group a pass may also read what
// the group writes later (or itself): the previous iteration's result, feedback.
void Validator::checkReadOrder(std::size_t i, const PassInput& in) {
    const PassSpec& p = spec_.passes[i];
    std::vector<std::size_t> writers;
    for (std::size_t j = 0; j < spec_.passes.size(); ++j)
        if (spec_.passes[j].target == in.target) writers.push_back(j);
    if (writers.empty()) {
        diag_.error(in.path, "reads target " + quoteJson(in.target) + ", which no pass draws into");
        return;
    }
    if (writers.front() < i) return;
    if (p.loop >= 0) {
        const LoopSpec& l = spec_.loops[static_cast<std::size_t>(p.loop)];
        for (std::size_t j : writers)
            if (j >= l.first && j <= l.last) return;
    }
    const std::size_t j = writers.front();
    if (j == i)
        diag_.error(in.path, "reads target " + quoteJson(in.target) +
                                 ", which this pass draws into and no earlier pass drew: there is nothing "
                                 "to read yet, unless the pass is repeated (it then reads the previous "
                                 "iteration's result)");
    else
        diag_.error(in.path, "reads target " + quoteJson(in.target) + ", which is first drawn by " +
                                 passPath(j) + " (" + quoteJson(spec_.passes[j].name) +
                                 ") after this pass: a cycle. A pass reads what earlier passes drew, unless "
                                 "both are in one repeat group");
}

void Validator::checkWork() {
    long total = 0;
    for (const SceneSpec& s : spec_.scenes) {
        long runs = 0;
        for (std::size_t i = 0; i < spec_.passes.size(); ++i) {
            const PassSpec& p = spec_.passes[i];
            long n = 1;
            if (p.loop >= 0) {
                const LoopSpec& l = spec_.loops[static_cast<std::size_t>(p.loop)];
                const auto it = s.repeats.find(l.declared_by);
                n = it != s.repeats.end() ? it->second : l.count;
            }
            const TargetSpec* t = spec_.findTarget(p.target);
            if (t && t->type == TargetType::Cube) n *= 6;
            runs += n;
        }
        if (runs > kMaxPassRunsPerScene)
            diag_.error(s.path, "runs passes " + std::to_string(runs) + " times for one scene; at most " +
                                    std::to_string(kMaxPassRunsPerScene) + " are allowed (lower \"repeat\")");
        total += runs;
    }
    if (total <= kMaxPassRunsPerLab) return;
    diag_.error("scenes", "together run passes " + std::to_string(total) + " times; at most " +
                              std::to_string(kMaxPassRunsPerLab) + " are allowed");
}

}  // namespace shaderlab::lab_spec_detail
