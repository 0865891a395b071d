// A student's file found by its case, read with the note, and problems said in the student's names.
#include "shaderlab/base/student_files.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;

namespace {

class StudentFilesTest : public ::testing::Test {
  protected:
    void SetUp() override {
        root_ = fs::temp_directory_path() / ("shaderlab_student_files_" + std::to_string(getpid()) + "_" +
                                             ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(root_);
        fs::create_directories(root_ / "01-phong");
    }
    void TearDown() override { fs::remove_all(root_); }
    void write(const std::string& relative, const std::string& text) {
        fs::create_directories((root_ / relative).parent_path());
        std::ofstream(root_ / relative) << text;
    }
    fs::path root_;
};

TEST_F(StudentFilesTest, AFileFoundByItsCaseIsReadWithANote) {
    write("01-phong/Phong.frag", "void main() {}\n");
    EXPECT_EQ(shaderlab::findIgnoringCase(root_.string(), "01-phong/phong.frag"), "01-phong/Phong.frag");
    std::string note;
    const shaderlab::FileText t =
        shaderlab::readStudentFile(root_.string(), "01-phong/phong.frag", "phong.frag", 1 << 20, &note);
    ASSERT_TRUE(t.ok) << t.error;
    EXPECT_EQ(t.text, "void main() {}\n");
    EXPECT_EQ(note, "found Phong.frag; the lab expects phong.frag");
    EXPECT_TRUE(shaderlab::isCaseNote(note));
    EXPECT_FALSE(shaderlab::isCaseNote("phong.frag: file not found"));
    // The folder too may differ in case.
    EXPECT_EQ(shaderlab::findIgnoringCase(root_.string(), "01-PHONG/PHONG.FRAG"), "01-phong/Phong.frag");
}

TEST_F(StudentFilesTest, TheExactNameNeedsNoNoteAndTwoCandidatesAreNone) {
    write("01-phong/phong.frag", "exact");
    write("01-phong/Phong.frag", "other");
    std::string note;
    const shaderlab::FileText t =
        shaderlab::readStudentFile(root_.string(), "01-phong/phong.frag", "phong.frag", 1 << 20, &note);
    ASSERT_TRUE(t.ok);
    EXPECT_EQ(t.text, "exact");
    EXPECT_TRUE(note.empty());
    EXPECT_EQ(shaderlab::findIgnoringCase(root_.string(), "01-phong/phong.frag"), "");
    write("01-phong/PHONG.VERT", "a");
    write("01-phong/Phong.Vert", "b");
    EXPECT_EQ(shaderlab::findIgnoringCase(root_.string(), "01-phong/phong.vert"), "") << "ambiguous";
}

TEST_F(StudentFilesTest, ProblemsNameTheFileAsTheStudentKnowsIt) {
    write("01-phong/notes.txt", "x");
    shaderlab::FileText t =
        shaderlab::readStudentFile(root_.string(), "01-phong/phong.frag", "phong.frag", 1 << 20);
    EXPECT_FALSE(t.ok);
    EXPECT_TRUE(t.missing);
    EXPECT_EQ(t.error, "phong.frag: file not found (its folder holds: notes.txt)");
    // A symlink out of the submission: refused, without saying where the submission lies.
    fs::create_symlink("/etc/passwd", root_ / "01-phong" / "phong.vert");
    t = shaderlab::readStudentFile(root_.string(), "01-phong/phong.vert", "phong.vert", 1 << 20);
    EXPECT_FALSE(t.ok);
    EXPECT_NE(t.error.find("phong.vert: resolves outside the submission"), std::string::npos) << t.error;
    EXPECT_EQ(t.error.find(root_.string()), std::string::npos) << t.error;
    // A lab folder that is a link out: nothing behind it is listed or found by its case.
    fs::create_directories(root_ / "elsewhere");
    fs::create_directories(root_ / "sub");
    std::ofstream(root_ / "elsewhere" / "Secret.frag") << "x";
    fs::create_directory_symlink(root_ / "elsewhere", root_ / "sub" / "02-toon");
    const std::string sub = (root_ / "sub").string();
    EXPECT_EQ(shaderlab::findIgnoringCase(sub, "02-toon/secret.frag"), "");
    t = shaderlab::readStudentFile(sub, "02-toon/toon.frag", "toon.frag", 1 << 20);
    EXPECT_EQ(t.error.find("Secret"), std::string::npos) << t.error;
    // A file found by its case is read inside the submission like any other.
    fs::create_symlink("/etc/passwd", root_ / "01-phong" / "Lit.frag");
    std::string note;
    t = shaderlab::readStudentFile(root_.string(), "01-phong/lit.frag", "lit.frag", 1 << 20, &note);
    EXPECT_FALSE(t.ok);
    EXPECT_EQ(t.text, "");
}

}  // namespace
