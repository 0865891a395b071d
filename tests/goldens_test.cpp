// The goldens stored in labs/*/golden/ are what the reference solutions render today. When this
// fails, run `build/framework/shaderlab goldens` and commit the result (never edit them by hand).
// On a renderer other than the one that drew them, "today" means within the grading tolerance.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

std::set<std::string> filesIn(const fs::path& dir) {
    std::set<std::string> names;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir, ec)) names.insert(e.path().filename().string());
    return names;
}

// Made by the renderer that drew the stored goldens (golden/renderer.txt), they must be equal to
// the bit. Made by another (a newer Mesa or LLVM), they must agree within the grading tolerance:
// the reference solutions score full marks against the stored goldens.
TEST(Goldens, UpToDate) {
    // Per process: several checkouts may run this test at once.
    const fs::path fresh =
        fs::temp_directory_path() / ("shaderlab_goldens_fresh_" + std::to_string(getpid()));
    fs::remove_all(fresh);
    const std::string cmd =
        std::string(SHADERLAB_CLI) + " goldens --no-hints --into " + fresh.string() + " > /dev/null";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
    const fs::path source(SHADERLAB_SOURCE_DIR);
    const fs::path labs = source / "labs";
    int compared = 0;
    std::vector<std::string> other_renderer;
    for (const auto& lab : fs::directory_iterator(fresh)) {
        const fs::path stored = labs / lab.path().filename() / "golden";
        const fs::path made = lab.path() / "golden";
        EXPECT_EQ(filesIn(stored), filesIn(made))
            << stored << " lists other files than a fresh render: run `shaderlab goldens`";
        const std::string stored_renderer = slurp(stored / "renderer.txt");
        const std::string renderer = slurp(made / "renderer.txt");
        EXPECT_FALSE(renderer.empty()) << made / "renderer.txt";
        if (!stored_renderer.empty() && stored_renderer != renderer) {
            other_renderer.push_back(lab.path().filename().string());
            std::printf("%s: goldens drawn by %s compared within the grading tolerance on %s",
                        other_renderer.back().c_str(), stored_renderer.c_str(), renderer.c_str());
            continue;
        }
        for (const std::string& name : filesIn(made)) {
            EXPECT_TRUE(slurp(stored / name) == slurp(made / name))
                << (stored / name) << " is stale: run `build/framework/shaderlab goldens` and commit";
            ++compared;
        }
    }
    for (const std::string& id : other_renderer) {
        const fs::path out = fresh / ("grade-" + id);
        const std::string grade = std::string(SHADERLAB_CLI) + " grade " +
                                  (source / "reference_solutions").string() + " --no-reference --labs " +
                                  labs.string() + " --lab " + id + " --out " + out.string() + " > /dev/null";
        EXPECT_EQ(std::system(grade.c_str()), 0)
            << id << ": the reference solution does not score full marks against the stored goldens here";
        ++compared;
    }
    EXPECT_GT(compared, 0);
    fs::remove_all(fresh);
}

}  // namespace
