// What the program says when a student or an instructor slips: a command or lab name one letter
// off gets the one meant, a comparison too small for SSIM says so, a lab whose only scene was
// refused is a failed render (exit 1), and `check` gives the known-mistake hint the report gives.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_run.h"
#include "grader/metrics/image.h"

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

const fs::path kRoot = SHADERLAB_SOURCE_DIR;

using CliResult = shaderlab_test::CliRun;

CliResult run(const std::string& args) {
    return shaderlab_test::runShell(std::string(SHADERLAB_CLI) + " " + args);
}

fs::path scratch(const std::string& name) {
    const fs::path p =
        fs::temp_directory_path() / ("shaderlab_messages_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(p);
    fs::create_directories(p);
    return p;
}

TEST(CliMessages, AMistypedCommandNamesTheOneMeant) {
    const CliResult r = run("chek 02-toon");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.output.find("there is no command 'chek' (did you mean \"check\"?)"), std::string::npos)
        << r.output;
    // A command kept off --help (the batch's worker) is still a command.
    EXPECT_EQ(run("batch-worker --help").exit_code, 0);
}

TEST(CliMessages, AMistypedLabNamesTheOneMeant) {
    const CliResult r = run("check 02-ton --submission " + (kRoot / "reference_solutions").string() +
                            " --labs " + (kRoot / "labs").string());
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.output.find("does not exist (did you mean \"02-toon\"?)"), std::string::npos) << r.output;
}

TEST(CliMessages, CompareSaysSsimIsUndefinedBelowItsWindow) {
    const fs::path dir = scratch("compare");
    grader::Image a(8, 8, 3, 0.25f), b(8, 8, 3, 0.5f);
    ASSERT_TRUE(grader::writePng(a, (dir / "a.png").string(), nullptr));
    ASSERT_TRUE(grader::writePng(b, (dir / "b.png").string(), nullptr));
    const CliResult text = run("compare " + (dir / "a.png").string() + " " + (dir / "b.png").string());
    EXPECT_EQ(text.exit_code, 0) << text.output;
    EXPECT_NE(text.output.find("SSIM      undefined"), std::string::npos) << text.output;
    const CliResult js =
        run("compare " + (dir / "a.png").string() + " " + (dir / "b.png").string() + " --json");
    const json j = json::parse(js.output, nullptr, false);
    ASSERT_TRUE(j.is_object()) << js.output;
    EXPECT_TRUE(j["ssim"].is_null()) << js.output;
    EXPECT_LT(j["psnr_db"].get<double>(), 20.0);
    fs::remove_all(dir);
}

TEST(CliMessages, RenderOfALabWhoseOnlySceneWasRefusedFails) {
    const fs::path root = scratch("refused");
    const fs::path data = kRoot / "tests/data/multipass";
    const fs::path labs = root / "labs";
    fs::create_directories(labs / "scenes");
    fs::copy(data / "labs/90-two-pass", labs / "90-two-pass", fs::copy_options::recursive);
    fs::copy_file(fs::path(SHADERLAB_TEST_DATA) / "gltf_realworld" / "basisu_textures.gltf",
                  labs / "scenes" / "basisu_textures.gltf");
    json lab = json::parse(std::ifstream(labs / "90-two-pass/lab.json"));
    lab["scenes"] = json::array({{{"name", "broken"}, {"file", "scenes/basisu_textures.gltf"}}});
    lab.erase("goals");
    std::ofstream(labs / "90-two-pass/lab.json") << lab.dump(2);
    const CliResult r = run("render " + (data / "reference").string() + " --labs " + labs.string() +
                            " --out " + (root / "out").string());
    EXPECT_EQ(r.exit_code, 1) << r.output;
    EXPECT_NE(r.output.find("scene broken was not rendered"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("KHR_texture_basisu"), std::string::npos) << r.output;
    fs::remove_all(root);
}

TEST(CliMessages, CheckGivesTheKnownMistakeHintOfTheReport) {
    const fs::path root = scratch("hint");
    fs::create_directories(root / "01-phong");
    for (const auto& e : fs::directory_iterator(kRoot / "reference_solutions/01-phong"))
        fs::copy_file(e.path(), root / "01-phong" / e.path().filename());
    fs::copy_file(kRoot / "tests/corpus/01-phong/blinn-phong/phong.frag", root / "01-phong/phong.frag",
                  fs::copy_options::overwrite_existing);
    const CliResult r = run("check 01-phong --no-reference --labs " + (kRoot / "labs").string() +
                            " --submission " + root.string() + " --out " + (root / "out").string());
    EXPECT_EQ(r.exit_code, 1) << r.output;
    const json report = json::parse(std::ifstream(root / "out/report.json"), nullptr, false);
    ASSERT_TRUE(report.is_object()) << r.output;
    std::string about;
    for (const json& s : report["labs"][0]["scenes"])
        if (s.value("hint", json()).is_object() && s["hint"].value("mistake", "") == "blinn-phong")
            about = s["hint"]["about"];
    ASSERT_FALSE(about.empty()) << report.dump(1).substr(0, 2000);
    EXPECT_NE(r.output.find("This looks like a known mistake:"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(about), std::string::npos) << r.output;
    fs::remove_all(root);
}

}  // namespace
