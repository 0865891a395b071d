// A goal that rests on others (lab.json "depends_on") on a real lab: 02-toon's "together" goal,
// without the work it is judged on (so on the whole shaders), declared to rest on the ramp,
// highlight and edge goals, graded for a mistake that only the edges
// show. The teapot goal is then not met because of the edges, and says so, in report.json and in
// the terminal; nothing else changes.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_run.h"

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

const fs::path kRoot = SHADERLAB_SOURCE_DIR;

std::string run(const std::string& cmd) { return shaderlab_test::runShell(cmd).output; }

const json* goal(const json& lab, const std::string& id) {
    for (const json& g : lab["goals"])
        if (g["id"] == id) return &g;
    return nullptr;
}

TEST(GoalDependencies, AGoalRestingOnAMissedOneIsNotMetBecauseOfIt) {
    const fs::path tmp = fs::temp_directory_path() / ("shaderlab_goal_deps_" + std::to_string(::getpid()));
    fs::remove_all(tmp);
    // The course's 02-toon with its goldens and hints, the teapot goal resting on the other three.
    const fs::path labs = tmp / "labs";
    fs::create_directories(labs);
    for (const char* part : {"02-toon", "scenes", "shared"})
        fs::copy(kRoot / "labs" / part, labs / part, fs::copy_options::recursive);
    json spec = json::parse(std::ifstream(labs / "02-toon" / "lab.json"));
    for (json& g : spec["goals"])
        if (g["id"] == "together") {
            // depends_on is for goals judged on the whole shaders (a goal with work rests on none).
            g.erase("work");
            g["depends_on"] = {"ramp", "highlight", "edges"};
        }
    std::ofstream(labs / "02-toon" / "lab.json") << spec.dump(2);
    // A mistake of the edges alone (n.l instead of n.v): the other goals stay met.
    const fs::path submission = tmp / "submission";
    fs::create_directories(submission / "02-toon");
    fs::copy(kRoot / "reference_solutions" / "02-toon", submission / "02-toon", fs::copy_options::recursive);
    fs::copy_file(kRoot / "tests" / "corpus" / "02-toon" / "edges-on-n-dot-l" / "toon_ramp.frag",
                  submission / "02-toon" / "toon_ramp.frag", fs::copy_options::overwrite_existing);

    const std::string out =
        run(std::string(SHADERLAB_CLI) + " check 02-toon --no-reference --labs " + labs.string() +
            " --submission " + submission.string() + " --out " + (tmp / "out").string());
    const json report = json::parse(std::ifstream(tmp / "out" / "report.json"), nullptr, false);
    ASSERT_TRUE(report.is_object()) << out;
    const json& lab = report["labs"][0];
    const json* together = goal(lab, "together");
    const json* edges = goal(lab, "edges");
    ASSERT_TRUE(together && edges) << out;
    EXPECT_FALSE((*edges)["met"].get<bool>()) << out;
    EXPECT_TRUE((*edges)["not_met_because"].empty());
    EXPECT_FALSE((*together)["met"].get<bool>()) << out;
    EXPECT_EQ((*together)["not_met_because"], json::array({"edges"})) << out;
    // Its points are lost with the edges', and the others' are kept.
    double expected = 0.0;
    for (const json& g : lab["goals"])
        if (g["id"] != "edges" && g["id"] != "together" && g["met"].get<bool>())
            expected += g["points"].get<double>();
    EXPECT_DOUBLE_EQ(lab["score"].get<double>(), expected);
    for (const char* kept : {"ramp", "highlight", "bands"})
        EXPECT_TRUE(goal(lab, kept) && (*goal(lab, kept))["met"].get<bool>()) << kept << "\n" << out;
    // The terminal says why, naming the goal it rests on.
    EXPECT_NE(out.find("not met because 'Darken silhouettes through the edge ramp"), std::string::npos)
        << out;
    fs::remove_all(tmp);
}

}  // namespace
