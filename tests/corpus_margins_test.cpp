// `shaderlab corpus --margins` on a real lab (08-gooch): margins.json holds every graded case and
// scene, its factors are the ones docs/grading.md ("Margins") defines, recomputed here from the
// case reports, corpus.json carries each case's margins, and raising lab.json
// `grading.margin_factor` flags verdicts without failing the run.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "cli_run.h"

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

const fs::path kRoot = SHADERLAB_SOURCE_DIR;
constexpr double kInf = std::numeric_limits<double>::infinity();

using shaderlab_test::CliRun;

CliRun run(const std::string& cmd) { return shaderlab_test::runShell(cmd); }

json readJson(const fs::path& file) {
    std::ifstream in(file);
    return json::parse(in, nullptr, false);
}

// A factor as margins.json writes it: null is infinite.
double factorOf(const json& v) { return v.is_number() ? v.get<double>() : kInf; }

// The factors of docs/grading.md, from a report's image: the smallest over its metrics.
double smallestFactor(const json& metrics, const json& thresholds) {
    double smallest = kInf;
    if (!metrics.value("identical", false))
        smallest = std::min(
            smallest,
            std::pow(10.0,
                     (metrics["psnr_db"].get<double>() - thresholds["psnr_min_db"].get<double>()) / 10.0));
    if (metrics["ssim"].is_number() && metrics["ssim"].get<double>() < 1.0)
        smallest = std::min(
            smallest, (1.0 - thresholds["ssim_min"].get<double>()) / (1.0 - metrics["ssim"].get<double>()));
    if (metrics["flip_mean"].get<double>() > 0.0)
        smallest = std::min(smallest,
                            thresholds["flip_mean_max"].get<double>() / metrics["flip_mean"].get<double>());
    if (metrics["mismatch_fraction"].get<double>() > 0.0)
        smallest = std::min(
            smallest, thresholds["mismatch_max"].get<double>() / metrics["mismatch_fraction"].get<double>());
    return smallest;
}

const json* findImage(const json& report, const std::string& scene, const std::string& image) {
    for (const json& s : report["labs"][0]["scenes"])
        if (s["name"] == scene)
            for (const json& p : s["passes"])
                if (p["name"] == image) return &p;
    return nullptr;
}

class CorpusMargins : public ::testing::Test {
  protected:
    void SetUp() override {
        tmp_ = fs::temp_directory_path() / ("shaderlab_corpus_margins_" + std::to_string(::getpid()));
        fs::remove_all(tmp_);
        fs::create_directories(tmp_);
    }
    void TearDown() override {
        if (!HasFailure()) fs::remove_all(tmp_);
    }
    fs::path tmp_;
};

