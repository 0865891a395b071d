// Pass isolation end to end (lab.json "isolate", docs/grading.md "Pass isolation"): a three-pass
// chain where the second pass reads the first's graded image and the third the second's. A wrong
// first pass costs the first goal only when the second is isolated (and all three without it),
// the third being judged with the second on the reference's first image; a wrong second pass
// costs its own goal (and the third's, which rests on it); the verdicts are the same against the
// rendered reference and against the goldens.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
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

// first.frag draws a gradient with values above 1 (compared in the hdr range, stored as .hdr);
// second.frag scales what it reads.
const char* const kFirst = R"(#version 330 core
in vec2 v_uv;
out vec4 frag_color;
void main() { frag_color = vec4(2.0 * v_uv.x, FIRST_G, 0.5, 1.0); }
)";
const char* const kSecond = R"(#version 330 core
in vec2 v_uv;
uniform sampler2D u_image;
out vec4 frag_color;
void main() { frag_color = vec4(texture(u_image, v_uv).rgb * SECOND_SCALE, 1.0); }
)";

std::string replaced(std::string text, const std::string& what, const std::string& with) {
    return text.replace(text.find(what), what.size(), with);
}

class PassIsolation : public ::testing::Test {
  protected:
    void SetUp() override {
        tmp_ = fs::temp_directory_path() / ("shaderlab_isolation_" + std::to_string(::getpid()));
        fs::remove_all(tmp_);
        fs::create_directories(tmp_ / "labs" / "iso");
        fs::copy(kRoot / "labs" / "shared", tmp_ / "labs" / "shared", fs::copy_options::recursive);
        writeLab(true);
        writeSubmission("reference", "0.25", "0.5");
        writeSubmission("wrong_first", "0.75", "0.5");
        writeSubmission("wrong_second", "0.25", "0.8");
        writeSubmission("labs", "0.0", "0.0");  // the lab's starter
    }
    void TearDown() override { fs::remove_all(tmp_); }

    void writeLab(bool isolate) {
        json lab = {{"schema", 2},
                    {"id", "iso"},
                    {"title", "Two passes"},
                    {"resolution", {32, 24}},
                    {"student_files", {"first.frag", "second.frag", "third.frag"}},
                    {"goals",
                     {{{"id", "first"}, {"title", "The first pass"}, {"points", 1}, {"passes", {"first"}}},
                      {{"id", "second"}, {"title", "The second pass"}, {"points", 1}, {"passes", {"second"}}},
                      {{"id", "third"},
                       {"title", "The third pass"},
                       {"points", 1},
                       {"passes", {"third"}},
                       {"depends_on", {"second"}}}}},
                    {"passes",
                     {{{"name", "first"},
                       {"program", {{"vertex", "shared/fullscreen.vert"}, {"fragment", "first.frag"}}},
                       {"draw", "fullscreen"},
                       {"target", {{"format", "rgba32f"}, {"depth", "none"}}},
                       {"graded", true}},
                      {{"name", "second"},
                       {"program", {{"vertex", "shared/fullscreen.vert"}, {"fragment", "second.frag"}}},
                       {"draw", "fullscreen"},
                       {"target", {{"format", "rgba32f"}, {"depth", "none"}}},
                       {"inputs", {{"u_image", "first"}}},
                       {"graded", true}},
                      {{"name", "third"},
                       {"program", {{"vertex", "shared/fullscreen.vert"}, {"fragment", "third.frag"}}},
                       {"draw", "fullscreen"},
                       {"target", {{"format", "rgba32f"}, {"depth", "none"}}},
                       {"inputs", {{"u_image", "second"}}}}}},
                    {"scenes", {{{"name", "flat"}}}}};
        if (isolate) lab["passes"][1]["isolate"] = true;
        std::ofstream(tmp_ / "labs" / "iso" / "lab.json") << lab.dump(2);
    }
    void writeSubmission(const std::string& name, const std::string& g, const std::string& scale) {
        const fs::path dir = tmp_ / name / "iso";
        fs::create_directories(dir);
        std::ofstream(dir / "first.frag") << replaced(kFirst, "FIRST_G", g);
        std::ofstream(dir / "second.frag") << replaced(kSecond, "SECOND_SCALE", scale);
        std::ofstream(dir / "third.frag") << replaced(kSecond, "SECOND_SCALE", "vec3(1.0, 0.5, 2.0)");
    }
    // The lab's report for a submission: against the rendered reference, or the goldens.
    json grade(const std::string& name, bool goldens) {
        const fs::path out = tmp_ / "out" / (name + (goldens ? "_goldens" : "_reference"));
        const std::string cmd =
            std::string(SHADERLAB_CLI) + " grade " + (tmp_ / name).string() + " --labs " +
            (tmp_ / "labs").string() +
            (goldens ? std::string(" --no-reference") : " --reference " + (tmp_ / "reference").string()) +
            " --out " + out.string();
        output_ = run(cmd);
        const json report = json::parse(std::ifstream(out / "report.json"), nullptr, false);
        return report.is_object() ? report["labs"][0] : json();
    }
    static bool met(const json& lab, const std::string& goal) {
        for (const json& g : lab["goals"])
            if (g["id"] == goal) return g["met"].get<bool>();
        return false;
    }
    static const json& secondPass(const json& lab) { return lab["scenes"][0]["passes"][1]; }

