// Checks that the committed scenes in labs/scenes/ are exactly what shaderlab_make_scenes writes
// today: it runs the generator into a scratch folder and compares every file byte for byte, in
// both directions (a scene the tool no longer writes is stale too). It fails with instructions
// to run scripts/regenerate_scenes.sh. It does not check what the scenes contain; the Gltf*
// tests load them.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>

namespace fs = std::filesystem;

namespace {

const char* const kHowToFix = "labs/scenes/ is stale: run scripts/regenerate_scenes.sh and commit the result";

std::string readBytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// The files the generator owns; anything else in labs/scenes/ (a README, say) is not compared.
std::set<std::string> sceneFiles(const fs::path& dir) {
    std::set<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir)) {
        const auto ext = entry.path().extension();
        if (entry.is_regular_file() && (ext == ".gltf" || ext == ".glb" || ext == ".bin")) {
            names.insert(entry.path().filename().string());
        }
    }
    return names;
}

std::string shellQuote(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

TEST(ScenesFresh, CommittedScenesMatchTheGenerator) {
    const fs::path committed = fs::path(SHADERLAB_SOURCE_DIR) / "labs" / "scenes";
    const fs::path fresh =
        fs::temp_directory_path() / ("shaderlab_scenes_fresh_" + std::to_string(::getpid()));
    fs::remove_all(fresh);

    const fs::path log = fresh.string() + ".log";
    const std::string command = shellQuote(SHADERLAB_MAKE_SCENES) + " " + shellQuote(fresh.string()) + " > " +
                                shellQuote(log.string()) + " 2>&1";
    const int status = std::system(command.c_str());
    const std::string output = readBytes(log);
    fs::remove(log);
    ASSERT_EQ(status, 0) << "shaderlab_make_scenes failed: " << command << "\n" << output;

    const std::set<std::string> generated = sceneFiles(fresh);
    ASSERT_FALSE(generated.empty()) << "the generator wrote nothing into " << fresh;
    ASSERT_TRUE(fs::is_directory(committed)) << kHowToFix;
    const std::set<std::string> present = sceneFiles(committed);

    for (const std::string& name : generated) {
        if (present.count(name) == 0) {
            ADD_FAILURE() << name << " is generated but missing from labs/scenes/. " << kHowToFix;
            continue;
        }
        EXPECT_TRUE(readBytes(fresh / name) == readBytes(committed / name))
            << name << " differs from what shaderlab_make_scenes writes. " << kHowToFix;
    }
    for (const std::string& name : present) {
        EXPECT_TRUE(generated.count(name) != 0)
            << name << " is in labs/scenes/ but the generator no longer writes it. " << kHowToFix;
    }
    fs::remove_all(fresh);
}

}  // namespace
