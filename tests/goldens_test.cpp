// The goldens stored in labs/*/golden/ are what the reference solutions render today. When this
// fails, run `build/framework/shaderlab goldens` and commit the result (never edit them by hand).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

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

TEST(Goldens, UpToDate) {
    // Per process: several checkouts may run this test at once.
    const fs::path fresh =
        fs::temp_directory_path() / ("shaderlab_goldens_fresh_" + std::to_string(getpid()));
    fs::remove_all(fresh);
    const std::string cmd =
        std::string(SHADERLAB_CLI) + " goldens --no-hints --into " + fresh.string() + " > /dev/null";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
    const fs::path labs = fs::path(SHADERLAB_SOURCE_DIR) / "labs";
    int compared = 0;
    for (const auto& lab : fs::directory_iterator(fresh)) {
        const fs::path stored = labs / lab.path().filename() / "golden";
        const fs::path made = lab.path() / "golden";
        EXPECT_EQ(filesIn(stored), filesIn(made))
            << stored << " lists other files than a fresh render: run `shaderlab goldens`";
        for (const std::string& name : filesIn(made)) {
            EXPECT_TRUE(slurp(stored / name) == slurp(made / name))
                << (stored / name) << " is stale: run `build/framework/shaderlab goldens` and commit";
            ++compared;
        }
    }
    EXPECT_GT(compared, 0);
    fs::remove_all(fresh);
}

}  // namespace