    fs::path tmp_;
    std::string output_;
};

TEST_F(PassIsolation, AWrongFirstPassCostsItsOwnGoalOnly) {
    for (const bool goldens : {false, true}) {
        if (goldens) {
            output_ = run(std::string(SHADERLAB_CLI) + " goldens --no-hints --labs " +
                          (tmp_ / "labs").string() + " --reference " + (tmp_ / "reference").string());
            ASSERT_TRUE(fs::exists(tmp_ / "labs" / "iso" / "golden" / "flat.first.hdr")) << output_;
        }
        const json lab = grade("wrong_first", goldens);
        ASSERT_TRUE(lab.is_object()) << output_;
        EXPECT_EQ(lab["status"], "failed") << output_;
        EXPECT_FALSE(met(lab, "first")) << output_;
        EXPECT_TRUE(met(lab, "second")) << output_;
        EXPECT_TRUE(met(lab, "third")) << output_;  // judged with the second on the reference's input
        EXPECT_DOUBLE_EQ(lab["score"].get<double>(), 2.0);
        EXPECT_TRUE(lab["scenes"][0]["passes"][2]["on_reference_inputs"]["passed"].get<bool>());
        // The pipeline as it is still differs, and the report says the pass is right alone.
        const json& second = secondPass(lab);
        EXPECT_FALSE(second["passed"].get<bool>());
        ASSERT_TRUE(second["on_reference_inputs"].is_object()) << second.dump();
        EXPECT_TRUE(second["on_reference_inputs"]["passed"].get<bool>());
        const json& scene = lab["scenes"][0];
        EXPECT_EQ(scene["first_failing_pass"], "first");
        EXPECT_NE(scene["message"].get<std::string>().find("differ only because of what they read"),
                  std::string::npos)
            << scene["message"];
    }
}

TEST_F(PassIsolation, AWrongSecondPassCostsItsOwnGoal) {
    const json lab = grade("wrong_second", false);
    ASSERT_TRUE(lab.is_object()) << output_;
    EXPECT_TRUE(met(lab, "first")) << output_;
    EXPECT_FALSE(met(lab, "second")) << output_;
    EXPECT_FALSE(met(lab, "third")) << output_;  // it reads the wrong second image, and rests on it
    EXPECT_FALSE(secondPass(lab)["on_reference_inputs"]["passed"].get<bool>());
    EXPECT_EQ(lab["scenes"][0]["first_failing_pass"], "second");
}

TEST_F(PassIsolation, WithoutIsolationAWrongFirstPassCostsEveryGoalAndACorrectOneIsNotRenderedAgain) {
    const json right = grade("reference", false);
    ASSERT_TRUE(right.is_object()) << output_;
    EXPECT_EQ(right["status"], "passed") << output_;
    EXPECT_TRUE(secondPass(right)["on_reference_inputs"].is_null());  // a passing scene: no second render
    writeLab(false);
    const json lab = grade("wrong_first", false);
    ASSERT_TRUE(lab.is_object()) << output_;
    EXPECT_FALSE(met(lab, "first"));
    EXPECT_FALSE(met(lab, "second"));
    EXPECT_TRUE(secondPass(lab)["on_reference_inputs"].is_null());
}

TEST_F(PassIsolation, AGoalJudgedOnThePipelineIsNotMetWhenWhatItReadsIsWrong) {
    json lab = json::parse(std::ifstream(tmp_ / "labs" / "iso" / "lab.json"));
    lab["goals"][1]["pipeline"] = true;
    std::ofstream(tmp_ / "labs" / "iso" / "lab.json") << lab.dump(2);
    const json report = grade("wrong_first", false);
    ASSERT_TRUE(report.is_object()) << output_;
    EXPECT_FALSE(met(report, "second")) << output_;
    // The pass was still judged on the reference's inputs, and the report shows it.
    EXPECT_TRUE(secondPass(report)["on_reference_inputs"]["passed"].get<bool>());
}

}  // namespace
