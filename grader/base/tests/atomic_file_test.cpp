// writeFileAtomically / AtomicFile / createFoldersInside: whole files or none, no temporary files
// left behind, planted symbolic links refused rather than written through.
#include "grader/base/atomic_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace grader {
namespace {

struct TempFolder {
    fs::path dir;
    TempFolder() {
        char tmpl[] = "/tmp/grader_atomic_XXXXXX";
        dir = mkdtemp(tmpl);
    }
    ~TempFolder() {
        std::error_code ec;
        fs::remove_all(dir, ec);
    }
};

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

int entries(const fs::path& dir) {
    int n = 0;
    for (const auto& e : fs::directory_iterator(dir)) n += e.path().empty() ? 0 : 1;
    return n;
}

TEST(AtomicFile, WritesAndReplacesWholeFilesWithoutLeftovers) {
    TempFolder t;
    const std::string path = (t.dir / "report.json").string();
    std::string error;
    ASSERT_TRUE(writeFileAtomically(path, "first", &error)) << error;
    EXPECT_EQ(slurp(path), "first");
    ASSERT_TRUE(writeFileAtomically(path, std::string(100000, 'x'), &error)) << error;
    EXPECT_EQ(slurp(path), std::string(100000, 'x'));
    ASSERT_TRUE(writeFileAtomically(path, "", &error, false)) << error;
    EXPECT_EQ(slurp(path), "");
    EXPECT_EQ(entries(t.dir), 1);  // no temporary file left
    EXPECT_EQ(fs::status(path).permissions() & fs::perms::others_read, fs::perms::others_read);
}

TEST(AtomicFile, RefusesALinkPlantedAtTheFinalName) {
    TempFolder t;
    const fs::path outside = t.dir / "outside.txt";
    std::ofstream(outside) << "precious";
    fs::create_directory(t.dir / "out");
    fs::create_symlink(outside, t.dir / "out" / "report.json");
    std::string error;
    EXPECT_FALSE(writeFileAtomically((t.dir / "out" / "report.json").string(), "evil", &error));
    EXPECT_NE(error.find("symbolic link"), std::string::npos) << error;
    EXPECT_EQ(slurp(outside), "precious");
    EXPECT_EQ(entries(t.dir / "out"), 1);
}

TEST(AtomicFile, RefusesAFolderAtTheFinalName) {
    TempFolder t;
    fs::create_directory(t.dir / "report.html");
    std::string error;
    EXPECT_FALSE(writeFileAtomically((t.dir / "report.html").string(), "x", &error));
    EXPECT_NE(error.find("not a regular file"), std::string::npos) << error;
}

TEST(AtomicFile, UncommittedFileLeavesNothing) {
    TempFolder t;
    std::string error;
    {
        AtomicFile f;
        ASSERT_TRUE(f.open((t.dir / "a.png").string(), &error)) << error;
        std::fputs("half a picture", f.stream());
    }
    EXPECT_EQ(entries(t.dir), 0);
}

TEST(AtomicFile, ReportsAFolderThatCannotTakeTheFile) {
    TempFolder t;
    std::string error;
    EXPECT_FALSE(writeFileAtomically((t.dir / "absent" / "x.json").string(), "x", &error));
    EXPECT_NE(error.find("absent/x.json"), std::string::npos) << error;
    EXPECT_NE(error.find("temporary file"), std::string::npos) << error;
}

TEST(AtomicFile, CreateFoldersInsideRefusesLinksOnTheWay) {
    TempFolder t;
    std::string error;
    ASSERT_TRUE(createFoldersInside(t.dir.string(), "01-phong/sphere", &error)) << error;
    EXPECT_TRUE(fs::is_directory(t.dir / "01-phong" / "sphere"));
    ASSERT_TRUE(createFoldersInside(t.dir.string(), "01-phong/sphere", &error)) << error;  // again: fine

    fs::create_directory(t.dir / "elsewhere");
    fs::create_directory_symlink(t.dir / "elsewhere", t.dir / "02-toon");
    EXPECT_FALSE(createFoldersInside(t.dir.string(), "02-toon/scene", &error));
    EXPECT_NE(error.find("symbolic link"), std::string::npos) << error;
    EXPECT_FALSE(fs::exists(t.dir / "elsewhere" / "scene"));

    EXPECT_FALSE(createFoldersInside(t.dir.string(), "../up", &error));
    std::ofstream(t.dir / "file") << "x";
    EXPECT_FALSE(createFoldersInside(t.dir.string(), "file/below", &error));
    EXPECT_NE(error.find("not a folder"), std::string::npos) << error;
}

}  // namespace
}  // namespace grader
