// The path resolver refuses what an untrusted submission could use to read outside its folder.
#include "shaderlab/base/paths.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;

namespace {

class PathsTest : public ::testing::Test {
  protected:
    void SetUp() override {
        root_ = fs::temp_directory_path() /
                ("shaderlab_paths_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
                 "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(root_);
        fs::create_directories(root_ / "sub" / "01-phong");
        std::ofstream(root_ / "sub" / "01-phong" / "phong.frag") << "void main() {}\n";
        std::ofstream(root_ / "secret.txt") << "top secret\n";
    }
    void TearDown() override { fs::remove_all(root_); }
    fs::path root_;
};

TEST_F(PathsTest, ResolvesAFileInsideTheFolder) {
    const auto r = shaderlab::resolveInside((root_ / "sub").string(), "01-phong/phong.frag");
    ASSERT_TRUE(r.ok) << r.error;
    EXPECT_EQ(fs::path(r.path).filename(), "phong.frag");
}

TEST_F(PathsTest, RefusesDotDotEscape) {
    const auto r = shaderlab::resolveInside((root_ / "sub").string(), "../secret.txt");
    EXPECT_FALSE(r.ok);
    EXPECT_NE(r.error.find("outside"), std::string::npos) << r.error;
}

TEST_F(PathsTest, RefusesSymlinkPointingOutside) {
    fs::create_symlink(root_ / "secret.txt", root_ / "sub" / "01-phong" / "phong.vert");
    const auto r = shaderlab::resolveInside((root_ / "sub").string(), "01-phong/phong.vert");
    EXPECT_FALSE(r.ok);
    EXPECT_NE(r.error.find("phong.vert"), std::string::npos) << r.error;
}

TEST_F(PathsTest, RefusesAbsolutePathAndMissingFile) {
    EXPECT_FALSE(shaderlab::resolveInside(root_.string(), (root_ / "secret.txt").string()).ok);
    const auto r = shaderlab::resolveInside(root_.string(), "nope.frag");
    EXPECT_FALSE(r.ok);
    EXPECT_NE(r.error.find("not found"), std::string::npos) << r.error;
}

TEST_F(PathsTest, RefusesOversizedFile) {
    std::ofstream(root_ / "sub" / "big.frag") << std::string(4096, 'x');
    const auto t = shaderlab::readFileInside((root_ / "sub").string(), "big.frag", 1024);
    EXPECT_FALSE(t.ok);
    EXPECT_NE(t.error.find("limit"), std::string::npos) << t.error;
}

}  // namespace
