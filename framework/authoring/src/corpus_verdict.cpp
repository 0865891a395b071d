// What a corpus case's grade must be; see corpus_verdict.h.
#include "shaderlab/authoring/corpus_verdict.h"

#include <algorithm>
#include <set>

namespace shaderlab::authoring {

namespace {

// Goal isolation (docs/grading.md): the goals a mistake fails that have work of their own are
// judged on that work alone, unless the case lists them in "whole" (its work is not where the lab
// asks), which must then be judged on the whole shaders and say why.
void checkJudgements(const LabSpec& spec, const Case& c, const grader::ReportLab& l, std::string* why) {
    auto add = [&](const std::string& reason) { *why += (why->empty() ? "" : "; ") + reason; };
    for (std::size_t i = 0; i < l.goals.size() && i < spec.goals.size(); ++i) {
        const grader::ReportGoal& g = l.goals[i];
        const bool listed = std::find(c.whole.begin(), c.whole.end(), g.id) != c.whole.end();
        if (listed && (g.judged != "whole" || g.judged_note.empty()))
            add("goal " + g.id + " must be judged on the whole shaders, saying why (it was judged " +
                (g.judged.empty() ? std::string("without isolation") : g.judged) + ")");
        const bool failed_with_work = !g.met && !spec.goals[i].work.empty();
        if (!listed && failed_with_work && g.judged != "alone")
            add("goal " + g.id + " must be judged on the student's own work for it (judged " + g.judged +
                (g.judged_note.empty() ? "" : ": " + g.judged_note) + ")");
        // Starter-given code the case changes goes with each goal it fails judged alone; a goal it
        // fails without such code is judged without it.
        if (g.met || listed) continue;
        const std::vector<std::string>& with = c.given;
        if (std::set<std::string>(g.judged_with.begin(), g.judged_with.end()) !=
            std::set<std::string>(with.begin(), with.end())) {
            std::string said;
            for (const std::string& w : g.judged_with) said += (said.empty() ? "" : ", ") + w;
            add("goal " + g.id + " was judged with " + (said.empty() ? "no given code" : said) +
                (with.empty()
                     ? "; the case changes none it uses"
                     : "; the case changes " + c.given.front() + (c.given.size() > 1 ? ", ..." : "")));
        }
    }
}

}  // namespace

std::string expectationsMissed(const LabSpec& spec, const Case& c, const grader::ReportLab& l) {
    std::string why;
    auto goalMet = [&](const std::string& id) {
        for (const grader::ReportGoal& g : l.goals)
            if (g.id == id) return g.met;
        return false;
    };
    const bool full = l.score >= l.max_score - 1e-9;
    if (c.kind == "alternative" || c.kind == "reference") {
        if (l.status != "passed" || !full) why = "must pass with full marks";
    } else if (c.kind == "starter") {
        if (l.status != "failed") why = "must render and fail (compile, run, but not pass)";
    } else if (l.status != c.status) {
        why = "must end as " + c.status;
    } else if (c.kind == "mistake") {
        // A mistake costs the goal whose idea it breaks and the goals declared to rest on it,
        // nothing else (issue 24: the grade names the one idea missed).
        if (full) why = "must lose points";
        const std::set<std::string> expected = expectedFailures(spec, c.fails);
        for (const std::string& g : c.fails)
            if (goalMet(g)) why += (why.empty() ? "" : "; ") + std::string("goal ") + g + " must not be met";
        for (const grader::ReportGoal& g : l.goals)
            if (!g.met && !expected.count(g.id))
                why += (why.empty() ? "" : "; ") + std::string("goal ") + g.id +
                       " must stay met (only the goals in \"fails\" and those resting on them may fail)";
        checkJudgements(spec, c, l, &why);
    }
    if (why.empty() && c.diagnostic) {
        bool found = false;
        for (const grader::ReportDiagnostic& d : l.diagnostics)
            found = found || (d.file == c.diagnostic->first && d.line == c.diagnostic->second);
        if (!found) why = "must report " + c.diagnostic->first + ":" + std::to_string(c.diagnostic->second);
    }
    return why;
}

}  // namespace shaderlab::authoring
