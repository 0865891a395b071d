// The class's counts from a small hand-made results folder: seven students, two labs, written by
// the test (summary.json with the batch's writer, report.json with the reports' writer, one
// report broken by hand). What each number must be is worked out in the comments.
#include "shaderlab/classview/class_report.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace shaderlab::classview {
namespace {

fs::path scratch(const std::string& name) {
    const fs::path p =
        fs::temp_directory_path() / ("shaderlab_classview_" + name + "_" + std::to_string(getpid()));
    fs::remove_all(p);
    fs::create_directories(p);
    return p;
}

void writeFile(const fs::path& p, const std::string& text) {
    fs::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << text;
}

std::string readFile(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

// A goal of a lab: met or not, seen in `scene`.
grader::ReportGoal goal(const std::string& id, double points, bool met, const std::string& scene) {
    grader::ReportGoal g;
    g.id = id;
    g.title = "Goal " + id;
    g.points = points;
    g.met = met;
    g.scenes = {scene};
    if (!met) g.failing = {scene + "/shade"};
    return g;
}

// A failing scene recognised as `mistake` (empty: none), with its pictures' paths.
grader::ReportScene scene(const std::string& name, const std::string& mistake) {
    grader::ReportScene s;
    s.name = name;
    s.status = mistake.empty() ? "passed" : "failed";
    s.student_image = "lab/" + name + "/student.png";
    s.reference_image = "lab/" + name + "/reference.png";
    grader::ReportPass p;
    p.name = "shade";
    p.student_image = s.student_image;
    p.reference_image = s.reference_image;
    s.passes.push_back(p);
    if (!mistake.empty()) s.hint = {mistake, "about " + mistake, "shade", 45.0};
    return s;
}

// Lab 01: goals A (2 points, scene sa), B (1, sb), C (1, sc). Lab 02: goals X (sx), Y (sy).
grader::ReportLab lab1(const std::string& status, bool a, bool b, bool c, const std::string& mistake_a = "",
                       const std::string& mistake_b = "") {
    grader::ReportLab l;
    l.id = "01-lab";
    l.title = "The first lab";
    l.status = status;
    l.max_score = 4;
    if (status == "passed" || status == "failed") {
        l.goals = {goal("A", 2, a, "sa"), goal("B", 1, b, "sb"), goal("C", 1, c, "sc")};
        l.scenes = {scene("sa", mistake_a), scene("sb", mistake_b), scene("sc", "")};
        l.score = 2 * a + b + c;
    }
    return l;
}

grader::ReportLab lab2(const std::string& status, bool x, bool y) {
    grader::ReportLab l;
    l.id = "02-lab";
    l.title = "The second lab";
    l.status = status;
    l.max_score = 2;
    if (status == "passed" || status == "failed") {
        l.goals = {goal("X", 1, x, "sx"), goal("Y", 1, y, "sy")};
        l.scenes = {scene("sx", ""), scene("sy", "")};  // X unmet with no known mistake
        l.score = x + y;
    }
    return l;
}

grader::ReportLab missingLab(const std::string& id) {
    grader::ReportLab l;
    l.id = id;
    l.status = "missing";
    return l;
}

struct Fixture {
    fs::path results;
    batch::Summary summary;

    void add(const std::string& student, const std::string& status, std::vector<grader::ReportLab> labs) {
        batch::SummaryRow row;
        row.student = student;
        row.status = status;
        row.message = status == "graded" ? "" : "the .zip cannot be read";
        row.report = student + "/report.json";
        grader::Report report;
        for (const grader::ReportLab& l : labs) {
            row.labs.push_back({l.id, l.score, l.max_score, l.status});
            row.total += l.score;
            row.max_total += l.max_score;
        }
        report.labs = std::move(labs);
        report.score = row.total;
        report.max_score = row.max_total;
        summary.rows.push_back(row);
        writeFile(results / row.report, grader::reportToJson(report));
        for (const grader::ReportLab& l : report.labs)
            for (const grader::ReportScene& s : l.scenes) {
                writeFile(results / student / s.student_image, "student picture of " + student);
                writeFile(results / student / s.reference_image, "reference picture");
            }
    }

    void write() { writeFile(results / "summary.json", batch::summaryToJson(summary)); }
};

// The class the counts below are worked out for.
Fixture makeClass(const std::string& name) {
    Fixture f;
    f.results = scratch(name) / "results";
    f.summary.labs = {"01-lab", "02-lab"};
    f.add("alice", "graded", {lab1("passed", true, true, true), lab2("passed", true, true)});
    f.add("bob", "graded", {lab1("failed", false, true, true, "gouraud"), lab2("failed", false, true)});
    f.add("carol", "graded",
          {lab1("failed", false, false, true, "gouraud", "model-matrix"), lab2("compile_error", 0, 0)});
    f.add("dave", "graded", {lab1("timeout", 0, 0, 0), lab2("timeout", 0, 0)});
    f.add("erin", "graded", {missingLab("01-lab"), lab2("passed", true, true)});
    f.add("frank", "bad_archive", {missingLab("01-lab"), missingLab("02-lab")});
    f.add("gina", "graded", {lab1("passed", true, true, true), lab2("passed", true, true)});
    writeFile(f.results / "gina/report.json", "{\"schema_version\": 2, \"labs\": [");  // cut short
    f.write();
    return f;
}

ClassReport readClass(const Fixture& f, ClassInput* in = nullptr) {
    ClassInput local;
    ClassInput* input = in ? in : &local;
    std::string error;
    EXPECT_TRUE(readClassResults(f.results.string(), input, &error)) << error;
    return aggregateClass(*input);
}

int statusCount(const std::vector<StatusCount>& counts, const std::string& status) {
    for (const StatusCount& c : counts)
        if (c.status == status) return c.count;
    return 0;
}

TEST(ClassReport, GoalSharesCountStudentsWhoHandedTheLabIn) {
    const ClassReport r = readClass(makeClass("shares"));
    ASSERT_EQ(r.labs.size(), 2u);
    const LabClass& l1 = r.labs[0];
    EXPECT_EQ(l1.id, "01-lab");
    EXPECT_EQ(l1.title, "The first lab");
    // Handed in: alice, bob, carol, dave, gina (row says passed); gina's report cannot be read,
    // so the goals count alice, bob, carol and dave (dave's timeout meets none).
    EXPECT_EQ(l1.handed_in, 5);
    ASSERT_EQ(l1.goals.size(), 3u);
    EXPECT_EQ(l1.goals[0].id, "A");
    EXPECT_EQ(l1.goals[0].met, 1);
    EXPECT_EQ(l1.goals[0].of, 4);
    EXPECT_DOUBLE_EQ(l1.goals[0].share(), 0.25);
    EXPECT_EQ(l1.goals[1].met, 2);  // B: alice, bob
    EXPECT_EQ(l1.goals[2].met, 3);  // C: alice, bob, carol
    EXPECT_EQ(l1.goals[0].not_rendered, 1);
    EXPECT_EQ(l1.goals[0].unexplained, 0);
    ASSERT_EQ(l1.goals[0].mistakes.size(), 1u);
    EXPECT_EQ(l1.goals[0].mistakes[0].mistake, "gouraud");
    EXPECT_EQ(l1.goals[0].mistakes[0].students, 2);

    const LabClass& l2 = r.labs[1];
    // X: of alice, bob, carol, dave, erin; met by alice and erin. Bob's X has no known mistake.
    EXPECT_EQ(l2.goals[0].met, 2);
    EXPECT_EQ(l2.goals[0].of, 5);
    EXPECT_EQ(l2.goals[0].unexplained, 1);
    EXPECT_EQ(l2.goals[0].not_rendered, 2);
    EXPECT_TRUE(l2.goals[0].mistakes.empty());
}

TEST(ClassReport, MistakesAndStatusesAreCounted) {
    const ClassReport r = readClass(makeClass("counts"));
    const LabClass& l1 = r.labs[0];
    ASSERT_EQ(l1.mistakes.size(), 2u);
    EXPECT_EQ(l1.mistakes[0].mistake, "gouraud");  // most students first
    EXPECT_EQ(l1.mistakes[0].students, 2);
    EXPECT_EQ(l1.mistakes[0].about, "about gouraud");
    EXPECT_EQ(l1.mistakes[0].goals, std::vector<std::string>{"A"});
    EXPECT_EQ(l1.mistakes[0].scene, "sa");
    EXPECT_EQ(l1.mistakes[0].image, "shade");
    EXPECT_EQ(l1.mistakes[1].mistake, "model-matrix");
    EXPECT_EQ(l1.mistakes[1].students, 1);
    EXPECT_EQ(l1.mistakes[1].goals, std::vector<std::string>{"B"});
    EXPECT_NE(l1.mistakes[0].reference_source.find("/bob/lab/sa/reference.png"), std::string::npos);

    // Lab statuses from summary.json, gina's among them although her report cannot be read.
    EXPECT_EQ(statusCount(l1.statuses, "passed"), 2);
    EXPECT_EQ(statusCount(l1.statuses, "failed"), 2);
    EXPECT_EQ(statusCount(l1.statuses, "timeout"), 1);
    EXPECT_EQ(statusCount(l1.statuses, "missing"), 2);
    EXPECT_EQ(l1.statuses.front().status, "passed");  // the closed set's order
    EXPECT_EQ(l1.statuses.back().status, "missing");
    EXPECT_EQ(statusCount(r.labs[1].statuses, "compile_error"), 1);
    EXPECT_EQ(r.submissions, 7);
    EXPECT_EQ(statusCount(r.submission_statuses, "graded"), 6);
    EXPECT_EQ(statusCount(r.submission_statuses, "bad_archive"), 1);
}

TEST(ClassReport, PointsHistogramOfThoseWhoHandedItIn) {
    const ClassReport r = readClass(makeClass("points"));
    const Histogram& h = r.labs[0].points;
    // alice 4, bob 2+1+0... bob: B and C met = 2; carol: C = 1; dave 0; gina 4 (from the summary).
    ASSERT_TRUE(h.whole_points);
    ASSERT_EQ(h.bins.size(), 5u);
    const std::vector<int> expected = {1, 1, 1, 0, 2};
    for (std::size_t i = 0; i < expected.size(); ++i) EXPECT_EQ(h.bins[i].count, expected[i]) << "bin " << i;
    EXPECT_DOUBLE_EQ(r.labs[0].mean, 11.0 / 5);
    EXPECT_DOUBLE_EQ(r.labs[0].median, 2.0);
    // Totals of all seven submissions, of 6.
    EXPECT_DOUBLE_EQ(r.max_total, 6.0);
    ASSERT_EQ(r.totals.bins.size(), 7u);
    EXPECT_EQ(r.totals.bins[6].count, 2);  // alice, gina
    EXPECT_EQ(r.totals.bins[0].count, 2);  // dave, frank
}

TEST(ClassReport, HistogramBins) {
    const Histogram whole = pointsHistogram({0, 3, 3, 1}, 3);
    ASSERT_TRUE(whole.whole_points);
    ASSERT_EQ(whole.bins.size(), 4u);
    EXPECT_EQ(whole.bins[0].count, 1);
    EXPECT_EQ(whole.bins[1].count, 1);
    EXPECT_EQ(whole.bins[2].count, 0);
    EXPECT_EQ(whole.bins[3].count, 2);

    // Fractions: ten bins of 1, each [from, to) but the last, which holds the maximum too.
    const Histogram tenths = pointsHistogram({0, 0.5, 5, 9.99, 10, 12, -1}, 10);
    ASSERT_FALSE(tenths.whole_points);
    ASSERT_EQ(tenths.bins.size(), 10u);
    EXPECT_EQ(tenths.bins[0].count, 3);  // 0, 0.5 and -1 (clamped)
    EXPECT_EQ(tenths.bins[5].count, 1);
    EXPECT_EQ(tenths.bins[9].count, 3);  // 9.99, 10 and 12 (clamped)
    EXPECT_DOUBLE_EQ(tenths.bins[9].from, 9.0);
    EXPECT_DOUBLE_EQ(tenths.bins[9].to, 10.0);

    EXPECT_FALSE(pointsHistogram({1, 2}, 30).whole_points);  // too many points for one bin each
    EXPECT_EQ(pointsHistogram({1, 2}, 30).bins.size(), 10u);
    EXPECT_TRUE(pointsHistogram({1, 2}, 0).bins.empty());
}

TEST(ClassReport, NeedsHelpOrder) {
    const ClassReport r = readClass(makeClass("help"));
    // Of 5 goals: dave 0 (two timeouts), frank 0 (archive refused), carol 1 (and a compile error),
    // erin 2 (01-lab not handed in). Bob has half the points of each lab (2 of 4, 1 of 2): short
    // of a goal in each, but not in need of help; alice met all, gina's report cannot be read.
    std::vector<std::string> order;
    for (const StudentNeed& n : r.needs_help) order.push_back(n.student);
    EXPECT_EQ(order, (std::vector<std::string>{"dave", "frank", "carol", "erin"}));
    const StudentNeed& dave = r.needs_help[0];
    EXPECT_EQ(dave.timeouts, 2);
    EXPECT_EQ(dave.goals_total, 5);
    EXPECT_EQ(dave.report_html, "dave/report.html");
    ASSERT_FALSE(dave.reasons.empty());
    EXPECT_NE(dave.reasons[0].find("timed out"), std::string::npos);
    EXPECT_EQ(r.needs_help[1].reasons, std::vector<std::string>{"archive refused (bad_archive)"});
    EXPECT_EQ(r.needs_help[2].goals_met, 1);
    EXPECT_EQ(r.needs_help[2].not_compiled, 1);
    EXPECT_EQ(r.needs_help[3].not_handed_in, 1);
    EXPECT_EQ(r.needs_help[3].reasons, std::vector<std::string>{"not handed in: 01-lab"});
    // Carol: 1 of 4 points in 01-lab, below half of it.
    const StudentNeed& carol = r.needs_help[2];
    EXPECT_EQ(carol.weak_labs, 1);
    EXPECT_EQ(carol.reasons,
              (std::vector<std::string>{"did not compile: 02-lab",
                                        "01-lab: 1 of 4 points; A, B not met (gouraud, model-matrix)"}));
}

TEST(ClassReport, ReteachFirstIsTheGoalsMostFailedOnTheStudentsOwnWork) {
    const ClassReport r = readClass(makeClass("reteach"));
    // Failed on the student's own work: A by bob and carol (2 of 4), B by carol (1 of 4), X by bob
    // (1 of 5); Y (3/5) and C (3/4) are unmet only by labs that did not render.
    std::vector<std::string> goals;
    for (const ReteachItem& t : r.reteach) goals.push_back(t.goal);
    EXPECT_EQ(goals, (std::vector<std::string>{"A", "B", "X"}));
    EXPECT_EQ(r.reteach[0].own_failed, 2);
    EXPECT_EQ(r.reteach[0].mistake, "gouraud");
    EXPECT_EQ(r.reteach[0].mistake_students, 2);
    EXPECT_EQ(r.reteach[0].about, "about gouraud");
    EXPECT_EQ(r.reteach[1].mistake, "model-matrix");
    EXPECT_TRUE(r.reteach[2].mistake.empty());
    ClassInput in;
    std::string error;
    ASSERT_TRUE(readClassResults(makeClass("reteach2").results.string(), &in, &error)) << error;
    EXPECT_EQ(aggregateClass(in, 2).reteach.size(), 2u);
}

// A graded student whose report was read, its labs left to the caller.
StudentResults gradedStudent(const std::string& name) {
    StudentResults s;
    s.row.student = name;
    s.row.status = "graded";
    s.row.report = name + "/report.json";
    s.has_report = true;
    return s;
}

// In memory: three students, goals P, Q, R; one mistake "m" behind both P and Q.
TEST(ClassReport, ReteachFoldsGoalsWithTheSameMistake) {
    ClassInput in;
    in.labs = {"03-lab"};
    const auto student = [&](const std::string& name, bool p, bool q, bool r, const std::string& mp,
                             const std::string& mq) {
        StudentResults s = gradedStudent(name);
        grader::ReportLab l;
        l.id = "03-lab";
        l.status = p && q && r ? "passed" : "failed";
        l.goals = {goal("P", 1, p, "sp"), goal("Q", 1, q, "sq"), goal("R", 1, r, "sr")};
        l.scenes = {scene("sp", mp), scene("sq", mq), scene("sr", "")};
        s.report.labs = {l};
        s.row.labs = {{"03-lab", double(p + q + r), 3.0, l.status}};
        in.students.push_back(s);
    };
    student("s1", false, false, true, "m", "m");
    student("s2", false, true, false, "m", "");
    student("s3", true, true, true, "", "");
    // P 1/3 (m behind it twice), Q 2/3 and R 2/3: Q's mistake is P's, so it is folded into P.
    const ClassReport r = aggregateClass(in);
    ASSERT_EQ(r.reteach.size(), 2u);
    EXPECT_EQ(r.reteach[0].goal, "P");
    EXPECT_EQ(r.reteach[0].mistake, "m");
    EXPECT_EQ(r.reteach[0].mistake_students, 2);
    EXPECT_EQ(r.reteach[0].also_goals, std::vector<std::string>{"Q"});
    EXPECT_EQ(r.reteach[1].goal, "R");
    EXPECT_TRUE(r.reteach[1].mistake.empty());
    EXPECT_EQ(r.labs[0].mistakes[0].goals, (std::vector<std::string>{"P", "Q"}));
    EXPECT_EQ(r.needs_help.size(), 2u);
}

// One student of lab 04: goal G (its own scene sg) and goal H (scene sh, resting on G). `g_met`,
// `h_met`; `h_because` gives H's not_met_because (a report graded with depends_on); `mistake` is
// recognised on both scenes, as a mistake in G's work shows wherever G's work is drawn.
StudentResults dependentStudent(const std::string& name, bool g_met, bool h_met, bool h_because,
                                const std::string& mistake) {
    StudentResults s = gradedStudent(name);
    grader::ReportLab l;
    l.id = "04-lab";
    l.max_score = 2;
    l.status = g_met && h_met ? "passed" : "failed";
    l.goals = {goal("G", 1, g_met, "sg"), goal("H", 1, h_met, "sh")};
    if (h_because) l.goals[1].not_met_because = {"G"};
    l.scenes = {scene("sg", g_met ? "" : mistake), scene("sh", h_met ? "" : mistake)};
    l.score = g_met + h_met;
    s.report.labs = {l};
    s.row.labs = {{"04-lab", l.score, 2.0, l.status}};
    return s;
}

// A goal lost only because another goal it rests on was not met is that goal's failure: its
// known mistake is listed under the goal it breaks, and re-teaching ranks by the students whose
// own work for a goal failed. Reports of both kinds (depends_on's not_met_because; a goal judged
// on the student's own work, which is met when that work is right) count the same.
TEST(ClassReport, GoalsCountTheStudentsWhoseOwnWorkFailedThem) {
    ClassInput in;
    in.labs = {"04-lab"};
    // Three students make mistake "m" in G's work. Older reports: H not met because of G. Newer
    // ones: H judged on the student's own work, which is right, so H is met.
    in.students.push_back(dependentStudent("old1", false, false, true, "m"));
    in.students.push_back(dependentStudent("old2", false, false, true, "m"));
    in.students.push_back(dependentStudent("new1", false, true, false, "m"));  // G's own work failed
    // ...and one student fails H on their own work alone (mistake "n").
    in.students.push_back(dependentStudent("own", true, false, false, "n"));
    const ClassReport r = aggregateClass(in);
    const LabClass& lab = r.labs[0];
    ASSERT_EQ(lab.goals.size(), 2u);
    EXPECT_EQ(lab.goals[0].own_failed, 3);  // G: old1, old2, new1
    EXPECT_EQ(lab.goals[1].own_failed, 1);  // H: own
    EXPECT_EQ(lab.goals[1].failed_because, 2);
    ASSERT_EQ(lab.goals[1].mistakes.size(), 1u);
    EXPECT_EQ(lab.goals[1].mistakes[0].mistake, "n");  // not m: m breaks G
    for (const MistakeTally& t : lab.mistakes)
        EXPECT_EQ(t.goals, std::vector<std::string>{t.mistake == "m" ? "G" : "H"}) << t.mistake;
    ASSERT_EQ(r.reteach.size(), 2u);
    EXPECT_EQ(r.reteach[0].goal, "G");
    EXPECT_EQ(r.reteach[0].own_failed, 3);
    EXPECT_EQ(r.reteach[0].mistake, "m");
    EXPECT_EQ(r.reteach[1].goal, "H");
    EXPECT_EQ(r.reteach[1].own_failed, 1);
    EXPECT_EQ(r.reteach[1].mistake, "n");
}

// Untouched starter code is handed in but not attempted: not counted among those who handed the
// lab in, no goal, no known mistake, and a reason to need help.
TEST(ClassReport, NotAttemptedIsNeitherHandedInNorAMistake) {
    Fixture f;
    f.results = scratch("not_attempted") / "results";
    f.summary.labs = {"01-lab"};
    f.add("alice", "graded", {lab1("passed", true, true, true)});
    f.add("bob", "graded", {lab1("failed", false, true, true, "gouraud")});
    grader::ReportLab starter;
    starter.id = "01-lab";
    starter.status = "not_attempted";
    starter.max_score = 4;
    starter.message = "not attempted: the starter code";
    f.add("sam", "graded", {starter});
    f.write();
    const ClassReport r = readClass(f);
    const LabClass& l = r.labs[0];
    EXPECT_EQ(l.handed_in, 2);
    EXPECT_EQ(l.not_attempted, 1);
    EXPECT_EQ(statusCount(l.statuses, "not_attempted"), 1);
    EXPECT_EQ(l.goals[0].of, 2);
    ASSERT_EQ(l.mistakes.size(), 1u);
    EXPECT_EQ(l.mistakes[0].students, 1);
    EXPECT_EQ(l.points.bins.size(), 5u);
    int counted = 0;
    for (const Histogram::Bin& b : l.points.bins) counted += b.count;
    EXPECT_EQ(counted, 2);  // alice and bob
    ASSERT_EQ(r.needs_help.size(), 1u);
    EXPECT_EQ(r.needs_help[0].student, "sam");
    EXPECT_EQ(r.needs_help[0].not_attempted, 1);
    EXPECT_EQ(r.needs_help[0].reasons,
              std::vector<std::string>{"not attempted (the starter code, untouched): 01-lab"});
}

// A summary written before the class's labs were recorded lists every lab of the course: the labs
// no one handed in are left out, and totals are over the others. Named labs (--lab) all stay.
TEST(ClassReport, TheClassLabsAreThoseHandedInUnlessNamed) {
    Fixture f;
    f.results = scratch("class_labs") / "results";
    f.summary.labs = {"01-lab", "02-lab", "09-lab"};
    f.add("alice", "graded",
          {lab1("passed", true, true, true), lab2("passed", true, true), missingLab("09-lab")});
    f.add("bob", "graded", {lab1("passed", true, true, true), missingLab("02-lab"), missingLab("09-lab")});
    // A refused archive: every lab missing, with the refusal as their message.
    std::vector<grader::ReportLab> refused = {missingLab("01-lab"), missingLab("02-lab"),
                                              missingLab("09-lab")};
    for (grader::ReportLab& l : refused) l.message = "carl.zip: not a zip archive";
    f.add("carl", "bad_archive", refused);
    for (batch::SummaryRow& row : f.summary.rows) row.max_total += 10;  // 09-lab's 10 points
    f.write();
    ClassReport r = readClass(f);
    ASSERT_EQ(r.labs.size(), 2u);
    EXPECT_EQ(r.labs[1].id, "02-lab");
    EXPECT_DOUBLE_EQ(r.max_total, 6.0);
    // Alice has every point of the class's labs: nothing to help with. Bob did not hand in 02-lab.
    ASSERT_EQ(r.needs_help.size(), 2u);
    EXPECT_EQ(r.needs_help[0].student, "carl");
    EXPECT_EQ(r.needs_help[0].reasons, std::vector<std::string>{"archive refused (bad_archive)"});
    EXPECT_EQ(r.needs_help[1].student, "bob");
    EXPECT_EQ(r.needs_help[1].reasons, std::vector<std::string>{"not handed in: 02-lab"});
    EXPECT_DOUBLE_EQ(r.needs_help[1].max_total, 6.0);

    f.summary.labs_named = true;
    f.write();
    r = readClass(f);
    ASSERT_EQ(r.labs.size(), 3u);
    EXPECT_EQ(r.labs[2].handed_in, 0);
    EXPECT_EQ(r.needs_help.size(), 3u);
}

TEST(ClassReport, MalformedReportIsNamedAndTheOthersCounted) {
    Fixture f = makeClass("malformed");
    // One more broken way: fields of the wrong type, which the report reader throws on.
    f.add("hank", "graded", {lab2("passed", true, true)});
    writeFile(f.results / "hank/report.json", R"({"schema_version": 2, "labs": [{"id": 5, "goals": 3}]})");
    // And a summary that points outside the results folder.
    batch::SummaryRow outside;
    outside.student = "ivan";
    outside.status = "graded";
    outside.report = "../elsewhere/report.json";
    f.summary.rows.push_back(outside);
    f.write();
    ClassInput in;
    const ClassReport r = readClass(f, &in);
    ASSERT_EQ(in.errors.size(), 3u);
    EXPECT_NE(in.errors[0].find((f.results / "gina/report.json").string()), std::string::npos)
        << in.errors[0];
    EXPECT_NE(in.errors[1].find((f.results / "hank/report.json").string()), std::string::npos)
        << in.errors[1];
    EXPECT_NE(in.errors[2].find("not inside the results folder"), std::string::npos) << in.errors[2];
    EXPECT_EQ(r.errors, in.errors);
    EXPECT_EQ(r.submissions, 9);
    EXPECT_EQ(r.labs[0].goals[0].of, 4);  // the others still counted
}

TEST(ClassReport, SummaryProblemsStopWithTheFileNamed) {
    const fs::path dir = scratch("nosummary");
    ClassInput in;
    std::string error;
    EXPECT_FALSE(readClassResults(dir.string(), &in, &error));
    EXPECT_NE(error.find((dir / "summary.json").string() + ": missing"), std::string::npos) << error;

    writeFile(dir / "summary.json",
              "{\"summary_version\": 1, \"submissions\": [{\"student\": \"a\", \"source\": 7}]}");
    EXPECT_FALSE(readClassResults(dir.string(), &in, &error));
    EXPECT_NE(error.find((dir / "summary.json").string()), std::string::npos) << error;

    EXPECT_FALSE(readClassResults((dir / "absent").string(), &in, &error));
    EXPECT_NE(error.find("not a folder"), std::string::npos) << error;
}

TEST(ClassReport, PageAndJsonWithPicturesBesideThem) {
    Fixture f = makeClass("page");
    f.add("<b>mallory</b>", "graded", {missingLab("01-lab"), lab2("timeout", 0, 0)});
    f.write();
    const fs::path labs = f.results.parent_path() / "labs";
    writeFile(labs / "01-lab/hints/hints.json",
              R"({"hints": [{"mistake": "gouraud", "about": "about gouraud", "scene": "sa", "image": "shade",
                             "file": "gouraud/sa.shade.png"}]})");
    writeFile(labs / "01-lab/hints/gouraud/sa.shade.png", "hint picture");
    const fs::path out = f.results.parent_path() / "class";
    std::vector<std::string> warnings;
    std::string error;
    ASSERT_TRUE(writeClassPage(readClass(f), out.string(), labs.string(), &warnings, &error)) << error;
    EXPECT_TRUE(warnings.empty()) << warnings.front();

    const json doc = json::parse(readFile(out / "class.json"));
    EXPECT_EQ(doc["class_version"], 1);
    EXPECT_EQ(doc["reteach_first"][0]["goal"], "A");
    EXPECT_EQ(doc["reteach_first"][0]["picture"], "pictures/01-lab/gouraud.mistake.png");
    const json& gouraud = doc["labs"][0]["mistakes"][0];
    EXPECT_EQ(gouraud["students"], 2);
    EXPECT_EQ(readFile(out / gouraud["mistake_picture"].get<std::string>()), "hint picture");
    EXPECT_EQ(readFile(out / gouraud["expected_picture"].get<std::string>()), "reference picture");
    // No hint picture for model-matrix: a student's picture stands in, and says so.
    const json& model = doc["labs"][0]["mistakes"][1];
    EXPECT_EQ(model["mistake_picture_is_students"], true);
    EXPECT_EQ(readFile(out / model["mistake_picture"].get<std::string>()), "student picture of carol");

    const std::string html = readFile(out / "index.html");
    EXPECT_NE(html.find("data-goal=\"A\" data-met=\"1\" data-of=\"4\""), std::string::npos);
    EXPECT_NE(html.find("data-mistake=\"gouraud\" data-students=\"2\""), std::string::npos);
    EXPECT_NE(html.find("&lt;b&gt;mallory&lt;/b&gt;"), std::string::npos);
    EXPECT_EQ(html.find("<b>mallory"), std::string::npos);
    EXPECT_NE(html.find("href=\"../results/dave/report.html\""), std::string::npos);
    EXPECT_NE(html.find("<svg class=\"plot histogram\""), std::string::npos);
    EXPECT_EQ(html.find("<script"), std::string::npos);
    EXPECT_EQ(html.find("http"), std::string::npos);  // nothing fetched from outside
}

