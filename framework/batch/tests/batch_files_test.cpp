// The batch library's building blocks (shaderlab/batch/batch.h) on their own: submitted zips
// unpacked safely or refused with one clear status, summaries, atomic writes, content hashes.
// The command that puts them together is tested over the program in tests/batch_test.cpp.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "batch_test_support.h"
#include "shaderlab/batch/batch.h"

namespace fs = std::filesystem;
using namespace shaderlab;
using namespace shaderlab::batch_testing;

namespace {

// ---- archives -----------------------------------------------------------------------------------

TEST(BatchArchive, UnpacksNestedFoldersWithNamesKept) {
    const fs::path dir = scratch("unpack");
    std::vector<ZipEntry> entries = referenceEntries("Zoë Ångström - 12 May/submission/");
    entries.push_back({"Zoë Ångström - 12 May/submission/notes à lire.txt", "hello"});
    entries.push_back({"__MACOSX/._x", "resource fork"});
    entries.push_back(
        {"Zoë Ångström - 12 May/submission/" + kLab + "/same.frag", "", AE_IFLNK, "phong.frag"});
    writeZip(dir / "in.zip", entries);
    const batch::ExtractResult x = batch::extractZip((dir / "in.zip").string(), (dir / "out").string());
    ASSERT_EQ(x.status, "ok") << x.message;
    EXPECT_EQ(x.files, entries.size());
    const std::string root = batch::unwrapSubmissionRoot((dir / "out").string(), {kLab});
    EXPECT_EQ(fs::path(root), dir / "out" / "Zoë Ångström - 12 May" / "submission");
    EXPECT_TRUE(fs::is_regular_file(fs::path(root) / "notes à lire.txt"));
    EXPECT_EQ(readFile(fs::path(root) / kLab / "phong.frag"),
              readFile(kSource / "reference_solutions" / kLab / "phong.frag"));
    EXPECT_TRUE(fs::is_symlink(fs::path(root) / kLab / "same.frag"));  // a link inside is kept
}

TEST(BatchArchive, RefusesEntriesThatLeaveTheFolder) {
    const fs::path dir = scratch("slip");
    struct Case {
        std::vector<ZipEntry> entries;
        std::string status, words;
    };
    const std::vector<Case> cases = {
        {{{"ok.txt", "x"}, {"../../escaped.txt", "zip-slip"}}, "unsafe_archive", "'..'"},
        {{{"/tmp/escaped.txt", "absolute"}}, "unsafe_archive", "absolute path"},
        {{{"a/..\\..\\escaped.txt", "windows"}}, "unsafe_archive", "'..'"},
        {{{"a/link", "", AE_IFLNK, "/etc/passwd"}}, "unsafe_archive", "outside the submission"},
        {{{"a/link", "", AE_IFLNK, "../../etc/passwd"}}, "unsafe_archive", "outside the submission"},
        {{{"a.txt", "1"}, {"a.txt", "2"}}, "unsafe_archive", "appears twice"},
    };
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const fs::path zip = dir / ("case" + std::to_string(i) + ".zip");
        writeZip(zip, cases[i].entries);
        fs::create_directories(dir / ("out" + std::to_string(i)));
        const batch::ExtractResult x =
            batch::extractZip(zip.string(), (dir / ("out" + std::to_string(i)) / "x").string());
        EXPECT_EQ(x.status, cases[i].status) << i << ": " << x.message;
        EXPECT_NE(x.message.find(cases[i].words), std::string::npos) << i << ": " << x.message;
    }
    EXPECT_FALSE(fs::exists(dir / "escaped.txt"));
    EXPECT_FALSE(fs::exists(fs::temp_directory_path() / "escaped.txt"));
    // Device files are refused; a FIFO's mode (which libarchive reads as a plain file) and a plain
    // file's give a plain file: nothing but files, folders and checked symlinks is ever made.
    const std::vector<std::pair<std::uint32_t, std::string>> modes = {
        {0020644, "unsafe_archive"}, {0060644, "unsafe_archive"}, {0010644, ""}, {0100644, "ok"}};
    for (std::size_t i = 0; i < modes.size(); ++i) {
        const fs::path zip = dir / ("mode" + std::to_string(i) + ".zip");
        writeFile(zip, zipWithUnixMode("lab/dev", modes[i].first));
        const fs::path into = dir / ("m" + std::to_string(i));
        const batch::ExtractResult x = batch::extractZip(zip.string(), into.string());
        if (!modes[i].second.empty()) {
            EXPECT_EQ(x.status, modes[i].second) << std::oct << modes[i].first;
        }
        if (x.status == "ok") {
            EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(into / "lab" / "dev")))
                << std::oct << modes[i].first;
        } else {
            EXPECT_NE(x.message.find("not a file, a folder or a symlink"), std::string::npos) << x.message;
        }
    }
}

