// What the class did not learn (`shaderlab class`): the results folder of `shaderlab batch` or
// `shaderlab merge` read as one class. Per lab: the share of students meeting each learning goal,
// the known mistakes recognised most often (report scenes' hints) with their pictures, the spread
// of points, the statuses; for the class: the students who need help most, and a short list of
// what to re-teach first (the goals met by the fewest, with the mistake most often behind them).
// Written as class.json and as a page (index.html) that stands alone: its plots are SVG drawn
// here, its pictures are copied beside it, and it has no script and fetches nothing.
//
// It does not grade, render or compare pictures: it counts what the batch wrote. POSIX paths.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "grader/reports/report.h"
#include "shaderlab/batch/batch.h"

namespace shaderlab::classview {

// ---- input: a results folder -------------------------------------------------------------------

// One submission as the batch left it: its summary row and, when it could be read, its report.
struct StudentResults {
    batch::SummaryRow row;
    bool has_report = false;  // false: no report, or one that could not be read (see ClassInput::errors)
    grader::Report report;
    std::string report_dir;  // the report's folder, absolute: its picture paths are relative to it
};

struct ClassInput {
    std::string results_dir;  // absolute
    std::string tool_version;
    std::vector<std::string> labs;  // the summary's lab columns, in order
    bool labs_named = false;        // the summary's: the labs were named (--lab), not handed in
    std::vector<StudentResults> students;
    std::vector<std::string> errors;  // "<file>: <problem>", one per report that could not be read
};

// Reads <results_dir>/summary.json and every submission's report.json. false, with the message,
// when the summary is missing or malformed. A report that is missing, malformed or outside the
// results folder is named in `errors`, and its student is counted from the summary row alone
// (statuses and points, not goals or mistakes).
bool readClassResults(const std::string& results_dir, ClassInput* out, std::string* error);

// ---- output: the class ---------------------------------------------------------------------------

struct StatusCount {
    std::string status;
    int count = 0;
};

// Points in bins. `whole_points`: one bin per whole point 0..max (scores and max are whole and
// max <= 20); otherwise ten bins of max/10, each [from, to) but the last [from, to].
struct Histogram {
    struct Bin {
        double from = 0.0, to = 0.0;
        int count = 0;
    };
    bool whole_points = false;
    std::vector<Bin> bins;  // empty when max_score is not above 0
};
Histogram pointsHistogram(const std::vector<double>& scores, double max_score);

struct MistakeCount {
    std::string mistake;
    int students = 0;
};

struct GoalShare {
    std::string id, title;
    double points = 0.0;
    int met = 0;
    int of = 0;  // students who handed the lab in and whose report was read
    // Of those who did not meet it: how many failed it on their own work for it (their report
    // gives no other goal it was lost because of: `not_met_because` empty), how many lost it only
    // because a goal it rests on was not met (reports graded with lab.json's depends_on), and how
    // many did not render the lab at all (compile error, timeout, crash).
    int own_failed = 0;
    // Of own_failed: those whose work for it could not be taken alone (renamed, inlined, left as the
    // starter had it: report goal judged "whole" with a judged_note), so the whole shaders failed it.
    int own_failed_whole = 0;
    int failed_because = 0;
    int not_rendered = 0;
    // Of those whose own work failed: the known mistakes recognised on its scenes (most first),
    // and how many showed no known mistake there.
    std::vector<MistakeCount> mistakes;
    int unexplained = 0;
    double share() const { return of > 0 ? double(met) / of : 0.0; }
};

// A known mistake (tests/corpus/<lab>/<mistake>, labs/<lab>/hints) recognised in the class.
struct MistakeTally {
    std::string mistake, about;
    int students = 0;                // students in whose report it was recognised (once each)
    std::vector<std::string> goals;  // ids of the goals it breaks: own work failed where it was seen
    std::string scene, image;        // where it was recognised most often (image: a ReportPass name)
    // Sources of its pictures, absolute (empty: none): the reference's and a student's picture of
    // that scene and image, from the first report that showed it.
    std::string reference_source, student_source;
    // The pictures the page shows, relative to the output folder (set by writeClassPage).
    std::string expected_picture, mistake_picture;
    bool mistake_picture_is_students = false;  // no hint picture found: a student's is shown
};

struct LabClass {
    std::string id, title;
    double max_score = 0.0;
    int students = 0;                    // rows of the summary
    int handed_in = 0;                   // rows whose lab status is neither "missing" nor "not_attempted"
    int not_attempted = 0;               // rows that handed in the starter code untouched
    std::vector<StatusCount> statuses;   // the closed set in order (then any other), zeros left out
    std::vector<GoalShare> goals;        // in the lab's order
    std::vector<MistakeTally> mistakes;  // most students first
    Histogram points;                    // of those who handed it in
    double mean = 0.0, median = 0.0;     // of those who handed it in
};

// A student who needs help (see aggregateClass): a lab not handed in, not attempted, not built or
// rendered, or below kHelpBelowShare of its points, or an archive refused.
struct StudentNeed {
    std::string student;
    std::string status;  // the submission's: graded, empty, bad_archive, ...
    std::string message;
    int goals_met = 0, goals_total = 0;  // over the class's labs (not handed in: unmet)
    int timeouts = 0, not_compiled = 0, crashed = 0, not_handed_in = 0, not_attempted = 0;
    int weak_labs = 0;                    // rendered, below kHelpBelowShare of their points
    double total = 0.0, max_total = 0.0;  // over the class's labs
    std::string report_html;              // relative to the results folder; empty when there is none
    std::vector<std::string> reasons;     // in plain words, most telling first
};

struct ReteachItem {
    std::string lab, lab_title, goal, goal_title;
    int met = 0, of = 0;
    int own_failed = 0;          // students whose own work for it failed (GoalShare::own_failed)
    int own_failed_whole = 0;    // of those, judged on the whole shaders (GoalShare::own_failed_whole)
    std::string mistake, about;  // the known mistake most often behind it; empty when none
    int mistake_students = 0;
    std::string picture;  // the mistake's picture, relative to the output folder; empty: none
    // Goals of the lab met by more students, with the same mistake most often behind them: one
    // thing to re-teach, so they are folded into this item rather than listed again.
    std::vector<std::string> also_goals;
};

struct ClassReport {
    std::string tool_version;
    std::string results_dir;
    int submissions = 0;
    std::vector<StatusCount> submission_statuses;  // graded, then the archive refusals
    double max_total = 0.0;                        // the points of the class's labs
    Histogram totals;                              // every submission's total over the class's labs
    std::vector<LabClass> labs;
    std::vector<ReteachItem> reteach;     // at most `reteach_max`, fewest met first (see aggregateClass)
    std::vector<StudentNeed> needs_help;  // neediest first (see aggregateClass)
    std::vector<std::string> errors;      // ClassInput::errors
};

// A rendered lab below this share of its points is a reason to need help.
constexpr double kHelpBelowShare = 0.5;

// Counts the class. The class's labs are the summary's columns: those named (--lab), or those the
// class handed in (a summary written before that was recorded lists every lab of the course: the
// labs no one handed in are left out). Each lab is counted over the students who handed it in (not
// "missing", not "not_attempted"); totals are over the class's labs.
//
// Goals to re-teach are the goals students failed on their own work (GoalShare::own_failed),
// ranked by the share of such students (then by their number); a goal lost only because of
// another goal, or only where a lab did not render, is not one, and a known mistake is listed
// under the goals it breaks, not those that rest on them. A goal whose most frequent mistake is
// that of a goal ranked before it is folded into that one.
//
// A student needs help when the archive was refused, or a lab of the class was not handed in, not
// attempted, did not build or render, or scored below kHelpBelowShare of its points; ranked by
// share of goals met, then by timeouts, then by labs that did not compile or crashed, then by
// total points, then by name. Students whose report could not be read are left out of goals,
// mistakes and the needs-help list.
ClassReport aggregateClass(const ClassInput& input, std::size_t reteach_max = 5);

// class.json (docs/instructors.md, "What the class did not learn").
std::string classToJson(const ClassReport& report);
// The page. `results_href`: the results folder as a link from the page's folder ("../results/"),
// for links to each student's report.html; empty: no links.
std::string classToHtml(const ClassReport& report, const std::string& results_href);

// Writes <out_dir>/index.html, class.json and pictures/<lab>/ (the hint pictures from
// <labs_root>/<lab>/hints/ and the reference pictures from the reports; empty `labs_root`: the
// students' pictures stand in for the hints). Pictures that cannot be found or copied are said in
// `warnings` and left out. false, with the message, when the output cannot be written.
bool writeClassPage(ClassReport report, const std::string& out_dir, const std::string& labs_root,
                    std::vector<std::string>* warnings, std::string* error);

}  // namespace shaderlab::classview
