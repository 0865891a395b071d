// End to end through the `shaderlab` program: exit codes of the commands, containment of student
// files, multi-pass reports and grading against the stored goldens. (The per-lab corpora of
// mistakes and alternatives are tests/corpus_test.cpp.)
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

struct CliRun {
    int exit_code = -1;
    std::string output;
};

// Runs the program with `args` from the working directory `cwd` (default: the test's own), with
// `env` ("NAME=value ...") before it.
CliRun runCli(const std::string& args, const std::string& cwd = "", const std::string& env = "") {
    CliRun r;
    const std::string cmd = (cwd.empty() ? std::string() : "cd '" + cwd + "' && ") + env +
                            std::string(SHADERLAB_CLI) + " " + args + " 2>&1";
    FILE* pipe = popen(cmd.c_str(), "r");
    if (!pipe) return r;
    char buf[4096];
    while (std::fgets(buf, sizeof buf, pipe)) r.output += buf;
    const int status = pclose(pipe);
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

json readJson(const fs::path& p) {
    std::ifstream in(p);
    return json::parse(in, nullptr, false);
}

fs::path scratch(const std::string& name) {
    const fs::path p = fs::temp_directory_path() / ("shaderlab_bundled_" + name);
    fs::remove_all(p);
    return p;
}

TEST(CliExitCodes, CheckPassesTheReferenceAndFailsTheStarter) {
    const fs::path out = scratch("check");
    const std::string ref = (fs::path(SHADERLAB_SOURCE_DIR) / "reference_solutions").string();
    const CliRun good = runCli("check 01-phong --submission " + ref + " --out " + out.string());
    EXPECT_EQ(good.exit_code, 0) << good.output;
    EXPECT_NE(good.output.find("PASS"), std::string::npos) << good.output;
    const std::string labs = (fs::path(SHADERLAB_SOURCE_DIR) / "labs").string();
    const CliRun bad =
        runCli("check 01-phong --submission " + labs + " --out " + out.string());  // the starter
    EXPECT_EQ(bad.exit_code, 1) << bad.output;
    EXPECT_NE(bad.output.find("FAIL"), std::string::npos) << bad.output;
    // Not a terminal: no colour escapes in the output.
    EXPECT_EQ(bad.output.find("\033["), std::string::npos);
}

// A course copied elsewhere grades its own files: `check` finds the course from the current
// folder upward (not from where the program was built), grades the student's work/ copy made by
// `start`, and names the folder and files it graded.
TEST(CliCheck, GradesTheCopiedCourseItRunsIn) {
    const fs::path course = scratch("course_copy");
    for (const char* folder :
         {"labs/01-phong", "labs/scenes", "labs/shared", "reference_solutions/01-phong"}) {
        fs::create_directories((course / folder).parent_path());
        fs::copy(fs::path(SHADERLAB_SOURCE_DIR) / folder, course / folder, fs::copy_options::recursive);
    }
    const fs::path deep = course / "work";
    fs::create_directories(deep);
    // Before `start` there is nothing to check, and check says what to do.
    const CliRun early = runCli("check 01-phong", deep.string());
    EXPECT_EQ(early.exit_code, 2) << early.output;
    EXPECT_NE(early.output.find("shaderlab start 01-phong"), std::string::npos) << early.output;

    const CliRun start = runCli("start 01-phong", deep.string());
    ASSERT_EQ(start.exit_code, 0) << start.output;
    ASSERT_TRUE(fs::is_regular_file(course / "work/01-phong/phong.frag"));
    // The starter code fails; solved in the copy, it passes; the source tree is never read.
    CliRun check = runCli("check 01-phong --out " + (course / "out").string(), deep.string());
    EXPECT_EQ(check.exit_code, 1) << check.output;
    for (const char* f : {"phong.vert", "phong.frag"})
        fs::copy_file(course / "reference_solutions/01-phong" / f, course / "work/01-phong" / f,
                      fs::copy_options::overwrite_existing);
    check = runCli("check 01-phong --out " + (course / "out").string(), deep.string());
    EXPECT_EQ(check.exit_code, 0) << check.output;
    EXPECT_NE(check.output.find((course / "work/01-phong").string()), std::string::npos) << check.output;
    EXPECT_NE(check.output.find("phong.vert, phong.frag"), std::string::npos) << check.output;
    const json report = readJson(course / "out/report.json");
    EXPECT_EQ(report["labs"][0]["folder"], (course / "work/01-phong").string());
    EXPECT_EQ(report["labs"][0]["files"], json::array({"phong.vert", "phong.frag"}));
    // `start` keeps work that is there.
    EXPECT_EQ(runCli("start 01-phong", deep.string()).exit_code, 2);
    EXPECT_EQ(runCli("start 01-phong --force", deep.string()).exit_code, 0);
}

TEST(CliCheck, OutsideACourseItSaysSo) {
    const fs::path empty = scratch("no_course");
    fs::create_directories(empty);
    const CliRun run = runCli("check 01-phong", empty.string());
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_NE(run.output.find("no course here"), std::string::npos) << run.output;
}

// A shader that never finishes is stopped after the short default and the message says where.
TEST(CliCheck, TimeoutNamesTheSceneAndPass) {
    const fs::path sub = scratch("slow_sub");
    fs::create_directories(sub / "01-phong");
    fs::copy_file(fs::path(SHADERLAB_SOURCE_DIR) / "reference_solutions/01-phong/phong.vert",
                  sub / "01-phong/phong.vert");
    fs::copy_file(fs::path(SHADERLAB_SOURCE_DIR) / "tests/corpus/01-phong/endless-loop/phong.frag",
                  sub / "01-phong/phong.frag");
    const CliRun run = runCli("check 01-phong --submission " + sub.string() + " --timeout 2 --out " +
                              scratch("slow_out").string());
    EXPECT_EQ(run.exit_code, 1) << run.output;
    EXPECT_NE(run.output.find("while drawing pass 'shade' of scene 'sphere'"), std::string::npos)
        << run.output;
}

TEST(CliExitCodes, BadArgumentsAndMissingInputsExitTwo) {
    EXPECT_EQ(runCli("check no-such-lab").exit_code, 2);
    EXPECT_EQ(runCli("grade /no/such/folder --out " + scratch("missing").string()).exit_code, 2);
    EXPECT_EQ(runCli("compare /no/such/a.png /no/such/b.png").exit_code, 2);
    EXPECT_NE(runCli("render").exit_code, 0);
}

TEST(CliExitCodes, SymlinkOutOfTheSubmissionIsRefused) {
    const fs::path sub = scratch("symlink");
    fs::create_directories(sub / "01-phong");
    fs::copy_file(fs::path(SHADERLAB_SOURCE_DIR) / "reference_solutions/01-phong/phong.vert",
                  sub / "01-phong/phong.vert");
    fs::create_symlink("/etc/passwd", sub / "01-phong/phong.frag");
    const fs::path out = scratch("symlink_out");
    const CliRun run = runCli("grade " + sub.string() + " --out " + out.string() + " --lab 01-phong");
    ASSERT_EQ(run.exit_code, 1) << run.output;
    const json report = readJson(out / "report.json");
    EXPECT_EQ(report["labs"][0]["status"], "missing");
    EXPECT_NE(report["labs"][0]["message"].get<std::string>().find("outside"), std::string::npos);
}

// A lab folder that is itself a symlink to the reference solution must not earn its points.
TEST(CliExitCodes, SymlinkedLabFolderIsRefused) {
    const fs::path sub = scratch("symlinked_lab");
    fs::create_directories(sub);
    fs::create_directory_symlink(fs::path(SHADERLAB_SOURCE_DIR) / "reference_solutions/01-phong",
                                 sub / "01-phong");
    const fs::path out = scratch("symlinked_lab_out");
    const CliRun run = runCli("grade " + sub.string() + " --out " + out.string() + " --lab 01-phong");
    ASSERT_EQ(run.exit_code, 1) << run.output;
    const json report = readJson(out / "report.json");
    EXPECT_EQ(report["labs"][0]["status"], "missing");
    EXPECT_DOUBLE_EQ(report["labs"][0]["score"].get<double>(), 0.0);
}

TEST(CliExitCodes, UnknownLabOrBadLimitsExitTwo) {
    const std::string ref = (fs::path(SHADERLAB_SOURCE_DIR) / "reference_solutions").string();
    const std::string out = scratch("unknown_lab").string();
    EXPECT_EQ(runCli("grade " + ref + " --out " + out + " --lab 99-nope").exit_code, 2);
    EXPECT_EQ(runCli("grade " + ref + " --out " + out + " --labs /no/such/labs").exit_code, 2);
    EXPECT_EQ(runCli("grade " + ref + " --out " + out + " --timeout 0").exit_code, 2);
    EXPECT_EQ(runCli("grade " + ref + " --out " + out + " --timeout -3").exit_code, 2);
}

// A two-pass lab (lit scene, then a fullscreen greyscale pass reading it): the report names the
// first pass that goes wrong, and writes pictures of the intermediate pass too.
TEST(CliMultiPass, ReportNamesTheFirstWrongPass) {
    const fs::path data = fs::path(SHADERLAB_SOURCE_DIR) / "tests/data/multipass";
    const fs::path labs = scratch("multipass_labs");
    fs::create_directories(labs);
    fs::copy(fs::path(SHADERLAB_SOURCE_DIR) / "labs/scenes", labs / "scenes", fs::copy_options::recursive);
    fs::copy(data / "labs/90-two-pass", labs / "90-two-pass", fs::copy_options::recursive);
    const struct {
        const char* submission;
        const char* status;
        const char* first_failing_pass;
    } cases[] = {{"reference", "passed", nullptr},
                 {"wrong-first-pass", "failed", "scene"},
                 {"wrong-second-pass", "failed", "grey"}};
    for (const auto& c : cases) {
        const fs::path out = scratch(std::string("multipass_") + c.submission);
        const CliRun run = runCli("grade " + (data / c.submission).string() + " --labs " + labs.string() +
                                  " --reference " + (data / "reference").string() + " --out " + out.string());
        ASSERT_EQ(run.exit_code, c.first_failing_pass ? 1 : 0) << run.output;
        const json report = readJson(out / "report.json");
        const json& scene = report["labs"][0]["scenes"][0];
        EXPECT_EQ(scene["status"], c.status) << c.submission << "\n" << scene.dump(2);
        if (c.first_failing_pass) {
            EXPECT_EQ(scene["first_failing_pass"], c.first_failing_pass) << c.submission;
            // Regression: the message mixed in the final pass's reasons and pixel positions. It
            // gives the first wrong pass's own reasons.
            std::string reasons;
            for (const json& p : scene["passes"])
                if (p["name"] == c.first_failing_pass)
                    for (const json& r : p["reasons"])
                        reasons += (reasons.empty() ? "" : "; ") + r.get<std::string>();
            const std::string message = scene["message"];
            EXPECT_NE(message.find(reasons), std::string::npos) << message << "\n" << reasons;
            if (std::string(c.first_failing_pass) == "scene") {
                EXPECT_EQ(message.rfind("first wrong pass: 'scene': ", 0), 0u) << message;
                for (const json& r : scene["passes"][1]["reasons"]) {
                    if (reasons.find(r.get<std::string>()) == std::string::npos) {
                        EXPECT_EQ(message.find(r.get<std::string>()), std::string::npos) << message;
                    }
                }
            }
        } else {
            EXPECT_TRUE(scene["first_failing_pass"].is_null()) << c.submission;
        }
        ASSERT_EQ(scene["passes"].size(), 2u);
        EXPECT_TRUE(fs::is_regular_file(out / scene["passes"][0]["images"]["student"].get<std::string>()));
    }
}

// A scene's thresholds reach the grader: loosened for the only scene, the wrong second pass
// passes; the lab's defaults fail it (above).
TEST(CliMultiPass, SceneThresholdsApplyToThatScenesImages) {
    const fs::path data = fs::path(SHADERLAB_SOURCE_DIR) / "tests/data/multipass";
    const fs::path labs = scratch("scene_thresholds_labs");
    fs::create_directories(labs);
    fs::copy(fs::path(SHADERLAB_SOURCE_DIR) / "labs/scenes", labs / "scenes", fs::copy_options::recursive);
    fs::copy(data / "labs/90-two-pass", labs / "90-two-pass", fs::copy_options::recursive);
    json lab = readJson(labs / "90-two-pass/lab.json");
    lab["scenes"][0]["thresholds"] = {
        {"psnr_min_db", 0}, {"ssim_min", 0}, {"flip_mean_max", 1}, {"mismatch_max", 1}};
    std::ofstream(labs / "90-two-pass/lab.json") << lab.dump(2);
    const fs::path out = scratch("scene_thresholds_out");
    const CliRun run = runCli("grade " + (data / "wrong-second-pass").string() + " --labs " + labs.string() +
                              " --reference " + (data / "reference").string() + " --out " + out.string());
    EXPECT_EQ(run.exit_code, 0) << run.output;
    EXPECT_EQ(readJson(out / "report.json")["labs"][0]["status"], "passed");
}

// Without the reference solution the stored goldens grade: the reference passes against them.
TEST(CliGoldens, ReferencePassesAgainstGoldens) {
    const fs::path out = scratch("goldens_grade");
    const std::string ref = (fs::path(SHADERLAB_SOURCE_DIR) / "reference_solutions").string();
    const CliRun run = runCli("grade " + ref + " --no-reference --out " + out.string() + " --lab 01-phong");
    ASSERT_EQ(run.exit_code, 0) << run.output;
    const json report = readJson(out / "report.json");
    EXPECT_EQ(report["labs"][0]["status"], "passed");
    EXPECT_EQ(report["labs"][0]["reference_source"], "goldens");
    const CliRun starter = runCli("grade " + (fs::path(SHADERLAB_SOURCE_DIR) / "labs").string() +
                                  " --no-reference --out " + out.string() + " --lab 01-phong");
    EXPECT_EQ(readJson(out / "report.json")["labs"][0]["status"], "failed") << starter.output;
}

TEST(CliCompare, JsonForIdenticalAndDifferentImages) {
    const fs::path out = scratch("compare");
    const std::string ref = (fs::path(SHADERLAB_SOURCE_DIR) / "reference_solutions").string();
    ASSERT_EQ(runCli("render " + ref + " --lab 01-phong --out " + out.string()).exit_code, 0);
    const std::string a = (out / "01-phong/sphere.png").string();
    const std::string b = (out / "01-phong/torus.png").string();
    const CliRun same = runCli("compare " + a + " " + a + " --json");
    ASSERT_EQ(same.exit_code, 0) << same.output;
    const json js = json::parse(same.output, nullptr, false);
    ASSERT_FALSE(js.is_discarded()) << same.output;
    EXPECT_TRUE(js["psnr_db"].is_null());
    EXPECT_TRUE(js["identical"].get<bool>());
    EXPECT_NEAR(js["ssim"].get<double>(), 1.0, 1e-6);
    EXPECT_DOUBLE_EQ(js["flip_mean"].get<double>(), 0.0);
    const CliRun diff = runCli("compare " + a + " " + b + " --json");
    const json jd = json::parse(diff.output, nullptr, false);
    ASSERT_FALSE(jd.is_discarded()) << diff.output;
    EXPECT_LT(jd["psnr_db"].get<double>(), 30.0);
    EXPECT_GT(jd["mismatch_fraction"].get<double>(), 0.01);
}

// `render --debug VIEW` needs no submission: one picture of the vertex data per scene of the lab,
// named <scene>.debug-<view>.png, and a line for each mesh the view has nothing to show of.
TEST(CliRenderDebug, OnePicturePerSceneWithoutASubmission) {
    const fs::path out = scratch("render_debug");
    const fs::path labs = fs::path(SHADERLAB_SOURCE_DIR) / "labs";
    const CliRun r =
        runCli("render --labs " + labs.string() + " --lab 01-phong --debug tangents --out " + out.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const json lab = readJson(labs / "01-phong" / "lab.json");
    ASSERT_TRUE(lab.contains("scenes")) << "01-phong's lab.json";
    for (const json& scene : lab["scenes"]) {
        const std::string name = scene["name"].get<std::string>();
        EXPECT_TRUE(fs::is_regular_file(out / "01-phong" / (name + ".debug-tangents.png"))) << name << "\n"
                                                                                            << r.output;
        EXPECT_FALSE(fs::exists(out / "01-phong" / (name + ".png"))) << "the lab's own picture is not drawn";
    }
    EXPECT_NE(
        r.output.find("01-phong: debug view: no tangents in scenes/sphere.gltf, mesh sphere: drawn grey"),
        std::string::npos)
        << r.output;

    const CliRun wrong =
        runCli("render --labs " + labs.string() + " --lab 01-phong --debug normal --out " + out.string());
    EXPECT_NE(wrong.exit_code, 0);
    EXPECT_NE(wrong.output.find("uv-checker"), std::string::npos) << "the views are listed\n" << wrong.output;
    const CliRun none = runCli("render --labs " + labs.string() + " --lab 01-phong --out " + out.string());
    EXPECT_EQ(none.exit_code, 2) << none.output;
    EXPECT_NE(none.output.find("needs a submission folder"), std::string::npos) << none.output;
}

}  // namespace

// Without OSMesa (Mesa 25.1 and later ship none) the default backend renders through EGL and says
// so in one line; naming OSMesa explicitly is then an error that names the library. The library is
// made unopenable with SHADERLAB_OSMESA_LIBRARY.
TEST(CliBackend, AutoFallsBackToEglWhereOSMesaCannotBeOpened) {
    const std::string no_osmesa = "SHADERLAB_OSMESA_LIBRARY=/nonexistent/libOSMesa.so.8 ";
    const CliRun fallback = runCli("info", "", no_osmesa);
    ASSERT_EQ(fallback.exit_code, 0) << fallback.output;
    EXPECT_NE(fallback.output.find("backend:  egl"), std::string::npos) << fallback.output;
    EXPECT_NE(fallback.output.find("cannot open /nonexistent/libOSMesa.so.8"), std::string::npos)
        << fallback.output;
    EXPECT_NE(fallback.output.find("rendering with EGL (surfaceless) instead"), std::string::npos)
        << fallback.output;

    const CliRun forced = runCli("info --backend osmesa", "", no_osmesa);
    EXPECT_EQ(forced.exit_code, 2) << forced.output;
    EXPECT_NE(forced.output.find("/nonexistent/libOSMesa.so.8"), std::string::npos) << forced.output;
}