TEST(BatchArchive, StopsZipBombsAndNamesBrokenZips) {
    const fs::path dir = scratch("bomb");
    writeZip(dir / "bomb.zip", {{"zeros.bin", std::string(40u << 20, '\0')}});
    ASSERT_LT(fs::file_size(dir / "bomb.zip"), 1u << 20);
    batch::ExtractResult x = batch::extractZip((dir / "bomb.zip").string(), (dir / "o1").string());
    EXPECT_EQ(x.status, "too_large") << x.message;
    EXPECT_LE(x.bytes, 17u << 20);  // stopped as the data came, not after
    // Within the absolute limits, the ratio alone stops it.
    batch::ArchiveLimits lax;
    lax.max_entry_bytes = lax.max_total_bytes = 1u << 30;
    x = batch::extractZip((dir / "bomb.zip").string(), (dir / "o2").string(), lax);
    EXPECT_EQ(x.status, "too_large");
    EXPECT_NE(x.message.find("zip bomb"), std::string::npos) << x.message;

    writeFile(dir / "garbage.zip", std::string("PK\x03\x04 not really a zip at all") + std::string(200, 'x'));
    x = batch::extractZip((dir / "garbage.zip").string(), (dir / "o3").string());
    EXPECT_EQ(x.status, "bad_archive") << x.message;
    writeFile(dir / "short.zip", "PK");
    x = batch::extractZip((dir / "short.zip").string(), (dir / "o4").string());
    EXPECT_EQ(x.status, "bad_archive") << x.message;
    // Empty zips unpack to nothing; the batch then says "empty".
    writeFile(dir / "zero.zip", "");
    EXPECT_EQ(batch::extractZip((dir / "zero.zip").string(), (dir / "o5").string()).status, "ok");
    writeZip(dir / "none.zip", {});
    x = batch::extractZip((dir / "none.zip").string(), (dir / "o6").string());
    EXPECT_EQ(x.status, "ok") << x.message;
    EXPECT_EQ(x.files, 0u);
}

// ---- small pieces -------------------------------------------------------------------------------

TEST(BatchSummary, CsvQuotesFieldsAndDefusesFormulas) {
    batch::Summary s;
    s.labs = {kLab};
    batch::SummaryRow r;
    r.student = "=HYPERLINK(\"x\")";
    r.status = "graded";
    r.message = "line one, \"two\"\nthree";
    r.total = 7.5;
    r.max_total = 10;
    r.labs = {{kLab, 7.5, 10, "failed"}};
    s.rows.push_back(r);
    const std::string csv = batch::summaryToCsv(s);
    EXPECT_NE(csv.find("student,status,total,max_total,01-phong,01-phong status,message\r\n"),
              std::string::npos);
    EXPECT_NE(
        csv.find("\"'=HYPERLINK(\"\"x\"\")\",graded,7.50,10.00,7.50,failed,\"line one, \"\"two\"\"\nthree\""),
        std::string::npos)
        << csv;
    batch::Summary back;
    std::string err;
    ASSERT_TRUE(batch::summaryFromJson(batch::summaryToJson(s), &back, &err)) << err;
    ASSERT_EQ(back.rows.size(), 1u);
    EXPECT_EQ(back.rows[0].student, r.student);
    EXPECT_EQ(back.rows[0].labs[0].status, "failed");
    EXPECT_DOUBLE_EQ(back.rows[0].total, 7.5);
}

