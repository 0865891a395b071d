// class.json: the counts of the class page as data; see class_report.h and docs/instructors.md.
#include <cmath>
#include <nlohmann/json.hpp>

#include "shaderlab/classview/class_report.h"

namespace shaderlab::classview {

namespace {

using json = nlohmann::ordered_json;

constexpr int kClassVersion = 1;

json number(double v) { return std::isfinite(v) ? json(std::round(v * 1e4) / 1e4) : json(nullptr); }

json statuses(const std::vector<StatusCount>& counts) {
    json j = json::object();
    for (const StatusCount& s : counts) j[s.status] = s.count;
    return j;
}

json histogram(const Histogram& h) {
    json bins = json::array();
    for (const Histogram::Bin& b : h.bins)
        bins.push_back({{"from", number(b.from)}, {"to", number(b.to)}, {"students", b.count}});
    return {{"whole_points", h.whole_points}, {"bins", bins}};
}

json goal(const GoalShare& g) {
    json mistakes = json::array();
    for (const MistakeCount& m : g.mistakes)
        mistakes.push_back({{"mistake", m.mistake}, {"students", m.students}});
    return {{"id", g.id},
            {"title", g.title},
            {"points", number(g.points)},
            {"met", g.met},
            {"of", g.of},
            {"share", number(g.share())},
            {"own_failed", g.own_failed},
            {"own_failed_whole", g.own_failed_whole},
            {"failed_because", g.failed_because},
            {"mistakes", mistakes},
            {"not_rendered", g.not_rendered},
            {"unexplained", g.unexplained}};
}

json mistake(const MistakeTally& t) {
    return {{"mistake", t.mistake},
            {"about", t.about},
            {"students", t.students},
            {"goals", t.goals},
            {"scene", t.scene},
            {"image", t.image},
            {"expected_picture", t.expected_picture},
            {"mistake_picture", t.mistake_picture},
            {"mistake_picture_is_students", t.mistake_picture_is_students}};
}

json lab(const LabClass& l) {
    json goals = json::array(), mistakes = json::array();
    for (const GoalShare& g : l.goals) goals.push_back(goal(g));
    for (const MistakeTally& t : l.mistakes) mistakes.push_back(mistake(t));
    return {{"id", l.id},
            {"title", l.title},
            {"max_score", number(l.max_score)},
            {"students", l.students},
            {"handed_in", l.handed_in},
            {"not_attempted", l.not_attempted},
            {"statuses", statuses(l.statuses)},
            {"goals", goals},
            {"mistakes", mistakes},
            {"points", histogram(l.points)},
            {"mean", number(l.mean)},
            {"median", number(l.median)}};
}

json need(const StudentNeed& n) {
    return {{"student", n.student},
            {"status", n.status},
            {"message", n.message},
            {"goals_met", n.goals_met},
            {"goals_total", n.goals_total},
            {"timeouts", n.timeouts},
            {"not_compiled", n.not_compiled},
            {"crashed", n.crashed},
            {"not_handed_in", n.not_handed_in},
            {"not_attempted", n.not_attempted},
            {"weak_labs", n.weak_labs},
            {"total", number(n.total)},
            {"max_total", number(n.max_total)},
            {"report", n.report_html},
            {"reasons", n.reasons}};
}

json reteach(const ReteachItem& r) {
    return {{"lab", r.lab},
            {"goal", r.goal},
            {"title", r.goal_title},
            {"met", r.met},
            {"of", r.of},
            {"share", number(r.of > 0 ? double(r.met) / r.of : 0.0)},
            {"own_failed", r.own_failed},
            {"mistake", r.mistake},
            {"about", r.about},
            {"mistake_students", r.mistake_students},
            {"also_goals", r.also_goals},
            {"picture", r.picture}};
}

}  // namespace

std::string classToJson(const ClassReport& r) {
    json labs = json::array(), needs = json::array(), first = json::array();
    for (const LabClass& l : r.labs) labs.push_back(lab(l));
    for (const StudentNeed& n : r.needs_help) needs.push_back(need(n));
    for (const ReteachItem& t : r.reteach) first.push_back(reteach(t));
    const json doc = {{"class_version", kClassVersion},
                      {"tool", "shaderlab"},
                      {"tool_version", r.tool_version},
                      {"results", r.results_dir},
                      {"submissions", r.submissions},
                      {"statuses", statuses(r.submission_statuses)},
                      {"max_total", number(r.max_total)},
                      {"totals", histogram(r.totals)},
                      {"reteach_first", first},
                      {"labs", labs},
                      {"needs_help", needs},
                      {"errors", r.errors}};
    return doc.dump(2, ' ', false, json::error_handler_t::replace) + "\n";
}

}  // namespace shaderlab::classview
