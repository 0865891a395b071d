// The plan's choices on their own, without grading: which labs a submission hands in, which are the
// class's, and what the progress line names while workers run.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include "batch_test_support.h"
#include "shaderlab/batch/plan.h"
#include "shaderlab/batch/results.h"
#include "shaderlab/batch/schedule.h"

namespace fs = std::filesystem;
using namespace shaderlab;
using namespace shaderlab::batch_testing;

namespace {

// A course of three labs (only their lab ids and student files matter here).
std::vector<batch::LabPlan> threeLabs() {
    std::vector<batch::LabPlan> labs(3);
    labs[0].id = "01-a";
    labs[0].student_files = {"a.vert", "a.frag"};
    labs[1].id = "02-b";
    labs[1].student_files = {"b.frag"};
    labs[2].id = "03-c";
    labs[2].student_files = {"c.frag"};
    return labs;
}

TEST(BatchPlan, EachSubmissionIsGradedInTheLabsItHandsIn) {
    const fs::path dir = scratch("handed_in");
    writeFile(dir / "subs" / "ann" / "01-a" / "a.frag", "mine");
    writeFile(dir / "subs" / "ann" / "02-b" / "B.FRAG", "mine, named in capitals");
    writeFile(dir / "subs" / "bo" / "01-a" / "a.vert", "mine");
    fs::create_directories(dir / "subs" / "bo" / "02-b");                     // empty
    writeFile(dir / "subs" / "bo" / "03-c" / "notes.txt", "not a lab file");  // none of its files
    batch::BatchSettings settings;
    settings.tool_version = "test";
    settings.all_lab_ids = {"01-a", "02-b", "03-c"};
    batch::ResultsFolder folder;
    std::string error;
    ASSERT_TRUE(batch::openResultsFolder((dir / "out").string(), "", &folder, &error)) << error;
    std::vector<batch::SubmissionSource> sources;
    ASSERT_TRUE(
        batch::selectSubmissions((dir / "subs").string(), (dir / "out").string(), 1, 1, &sources, &error));
    batch::Plan plan;
    plan.labs = threeLabs();
    batch::surveySubmissions(settings, folder, sources, &plan);
    ASSERT_EQ(plan.subs.size(), 2u);
    EXPECT_EQ(plan.subs[0].handed_in, (std::vector<std::string>{"01-a", "02-b"}));
    EXPECT_EQ(plan.subs[1].handed_in, std::vector<std::string>{"01-a"});
    ASSERT_EQ(plan.subs[1].lab_notes.size(), 2u);
    EXPECT_EQ(plan.subs[1].lab_notes[0].second,
              "not handed in: 02-b/ holds none of the lab's files (b.frag); it holds nothing");
    EXPECT_EQ(plan.subs[1].lab_notes[1].second,
              "not handed in: 03-c/ holds none of the lab's files (c.frag); it holds notes.txt");
    // The class's labs: those someone handed in, in the course's order.
    batch::chooseClassLabs(settings, &plan);
    ASSERT_EQ(plan.labs.size(), 2u);
    EXPECT_EQ(plan.labs[0].id, "01-a");
    EXPECT_EQ(plan.labs[1].id, "02-b");
    // Named labs stay, handed in or not.
    batch::Plan named;
    named.labs = threeLabs();
    settings.labs_named = true;
    batch::surveySubmissions(settings, folder, sources, &named);
    batch::chooseClassLabs(settings, &named);
    EXPECT_EQ(named.labs.size(), 3u);
}

TEST(BatchPlan, TheProgressLineNamesTheSubmissionsBeingGraded) {
    batch::Plan plan;
    plan.subs.resize(3);
    plan.subs[0].source.student = "ann";
    plan.subs[1].source.student = "bo";
    plan.subs[2].source.student = "cy";
    const auto now = std::chrono::steady_clock::now();
    EXPECT_EQ(batch::describeRunning(plan, now), "");
    auto job = [&](const std::string& lab, std::size_t sub, pid_t pid, double seconds, bool done) {
        batch::Job j;
        j.lab = lab;
        j.waiting = {sub};
        j.pid = pid;
        j.done = done;
        j.started = now - std::chrono::milliseconds(static_cast<long>(seconds * 1000));
        plan.jobs.push_back(j);
    };
    job("01-a", 0, 100, 1.0, true);    // ann's first lab: finished
    job("02-b", 0, 101, 42.0, false);  // ann's second: still drawing after 42 s
    job("01-a", 1, 102, 2.0, false);   // bo's
    job("02-b", 1, 102, 2.0, false);   // bo's second lab, the same worker
    EXPECT_EQ(batch::describeRunning(plan, now), "grading ann (02-b), bo (01-a); ann (02-b) for 42 s");
    job("01-a", 2, 103, 0.5, false);
    EXPECT_EQ(batch::describeRunning(plan, now), "grading ann (02-b), bo (01-a) +1; ann (02-b) for 42 s");
}

}  // namespace
