// The words of the window's grade panel for a grade that carries every field: goals met and
// missed, the goals a goal waits on (by number, not by title), the checks where one fails, how a
// goal was judged (judged, judged_note, whole_failing), failing scenes and their hints. The
// drawing is the window tests' (tests/viewer_test.cpp); this is what it draws.
#include <gtest/gtest.h>

#include <string>
#include <vector>

// The viewer's private lines, tested without a window.
#include "../src/viewer_grade_lines.h"

namespace {

using shaderlab::viewer::detail::gradeLines;
using shaderlab::viewer::detail::PanelLine;

grader::ReportGoal goal(const std::string& id, const std::string& title, bool met) {
    grader::ReportGoal g;
    g.id = id;
    g.title = title;
    g.met = met;
    g.points = 1.0;
    return g;
}

// The text of each line of `kind`, in order.
std::vector<std::string> texts(const std::vector<PanelLine>& lines, PanelLine::Kind kind) {
    std::vector<std::string> out;
    for (const PanelLine& l : lines)
        if (l.kind == kind) out.push_back(l.text);
    return out;
}

grader::ReportLab judgedLab() {
    grader::ReportLab lab;
    lab.id = "09-test";
    lab.status = "failed";
    grader::ReportGoal diffuse = goal("diffuse", "Lambert diffuse", true);
    diffuse.judged = "alone";
    diffuse.whole_failing = {"sphere/shade"};  // right alone, failing in the whole shader
    grader::ReportGoal spec = goal("specular", "Phong highlight", false);
    spec.judged = "alone";
    spec.failing = {"torus_grazing/shade", "sphere_grazing/shade"};
    spec.judged_with = {"phong.frag: main"};  // the student changed the main the starter gave
    grader::ReportGoal shadows = goal("shadows", "Shadow lookups", false);
    shadows.judged = "whole";
    shadows.judged_note = "its work is in main(), with the rest: it cannot be taken alone";
    shadows.failing = {"plane/shade"};
    grader::ReportGoal together = goal("together", "Everything together", false);
    together.judged = "combination";
    together.not_met_because = {"specular", "shadows"};
    lab.goals = {diffuse, spec, shadows, together};
    grader::ReportScene scene;
    scene.name = "torus_grazing";
    scene.status = "failed";
    scene.message = "'shade': PSNR 22.6 dB is below 30.0 dB";
    scene.hint.mistake = "blinn-phong";
    scene.hint.about = "Blinn's half vector instead of Phong's mirror direction";
    grader::ReportScene passing;
    passing.name = "sphere";
    passing.status = "passed";
    lab.scenes = {scene, passing};
    return lab;
}

TEST(GradeLines, EveryGoalMetOrMissedNumbered) {
    const std::vector<PanelLine> lines = gradeLines(judgedLab());
    EXPECT_EQ(texts(lines, PanelLine::Met), std::vector<std::string>{"1. Lambert diffuse (1.00)"});
    EXPECT_EQ(texts(lines, PanelLine::Missed),
              (std::vector<std::string>{"2. Phong highlight (1.00)", "3. Shadow lookups (1.00)",
                                        "4. Everything together (1.00)"}));
}

TEST(GradeLines, WhyAGoalIsMissedByNumberAndByCheck) {
    const std::vector<std::string> why = texts(gradeLines(judgedLab()), PanelLine::Why);
    ASSERT_GE(why.size(), 3u);
    EXPECT_EQ(why[0], "not met in torus_grazing/shade, sphere_grazing/shade");
    EXPECT_EQ(why[1], "not met in plane/shade");
    EXPECT_EQ(why[2], "waits on goals 2 and 3, not met");
    for (const std::string& w : why) EXPECT_EQ(w.find("Phong highlight"), std::string::npos) << w;
}

TEST(GradeLines, HowEachGoalWasJudged) {
    const std::vector<std::string> judged = texts(gradeLines(judgedLab()), PanelLine::Judged);
    EXPECT_EQ(
        judged,
        (std::vector<std::string>{
            "your own work for it is right; it fails in your whole shader because of another part",
            "judged on your own work for it, with your changes to phong.frag: main, code the starter gave "
            "that uses it",
            "its work is in main(), with the rest: it cannot be taken alone"}));
    // An older grade without the fields says nothing about it.
    grader::ReportLab old = judgedLab();
    for (grader::ReportGoal& g : old.goals) {
        g.judged.clear();
        g.judged_note.clear();
        g.whole_failing.clear();
    }
    EXPECT_TRUE(texts(gradeLines(old), PanelLine::Judged).empty());
}

TEST(GradeLines, FailingScenesWithTheirMessageAndHint) {
    const std::vector<PanelLine> lines = gradeLines(judgedLab());
    const std::vector<std::string> scenes = texts(lines, PanelLine::FailingScene);
    EXPECT_EQ(scenes, std::vector<std::string>{"FAIL scene torus_grazing"});
    for (const PanelLine& l : lines) {
        if (l.kind == PanelLine::FailingScene) {
            EXPECT_EQ(l.scene, "torus_grazing");
        }
    }
    EXPECT_EQ(
        texts(lines, PanelLine::Hint),
        std::vector<std::string>{
            "This looks like a known mistake: Blinn's half vector instead of Phong's mirror direction"});
}

TEST(GradeLines, ALabThatDoesNotBuildSaysWhyThereAreNoGoals) {
    grader::ReportLab lab;
    lab.status = "compile_error";
    lab.message = "phong.frag:21: missing `;`";
    const std::vector<std::string> notes = texts(gradeLines(lab), PanelLine::Note);
    ASSERT_EQ(notes.size(), 1u);
    EXPECT_EQ(notes[0],
              "compile_error: phong.frag:21: missing `;`. No goal can be judged until your shaders build.");
}

}  // namespace