// A shard's summary says which shard it is and of what list; a whole batch's says nothing of it,
// so that the merge of the shards writes the whole batch's bytes.
TEST(BatchSummary, OnlyAShardRecordsItsPlan) {
    batch::Summary s;
    s.labs = {kLab};
    EXPECT_EQ(batch::summaryToJson(s).find("\"shard\""), std::string::npos);
    s.shard = {2, 8, 40, "0123456789abcdef"};
    batch::Summary back;
    std::string err;
    ASSERT_TRUE(batch::summaryFromJson(batch::summaryToJson(s), &back, &err)) << err;
    EXPECT_EQ(back.shard.index, 2);
    EXPECT_EQ(back.shard.count, 8);
    EXPECT_EQ(back.shard.submissions, 40u);
    EXPECT_EQ(back.shard.list, "0123456789abcdef");
    for (const char* bad : {"{\"index\": 9, \"count\": 8, \"submissions\": 1, \"list\": \"x\"}",
                            "{\"index\": 0, \"count\": 8, \"submissions\": 1, \"list\": \"x\"}", "\"2/8\""}) {
        const std::string text = std::string("{\"summary_version\": 1, \"labs\": [], \"shard\": ") + bad +
                                 ", \"submissions\": []}";
        EXPECT_FALSE(batch::summaryFromJson(text, &back, &err)) << bad;
        EXPECT_NE(err.find("'shard'"), std::string::npos) << err;
    }
}

TEST(BatchFiles, PrintableEscapesControlsAndBadUtf8) {
    EXPECT_EQ(batch::printable("Zoë\033[31m red\xff"), "Zoë\\x1B[31m red\\xFF");
    EXPECT_EQ(batch::printable(std::string(50, 'a'), 10), std::string(10, 'a') + "...");
}

TEST(BatchFiles, AtomicWriteReplacesASymlinkInsteadOfFollowingIt) {
    const fs::path dir = scratch("atomic");
    writeFile(dir / "victim.txt", "keep me");
    fs::create_symlink(dir / "victim.txt", dir / "report.json");
    std::string err;
    ASSERT_TRUE(batch::writeFileAtomically((dir / "report.json").string(), "{}", &err)) << err;
    EXPECT_EQ(readFile(dir / "victim.txt"), "keep me");
    EXPECT_FALSE(fs::is_symlink(dir / "report.json"));
    EXPECT_EQ(readFile(dir / "report.json"), "{}");
    EXPECT_FALSE(batch::writeFileAtomically((dir / "no" / "such" / "x").string(), "{}", &err));
    EXPECT_NE(err.find("No such file"), std::string::npos) << err;
}

TEST(BatchFiles, TreeHashSeesContentNotTimes) {
    const fs::path dir = scratch("hash");
    copyReference(dir / "a");
    copyReference(dir / "b");
    auto hashOf = [](const fs::path& p) {
        batch::Hasher h;
        EXPECT_TRUE(h.addTree(p.string(), p.string()));
        return h.hex();
    };
    EXPECT_EQ(hashOf(dir / "a"), hashOf(dir / "b"));
    writeFile(dir / "b" / kLab / "phong.frag", readFile(dir / "b" / kLab / "phong.frag") + " ");
    EXPECT_NE(hashOf(dir / "a"), hashOf(dir / "b"));
    fs::create_symlink("/etc/passwd", dir / "a" / "stolen");  // hashed as its target's name only
    EXPECT_NE(hashOf(dir / "a"), hashOf(dir / "b"));
}

}  // namespace