TEST_F(CorpusMargins, EveryVerdictWithItsFactorAndThinOnesFlagged) {
    const fs::path out = tmp_ / "out";
    const CliRun first = run(std::string(SHADERLAB_CLI) + " corpus --lab 08-gooch --margins --labs " +
                             (kRoot / "labs").string() + " --out " + out.string());
    ASSERT_EQ(first.exit_code, 0) << first.output;
    EXPECT_NE(first.output.find("tightest pass:"), std::string::npos) << first.output;
    EXPECT_NE(first.output.find("tightest fail:"), std::string::npos) << first.output;
    const json margins = readJson(out / "08-gooch" / "margins.json");
    ASSERT_TRUE(margins.is_object()) << first.output;
    EXPECT_EQ(margins["margin_factor"], 2.0);  // the default

    // An entry for the reference and every graded case, with every scene of the lab.
    std::set<std::string> expected_cases = {"reference"};
    const json corpus_cases = readJson(kRoot / "tests" / "corpus" / "08-gooch" / "cases.json");
    for (const json& c : corpus_cases["cases"])
        if (c["kind"] != "broken") expected_cases.insert(c["name"].get<std::string>());
    std::set<std::string> scenes;
    const json lab_spec = readJson(kRoot / "labs" / "08-gooch" / "lab.json");
    for (const json& s : lab_spec["scenes"]) scenes.insert(s["name"].get<std::string>());
    std::set<std::string> cases;
    int recomputed = 0, failing = 0, passing = 0;
    for (const json& c : margins["cases"]) {
        cases.insert(c["case"].get<std::string>());
        std::set<std::string> seen;
        const json report = readJson(c["report"].get<std::string>());
        ASSERT_TRUE(report.is_object()) << c["report"];
        for (const json& im : c["images"]) {
            seen.insert(im["scene"].get<std::string>());
            if (im["identical"].get<bool>()) {
                EXPECT_TRUE(im["margin"].is_null()) << c["case"] << " " << im["scene"];
                continue;
            }
            // The factor recomputed from the report, by the formulas of docs/grading.md.
            const json* p = findImage(report, im["scene"], im["image"]);
            ASSERT_NE(p, nullptr) << c["case"] << " " << im["scene"];
            const bool isolated = im["judged_on"] == "reference_inputs";
            const json& judged = isolated ? (*p)["on_reference_inputs"] : *p;
            const bool passed = judged["passed"].get<bool>();
            EXPECT_EQ(im["verdict"], passed ? "passed" : "failed");
            const double smallest = smallestFactor(judged["metrics"], (*p)["thresholds"]);
            if (!passed && smallest >= 1.0) continue;  // failed on a check no threshold measures
            const double margin = passed ? smallest : 1.0 / smallest;
            if (std::isinf(margin)) {
                EXPECT_TRUE(im["margin"].is_null()) << c["case"] << " " << im["scene"];
            } else {
                EXPECT_NEAR(factorOf(im["margin"]), margin, 1e-6 * margin) << c["case"] << " " << im["scene"];
            }
            EXPECT_EQ(im["thin"].get<bool>(),
                      margin < 2.0 && im["expected"] == im["verdict"].get<std::string>().substr(0, 4))
                << c["case"] << " " << im["scene"] << " " << im.dump();
            ++recomputed;
            failing += !passed && im["expected"] == "fail";
            passing += passed;
        }
        EXPECT_EQ(seen, scenes) << c["case"];
    }
    EXPECT_EQ(cases, expected_cases);
    EXPECT_GT(failing, 0) << "no mistake's failing image was checked";
    EXPECT_GT(passing, 0) << "no passing image that differs from the reference was checked";
    EXPECT_GT(recomputed, 0);
    // The tightest failing verdict is a mistake's.
    ASSERT_TRUE(margins["tightest_fail"].is_object());
    for (const json& c : margins["cases"]) {
        if (c["case"] == margins["tightest_fail"]["case"]) {
            EXPECT_EQ(c["kind"], "mistake");
        }
    }

    // corpus.json: every graded case carries its margins.
    const json corpus = readJson(out / "corpus.json");
    for (const json& o : corpus) {
        if (expected_cases.count(o["case"].get<std::string>())) {
            EXPECT_TRUE(o.contains("margins") && o["margins"].contains("tightest_pass")) << o.dump();
        }
    }

    // The same lab asking for 1000x: verdicts are flagged, and the run still passes.
    const fs::path labs = tmp_ / "labs";
    fs::create_directories(labs);
    for (const char* part : {"08-gooch", "scenes", "shared"})
        fs::copy(kRoot / "labs" / part, labs / part, fs::copy_options::recursive);
    json spec = readJson(labs / "08-gooch" / "lab.json");
    spec["grading"]["margin_factor"] = 1000;
    std::ofstream(labs / "08-gooch" / "lab.json") << spec.dump(2);
    const fs::path strict_out = tmp_ / "strict";
    const CliRun strict =
        run(std::string(SHADERLAB_CLI) + " corpus --lab 08-gooch --margins --labs " + labs.string() +
            " --corpus " + (kRoot / "tests" / "corpus").string() + " --reference " +
            (kRoot / "reference_solutions").string() + " --out " + strict_out.string());
    EXPECT_EQ(strict.exit_code, 0) << "thin margins are advice, never a failure\n" << strict.output;
    EXPECT_NE(strict.output.find("THIN"), std::string::npos) << strict.output;
    EXPECT_NE(strict.output.find("hold by less than 1000x"), std::string::npos) << strict.output;
    const json strict_margins = readJson(strict_out / "08-gooch" / "margins.json");
    ASSERT_TRUE(strict_margins.is_object()) << strict.output;
    EXPECT_EQ(strict_margins["margin_factor"], 1000.0);
    EXPECT_GT(strict_margins["thin_images"].get<int>(), margins["thin_images"].get<int>());
}

}  // namespace
