// One scene whose file does not load must not lose the lab (docs/scenes.md): graded through the
// `shaderlab grade` program, the lab's other scene is rendered and passes, the broken one is
// reported as failed with the loader's reason, and the loader's warnings reach the output.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

std::string run(const std::string& args, int* exit_code) {
    std::string out;
    FILE* pipe = popen((std::string(SHADERLAB_CLI) + " " + args + " 2>&1").c_str(), "r");
    if (!pipe) return out;
    char buf[4096];
    while (std::fgets(buf, sizeof buf, pipe)) out += buf;
    const int status = pclose(pipe);
    *exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return out;
}

TEST(GltfSceneFailure, OtherScenesAreGradedAndTheReportSaysWhichFailedAndWhy) {
    const fs::path root =
        fs::temp_directory_path() / ("shaderlab_scene_failure_" + std::to_string(::getpid()));
    fs::remove_all(root);
    const fs::path data = fs::path(SHADERLAB_SOURCE_DIR) / "tests/data/multipass";
    const fs::path labs = root / "labs";
    fs::create_directories(labs / "scenes");
    fs::copy(data / "labs/90-two-pass", labs / "90-two-pass", fs::copy_options::recursive);
    for (const char* f : {"torus.gltf", "torus.bin"})
        fs::copy_file(fs::path(SHADERLAB_SOURCE_DIR) / "labs/scenes" / f, labs / "scenes" / f);
    for (const char* f : {"basisu_textures.gltf", "strip_fan_lines_points.gltf"})
        fs::copy_file(fs::path(SHADERLAB_TEST_DATA) / "gltf_realworld" / f, labs / "scenes" / f);
    json lab = json::parse(std::ifstream(labs / "90-two-pass/lab.json"));
    lab["scenes"].push_back({{"name", "broken"}, {"file", "scenes/basisu_textures.gltf"}});
    lab["scenes"].push_back({{"name", "lines"}, {"file", "scenes/strip_fan_lines_points.gltf"}});
    std::ofstream(labs / "90-two-pass/lab.json") << lab.dump(2);

    int code = -1;
    const std::string output =
        run("grade " + (data / "reference").string() + " --labs " + labs.string() + " --reference " +
                (data / "reference").string() + " --out " + (root / "out").string(),
            &code);
    EXPECT_EQ(code, 1) << output;  // the lab is not passed while one of its scenes cannot be drawn
    const json report = json::parse(std::ifstream(root / "out/report.json"), nullptr, false);
    ASSERT_TRUE(report.is_object()) << output;
    const json& scenes = report["labs"][0]["scenes"];
    ASSERT_EQ(scenes.size(), 3u) << report.dump(2);
    EXPECT_EQ(scenes[0]["name"], "torus");
    EXPECT_EQ(scenes[0]["status"], "passed") << scenes[0].dump(2);
    EXPECT_EQ(scenes[1]["name"], "broken");
    EXPECT_EQ(scenes[1]["status"], "failed");
    const std::string message = scenes[1]["message"];
    EXPECT_NE(message.find("did not load"), std::string::npos) << message;
    EXPECT_NE(message.find("not of the submission"), std::string::npos) << message;
    EXPECT_NE(message.find("requires extension 'KHR_texture_basisu'"), std::string::npos) << message;
    EXPECT_EQ(scenes[2]["status"], "passed") << scenes[2].dump(2);
    const std::string lab_message = report["labs"][0]["message"];
    EXPECT_NE(lab_message.find("scene 'broken' did not load"), std::string::npos) << lab_message;
    // The warnings of the scene that loaded reach the person running the grader.
    EXPECT_NE(output.find("mode 2 (LINE_LOOP) skipped"), std::string::npos) << output;
    fs::remove_all(root);
}

}  // namespace
