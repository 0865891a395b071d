// Counting a class: goals met, known mistakes, statuses, points, who needs help, what to re-teach.
// See class_report.h. Pure: reads a ClassInput, touches no file.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <tuple>

#include "shaderlab/classview/class_report.h"

namespace shaderlab::classview {

namespace {

const std::vector<std::string> kLabStatuses = {"passed",  "failed",  "compile_error", "link_error",
                                               "timeout", "crashed", "missing",       "not_attempted"};
const std::vector<std::string> kSubmissionStatuses = {"graded", "empty", "bad_archive", "unsafe_archive",
                                                      "too_large"};

// The counts in the order of `known`, then any other status by name; zeros left out.
std::vector<StatusCount> orderedCounts(const std::map<std::string, int>& counts,
                                       const std::vector<std::string>& known) {
    std::vector<StatusCount> out;
    for (const std::string& s : known) {
        const auto it = counts.find(s);
        if (it != counts.end() && it->second > 0) out.push_back({s, it->second});
    }
    for (const auto& [s, n] : counts)
        if (n > 0 && std::find(known.begin(), known.end(), s) == known.end()) out.push_back({s, n});
    return out;
}

const grader::ReportLab* reportLab(const StudentResults& s, const std::string& id) {
    if (!s.has_report) return nullptr;
    for (const grader::ReportLab& l : s.report.labs)
        if (l.id == id) return &l;
    return nullptr;
}

const batch::SummaryLab* rowLab(const StudentResults& s, const std::string& id) {
    for (const batch::SummaryLab& l : s.row.labs)
        if (l.id == id) return &l;
    return nullptr;
}

// The lab's status as summary.csv says it (the report's when the row has none); "missing" when
// neither names the lab.
std::string labStatus(const StudentResults& s, const std::string& id) {
    const batch::SummaryLab* r = rowLab(s, id);
    if (r && !r->status.empty()) return r->status;
    const grader::ReportLab* l = reportLab(s, id);
    return l && !l->status.empty() ? l->status : "missing";
}

double labScore(const StudentResults& s, const std::string& id) {
    if (const batch::SummaryLab* r = rowLab(s, id)) return r->score;
    const grader::ReportLab* l = reportLab(s, id);
    return l ? l->score : 0.0;
}

bool rendered(const std::string& status) { return status == "passed" || status == "failed"; }

// Handed in: graded from the student's own files (not absent, not the starter untouched).
bool handedIn(const std::string& status) { return status != "missing" && status != "not_attempted"; }

// The scenes a goal is seen in, by the student's report (older reports name only failing checks;
// a goal judged alone names its whole shaders' failures apart).
std::set<std::string> goalScenes(const grader::ReportGoal& g) {
    std::set<std::string> scenes(g.scenes.begin(), g.scenes.end());
    for (const auto* list : {&g.failing, &g.whole_failing})
        for (const std::string& f : *list) scenes.insert(f.substr(0, f.find('/')));
    return scenes;
}

// Where the pictures of a recognised mistake come from in one report: the graded image the hint
// names, else the scene's final image.
void pictureSources(const StudentResults& s, const grader::ReportScene& scene, MistakeTally* t) {
    std::string reference = scene.reference_image, student = scene.student_image;
    for (const grader::ReportPass& p : scene.passes)
        if (p.name == scene.hint.image) reference = p.reference_image, student = p.student_image;
    if (t->reference_source.empty() && !reference.empty())
        t->reference_source = s.report_dir + "/" + reference;
    if (t->student_source.empty() && !student.empty()) t->student_source = s.report_dir + "/" + student;
}

// Everything of one lab that is counted per student, kept while the class is read.
struct LabCounting {
    LabClass lab;
    std::map<std::string, std::size_t> goal_index;
    std::map<std::string, std::size_t> mistake_index;
    std::vector<std::map<std::string, int>> goal_mistakes;   // per goal: mistake -> students
    std::vector<std::map<std::string, int>> mistake_places;  // per mistake: "scene\nimage" -> students
    std::vector<std::set<std::string>> mistake_goals;        // per mistake: goal ids
    std::vector<double> scores;
};

// The class's goals of the lab: every goal any report lists, in the order first seen.
void collectGoals(const ClassInput& in, LabCounting* c) {
    for (const StudentResults& s : in.students) {
        const grader::ReportLab* l = reportLab(s, c->lab.id);
        if (!l) continue;
        if (c->lab.title.empty()) c->lab.title = l->title;
        c->lab.max_score = std::max(c->lab.max_score, l->max_score);
        for (const grader::ReportGoal& g : l->goals) {
            if (c->goal_index.count(g.id)) continue;
            c->goal_index[g.id] = c->lab.goals.size();
            GoalShare share;
            share.id = g.id;
            share.title = g.title;
            share.points = g.points;
            c->lab.goals.push_back(share);
        }
    }
    c->goal_mistakes.resize(c->lab.goals.size());
}

// The known mistakes recognised in one student's lab, each once, with its pictures' sources.
std::map<std::string, const grader::ReportScene*> countMistakes(const StudentResults& s,
                                                                const grader::ReportLab& l, LabCounting* c) {
    std::map<std::string, const grader::ReportScene*> seen;
    for (const grader::ReportScene& scene : l.scenes)
        if (!scene.hint.mistake.empty() && !seen.count(scene.hint.mistake)) seen[scene.hint.mistake] = &scene;
    for (const auto& [mistake, scene] : seen) {
        auto [it, fresh] = c->mistake_index.emplace(mistake, c->lab.mistakes.size());
        if (fresh) {
            MistakeTally t;
            t.mistake = mistake;
            t.about = scene->hint.about;
            c->lab.mistakes.push_back(t);
            c->mistake_places.emplace_back();
            c->mistake_goals.emplace_back();
        }
        MistakeTally& t = c->lab.mistakes[it->second];
        ++t.students;
        for (const grader::ReportScene& sc : l.scenes)
            if (sc.hint.mistake == mistake) ++c->mistake_places[it->second][sc.name + "\n" + sc.hint.image];
        pictureSources(s, *scene, &t);
    }
    return seen;
}

// One student's goals of the lab: met, or what is behind them when not. A goal not met because of
// another (not_met_because set: lab.json depends_on) is that goal's failure, not its own: its known
// mistakes are counted under the goal the student's own work failed.
void countGoals(const grader::ReportLab* l, const std::string& status, LabCounting* c) {
    std::map<std::string, const grader::ReportGoal*> own;
    if (l)
        for (const grader::ReportGoal& g : l->goals) own[g.id] = &g;
    // Per goal failed on the student's own work: the known mistakes seen on its scenes.
    std::map<std::size_t, std::set<std::string>> behind;
    std::set<std::string> behind_alone;  // those behind a goal whose work was judged alone
    for (std::size_t i = 0; i < c->lab.goals.size(); ++i) {
        GoalShare& goal = c->lab.goals[i];
        ++goal.of;
        const auto it = own.find(goal.id);
        if (it != own.end() && it->second->met) {
            ++goal.met;
            continue;
        }
        if (!rendered(status) || it == own.end()) {
            ++(rendered(status) ? goal.unexplained : goal.not_rendered);
            continue;
        }
        if (!it->second->not_met_because.empty()) {
            ++goal.failed_because;
            continue;
        }
        ++goal.own_failed;
        const bool whole = !it->second->judged_note.empty();
        if (whole) ++goal.own_failed_whole;
        const std::set<std::string> scenes = goalScenes(*it->second);
        std::set<std::string>& mistakes = behind[i];
        for (const grader::ReportScene& sc : l->scenes)
            if (!sc.hint.mistake.empty() && scenes.count(sc.name)) mistakes.insert(sc.hint.mistake);
        if (!whole) behind_alone.insert(mistakes.begin(), mistakes.end());
    }
    // A mistake is listed under the goals it breaks: where a goal judged alone shows it, not also
    // under a goal whose work could not be taken alone (whose whole shaders show every mistake).
    for (auto& [i, mistakes] : behind) {
        if (mistakes.empty()) ++c->lab.goals[i].unexplained;
        if (!own.at(c->lab.goals[i].id)->judged_note.empty())
            for (auto m = mistakes.begin(); m != mistakes.end();)
                m = behind_alone.count(*m) ? mistakes.erase(m) : std::next(m);
        for (const std::string& m : mistakes) {
            ++c->goal_mistakes[i][m];
            c->mistake_goals[c->mistake_index.at(m)].insert(c->lab.goals[i].id);
        }
    }
}

// Sorted lists and figures once every student is counted.
void finishLab(LabCounting* c) {
    LabClass& lab = c->lab;
    for (std::size_t i = 0; i < lab.goals.size(); ++i) {
        for (const auto& [m, n] : c->goal_mistakes[i]) lab.goals[i].mistakes.push_back({m, n});
        std::stable_sort(
            lab.goals[i].mistakes.begin(), lab.goals[i].mistakes.end(),
            [](const MistakeCount& a, const MistakeCount& b) { return a.students > b.students; });
    }
    for (std::size_t i = 0; i < lab.mistakes.size(); ++i) {
        MistakeTally& t = lab.mistakes[i];
        int best = 0;
        for (const auto& [place, n] : c->mistake_places[i]) {
            if (n <= best) continue;
            best = n;
            t.scene = place.substr(0, place.find('\n'));
            t.image = place.substr(place.find('\n') + 1);
        }
        for (const GoalShare& g : lab.goals)
            if (c->mistake_goals[i].count(g.id)) t.goals.push_back(g.id);
    }
    std::stable_sort(lab.mistakes.begin(), lab.mistakes.end(),
                     [](const MistakeTally& a, const MistakeTally& b) {
                         return a.students != b.students ? a.students > b.students : a.mistake < b.mistake;
                     });
    std::vector<double> s = c->scores;
    std::sort(s.begin(), s.end());
    if (!s.empty()) {
        double sum = 0.0;
        for (double v : s) sum += v;
        lab.mean = sum / s.size();
        lab.median = s.size() % 2 ? s[s.size() / 2] : (s[s.size() / 2 - 1] + s[s.size() / 2]) / 2.0;
    }
    lab.points = pointsHistogram(c->scores, lab.max_score);
}

LabClass countLab(const ClassInput& in, const std::string& id) {
    LabCounting c;
    c.lab.id = id;
    collectGoals(in, &c);
    std::map<std::string, int> statuses;
    for (const StudentResults& s : in.students) {
        ++c.lab.students;
        const std::string status = labStatus(s, id);
        ++statuses[status];
        if (const batch::SummaryLab* r = rowLab(s, id))
            c.lab.max_score = std::max(c.lab.max_score, r->max_score);
        c.lab.not_attempted += status == "not_attempted" ? 1 : 0;
        if (!handedIn(status)) continue;
        ++c.lab.handed_in;
        c.scores.push_back(labScore(s, id));
        if (!s.has_report) continue;
        const grader::ReportLab* l = reportLab(s, id);
        if (l) countMistakes(s, *l, &c);
        countGoals(l, status, &c);
    }
    c.lab.statuses = orderedCounts(statuses, kLabStatuses);
    finishLab(&c);
    return c.lab;
}

std::string joined(const std::vector<std::string>& ids) {
    std::string out;
    for (const std::string& id : ids) out += (out.empty() ? "" : ", ") + id;
    return out;
}

// "timed out in 2 labs: 01-phong, 02-toon", "did not compile: 03-cel-outline".
std::string labsPhrase(const char* what, const std::vector<std::string>& ids, bool count = false) {
    std::string head = what;
    if (count) head += " in " + std::to_string(ids.size()) + (ids.size() == 1 ? " lab" : " labs");
    return head + ": " + joined(ids);
}

int goalsMet(const grader::ReportLab& l, const LabClass& lab) {
    int met = 0;
    for (const grader::ReportGoal& g : l.goals)
        for (const GoalShare& cg : lab.goals)
            if (g.met && g.id == cg.id) ++met;
    return met;
}

// "01-phong: per_fragment, normal_matrix not met (gouraud)": a rendered lab's unmet goals and the
// known mistakes recognised in it.
std::string unmetPhrase(const grader::ReportLab& l, const LabClass& lab) {
    std::vector<std::string> goals, mistakes;
    for (const GoalShare& cg : lab.goals) {
        bool met = false;
        for (const grader::ReportGoal& g : l.goals) met = met || (g.id == cg.id && g.met);
        if (!met) goals.push_back(cg.id);
    }
    for (const grader::ReportScene& sc : l.scenes)
        if (!sc.hint.mistake.empty() &&
            std::find(mistakes.begin(), mistakes.end(), sc.hint.mistake) == mistakes.end())
            mistakes.push_back(sc.hint.mistake);
    return lab.id + ": " + joined(goals) + " not met" +
           (mistakes.empty() ? "" : " (" + joined(mistakes) + ")");
}

// "not handed in", or what the lab's message says is missing (a file of a lab handed in).
bool notHandedIn(const StudentResults& s, const std::string& id) {
    const grader::ReportLab* l = reportLab(s, id);
    return !l || l->message.empty() || l->message.rfind("not handed in", 0) == 0 ||
           l->message.find("has no folder for this lab") != std::string::npos;
}

// "01-phong: 3 of 10 points; per_fragment, phong_lobe not met (blinn-phong)".
std::string weakPhrase(const grader::ReportLab& l, const LabClass& lab, double score) {
    char points[64];
    std::snprintf(points, sizeof points, "%g of %g points", score, lab.max_score);
    return lab.id + ": " + points + "; " + unmetPhrase(l, lab).substr(lab.id.size() + 2);
}

// One student across the class's labs; false when there is nothing to help with (or no report).
bool studentNeed(const StudentResults& s, const std::vector<LabClass>& labs, double max_total,
                 StudentNeed* out) {
    if (s.row.status == "graded" && !s.has_report) return false;
    StudentNeed n;
    n.student = s.row.student;
    n.status = s.row.status;
    n.message = s.row.message;
    n.max_total = max_total;
    if (s.has_report && s.row.report.size() > 11 &&
        s.row.report.compare(s.row.report.size() - 11, 11, "report.json") == 0)
        n.report_html = s.row.report.substr(0, s.row.report.size() - 11) + "report.html";
    std::vector<std::string> timeouts, not_compiled, crashed, missing, files_missing, not_attempted, weak;
    for (const LabClass& lab : labs) {
        n.goals_total += int(lab.goals.size());
        const std::string status = labStatus(s, lab.id);
        n.total += labScore(s, lab.id);
        if (status == "timeout") timeouts.push_back(lab.id);
        if (status == "compile_error" || status == "link_error") not_compiled.push_back(lab.id);
        if (status == "crashed") crashed.push_back(lab.id);
        // A refused archive's labs are all missing: the refusal is the reason, said below.
        if (status == "missing" && n.status == "graded")
            (notHandedIn(s, lab.id) ? missing : files_missing).push_back(lab.id);
        if (status == "not_attempted") not_attempted.push_back(lab.id);
        if (const grader::ReportLab* l = reportLab(s, lab.id)) {
            n.goals_met += goalsMet(*l, lab);
            const double score = labScore(s, lab.id);  // the summary's, as the totals
            if (rendered(status) && score < kHelpBelowShare * lab.max_score)
                weak.push_back(weakPhrase(*l, lab, score));
        }
    }
    n.timeouts = int(timeouts.size());
    n.not_compiled = int(not_compiled.size());
    n.crashed = int(crashed.size());
    n.not_handed_in = int(missing.size());
    n.not_attempted = int(not_attempted.size());
    n.weak_labs = int(weak.size());
    if (n.status != "graded") {
        n.reasons.push_back(n.status == "empty" ? "no lab folder in the submission"
                                                : "archive refused (" + n.status + ")");
    } else if (!missing.empty()) {
        n.reasons.push_back(labsPhrase("not handed in", missing));
    }
    if (!not_attempted.empty())
        n.reasons.push_back(labsPhrase("not attempted (the starter code, untouched)", not_attempted));
    if (!files_missing.empty()) n.reasons.push_back(labsPhrase("a file missing", files_missing));
    if (!timeouts.empty()) n.reasons.push_back(labsPhrase("timed out", timeouts, true));
    if (!not_compiled.empty()) n.reasons.push_back(labsPhrase("did not compile", not_compiled));
    if (!crashed.empty()) n.reasons.push_back(labsPhrase("crashed", crashed));
    n.reasons.insert(n.reasons.end(), weak.begin(), weak.end());
    if (n.reasons.empty()) return false;
    *out = std::move(n);
    return true;
}

double goalFraction(const StudentNeed& n) {
    return n.goals_total > 0 ? double(n.goals_met) / n.goals_total : 0.0;
}

std::vector<ReteachItem> reteachFirst(const std::vector<LabClass>& labs, std::size_t max_items) {
    std::vector<ReteachItem> items;
    for (const LabClass& lab : labs) {
        for (const GoalShare& g : lab.goals) {
            // Only goals students failed on their own work: one lost because of another goal is
            // that goal's to re-teach, and one lost where the lab did not render is needs_help's.
            if (g.of == 0 || g.own_failed == 0) continue;
            ReteachItem r;
            r.lab = lab.id;
            r.lab_title = lab.title;
            r.goal = g.id;
            r.goal_title = g.title;
            r.met = g.met;
            r.of = g.of;
            r.own_failed = g.own_failed;
            r.own_failed_whole = g.own_failed_whole;
            if (!g.mistakes.empty()) {
                r.mistake = g.mistakes.front().mistake;
                r.mistake_students = g.mistakes.front().students;
                for (const MistakeTally& t : lab.mistakes)
                    if (t.mistake == r.mistake) r.about = t.about;
            }
            items.push_back(r);
        }
    }
    std::stable_sort(items.begin(), items.end(), [](const ReteachItem& a, const ReteachItem& b) {
        // share a.own_failed/a.of > b.own_failed/b.of without rounding; then more such students first.
        const long lhs = long(a.own_failed) * b.of, rhs = long(b.own_failed) * a.of;
        if (lhs != rhs) return lhs > rhs;
        // A goal whose failures were judged on the student's own work for it before one whose work
        // could not be taken alone (the whole shaders failed it, maybe because of another goal).
        if (a.own_failed_whole != b.own_failed_whole) return a.own_failed_whole < b.own_failed_whole;
        return a.own_failed > b.own_failed;
    });
    std::vector<ReteachItem> first;
    for (ReteachItem& item : items) {
        auto same = std::find_if(first.begin(), first.end(), [&](const ReteachItem& f) {
            return !item.mistake.empty() && f.lab == item.lab && f.mistake == item.mistake;
        });
        if (same != first.end())
            same->also_goals.push_back(item.goal);
        else if (first.size() < max_items)
            first.push_back(std::move(item));
    }
    return first;
}

// The class's labs: the summary's columns and any other lab a report holds; unless the labs were
// named, those no one handed in are left out (an older batch listed every lab of the course).
std::vector<std::string> classLabs(const ClassInput& in) {
    std::vector<std::string> ids = in.labs;
    for (const StudentResults& s : in.students)
        for (const grader::ReportLab& l : s.report.labs)
            if (s.has_report && std::find(ids.begin(), ids.end(), l.id) == ids.end()) ids.push_back(l.id);
    if (in.labs_named) return ids;
    std::vector<std::string> kept;
    for (const std::string& id : ids)
        for (const StudentResults& s : in.students)
            if (s.row.status == "graded" && (labStatus(s, id) != "missing" || !notHandedIn(s, id))) {
                kept.push_back(id);
                break;
            }
    return kept;
}

}  // namespace

Histogram pointsHistogram(const std::vector<double>& scores, double max_score) {
    Histogram h;
    if (!(max_score > 0.0) || !std::isfinite(max_score)) return h;
    const auto whole = [](double v) { return std::isfinite(v) && std::fabs(v - std::round(v)) < 1e-6; };
    h.whole_points =
        whole(max_score) && max_score <= 20.0 && std::all_of(scores.begin(), scores.end(), whole);
    if (h.whole_points) {
        const int n = int(std::lround(max_score)) + 1;
        for (int k = 0; k < n; ++k) h.bins.push_back({double(k), double(k), 0});
        for (double v : scores) ++h.bins[std::clamp(int(std::lround(v)), 0, n - 1)].count;
        return h;
    }
    const int n = 10;
    const double w = max_score / n;
    for (int k = 0; k < n; ++k) h.bins.push_back({k * w, k + 1 == n ? max_score : (k + 1) * w, 0});
    for (double v : scores) {
        const double x = std::isfinite(v) ? v / w : 0.0;
        ++h.bins[std::clamp(int(std::floor(x)), 0, n - 1)].count;
    }
    return h;
}

ClassReport aggregateClass(const ClassInput& in, std::size_t reteach_max) {
    ClassReport r;
    r.tool_version = in.tool_version;
    r.results_dir = in.results_dir;
    r.errors = in.errors;
    r.submissions = int(in.students.size());
    for (const std::string& id : classLabs(in)) r.labs.push_back(countLab(in, id));
    for (const LabClass& lab : r.labs) r.max_total += lab.max_score;

    std::map<std::string, int> statuses;
    std::vector<double> totals;
    for (const StudentResults& s : in.students) {
        ++statuses[s.row.status];
        double total = 0.0;
        for (const LabClass& lab : r.labs) total += labScore(s, lab.id);
        totals.push_back(total);
        StudentNeed n;
        if (studentNeed(s, r.labs, r.max_total, &n)) r.needs_help.push_back(std::move(n));
    }
    r.submission_statuses = orderedCounts(statuses, kSubmissionStatuses);
    r.totals = pointsHistogram(totals, r.max_total);
    std::stable_sort(
        r.needs_help.begin(), r.needs_help.end(), [](const StudentNeed& a, const StudentNeed& b) {
            const double fa = goalFraction(a), fb = goalFraction(b);
            return std::make_tuple(fa, -a.timeouts, -(a.not_compiled + a.crashed), a.total, a.student) <
                   std::make_tuple(fb, -b.timeouts, -(b.not_compiled + b.crashed), b.total, b.student);
        });
    r.reteach = reteachFirst(r.labs, reteach_max);
    return r;
}

}  // namespace shaderlab::classview
