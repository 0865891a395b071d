// What a corpus case's grade must be: each kind's rule, and goal isolation's judged fields.
#include "shaderlab/authoring/corpus_verdict.h"

#include <gtest/gtest.h>

namespace shaderlab::authoring {
namespace {

LabSpec twoGoals() {
    LabSpec spec;
    spec.id = "01-phong";
    GoalSpec lambert;
    lambert.id = "lambert";
    lambert.work = {{"phong.frag", "diffuse"}};
    GoalSpec together;
    together.id = "together";  // judged on the whole shaders
    spec.goals = {lambert, together};
    return spec;
}

grader::ReportLab graded(bool lambert_met, const std::string& judged, const std::string& note = "") {
    grader::ReportLab lab;
    lab.status = "failed";
    lab.max_score = 10.0;
    grader::ReportGoal a;
    a.id = "lambert";
    a.points = 4.0;
    a.met = lambert_met;
    a.judged = judged;
    a.judged_note = note;
    grader::ReportGoal b;
    b.id = "together";
    b.points = 6.0;
    b.met = true;
    b.judged = "whole";
    lab.goals = {a, b};
    lab.score = (lambert_met ? 4.0 : 0.0) + 6.0;
    return lab;
}

Case mistake(std::vector<std::string> fails, std::vector<std::string> whole = {}) {
    Case c;
    c.name = "case";
    c.kind = "mistake";
    c.status = "failed";
    c.fails = std::move(fails);
    c.whole = std::move(whole);
    return c;
}

TEST(CorpusVerdict, GivenCodeTheCaseChangesIsJudgedWithTheGoal) {
    const LabSpec spec = twoGoals();
    Case c = mistake({"lambert"});
    c.given = {"phong.frag: main"};
    grader::ReportLab lab = graded(false, "alone");
    EXPECT_EQ(expectationsMissed(spec, c, lab),
              "goal lambert was judged with no given code; the case changes phong.frag: main");
    lab.goals[0].judged_with = {"phong.frag: main"};
    EXPECT_EQ(expectationsMissed(spec, c, lab), "");
    // Judged with given code a case does not say it changes.
    EXPECT_EQ(expectationsMissed(spec, mistake({"lambert"}), lab),
              "goal lambert was judged with phong.frag: main; the case changes none it uses");
}

TEST(CorpusVerdict, AMistakeFailsItsGoalJudgedOnItsOwnWork) {
    const LabSpec spec = twoGoals();
    EXPECT_EQ(expectationsMissed(spec, mistake({"lambert"}), graded(false, "alone")), "");
    // Failed, but judged on the whole shaders: isolation did not do its work.
    EXPECT_EQ(expectationsMissed(spec, mistake({"lambert"}), graded(false, "whole", "no diffuse")),
              "goal lambert must be judged on the student's own work for it (judged whole: no diffuse)");
    // A goal the mistake should not cost.
    EXPECT_NE(expectationsMissed(spec, mistake({"together"}), graded(false, "alone"))
                  .find("goal lambert must stay met"),
              std::string::npos);
    EXPECT_EQ(expectationsMissed(spec, mistake({"lambert"}), graded(true, "whole")),
              "must lose points; goal lambert must not be met");
}

TEST(CorpusVerdict, GoalsListedWholeMustSayWhy) {
    const LabSpec spec = twoGoals();
    EXPECT_EQ(
        expectationsMissed(spec, mistake({"lambert"}, {"lambert"}),
                           graded(false, "whole", "`diffuse` in phong.frag is still as the starter had it")),
        "");
    EXPECT_EQ(expectationsMissed(spec, mistake({"lambert"}, {"lambert"}), graded(false, "alone")),
              "goal lambert must be judged on the whole shaders, saying why (it was judged alone)");
}

TEST(CorpusVerdict, AlternativesStartersAndBrokenCases) {
    const LabSpec spec = twoGoals();
    Case alternative;
    alternative.kind = "alternative";
    alternative.status = "passed";
    grader::ReportLab full = graded(true, "whole");
    full.status = "passed";
    EXPECT_EQ(expectationsMissed(spec, alternative, full), "");
    EXPECT_EQ(expectationsMissed(spec, alternative, graded(false, "alone")), "must pass with full marks");
    Case broken;
    broken.kind = "broken";
    broken.status = "compile_error";
    broken.diagnostic = std::make_pair(std::string("phong.frag"), 25);
    grader::ReportLab lab;
    lab.status = "compile_error";
    lab.diagnostics.push_back({"phong.frag", 26, 0, "error", "syntax error", "", "", "", 0});
    EXPECT_EQ(expectationsMissed(spec, broken, lab), "must report phong.frag:25");
    lab.diagnostics[0].line = 25;
    EXPECT_EQ(expectationsMissed(spec, broken, lab), "");
    lab.status = "timeout";
    EXPECT_EQ(expectationsMissed(spec, broken, lab), "must end as compile_error");
}

}  // namespace
}  // namespace shaderlab::authoring