TEST(ClassReport, PageIsNotWrittenIntoTheResultsFolder) {
    const Fixture f = makeClass("inside");
    const ClassReport r = readClass(f);
    std::vector<std::string> warnings;
    std::string error;
    for (const fs::path& out : {f.results, f.results / "class", f.results / "alice" / "page"}) {
        EXPECT_FALSE(writeClassPage(r, out.string(), "", &warnings, &error)) << out;
        EXPECT_NE(error.find("inside the results folder"), std::string::npos) << error;
    }
    EXPECT_FALSE(fs::exists(f.results / "class"));
    // Beside it: an earlier page's pictures go, files that are not the page's stay.
    const fs::path out = f.results.parent_path() / "mine";
    writeFile(out / "pictures" / "holiday.png", "not ours");
    writeFile(out / "pictures" / "01-lab" / "notes.txt", "not ours");
    writeFile(out / "pictures" / "01-lab" / "stale.expected.png", "an earlier page's");
    ASSERT_TRUE(writeClassPage(r, out.string(), "", &warnings, &error)) << error;
    EXPECT_EQ(readFile(out / "pictures" / "holiday.png"), "not ours");
    EXPECT_EQ(readFile(out / "pictures" / "01-lab" / "notes.txt"), "not ours");
    EXPECT_FALSE(fs::exists(out / "pictures" / "01-lab" / "stale.expected.png"));
    EXPECT_TRUE(fs::exists(out / "pictures" / "01-lab" / "gouraud.expected.png"));
}

}  // namespace
}  // namespace shaderlab::classview
