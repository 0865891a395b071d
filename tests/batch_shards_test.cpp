// Shards of a batch (`batch --shard K/N`) and `merge` over the program: shards that share a cache
// (--cache) grade each distinct lab folder once for the whole class, one after the other or at
// the same time; their merge equals one unsharded batch, its reports of zipped submissions name
// the zip (never a shard's folder); and merge refuses a set of shards that is incomplete or was
// not cut from one plan, saying which shard is missing. Slurm itself is tests/slurm/slurm_test.sh.
// The batches grade 01-phong only, so that each stays within a few seconds of work.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>
#include <thread>

#include "batch_test_support.h"

namespace fs = std::filesystem;
using json = nlohmann::json;
using namespace shaderlab::batch_testing;

namespace {

std::string quoted(const fs::path& p) { return "'" + p.string() + "'"; }

CommandRun batch(const fs::path& subs, const fs::path& out, const std::string& more) {
    return runCommand(std::string(SHADERLAB_CLI) + " batch " + quoted(subs) + " --out " + quoted(out) +
                      " --lab " + kLab + " --timeout 20 --jobs 1 " + more);
}

CommandRun merge(const std::vector<fs::path>& inputs, const fs::path& out) {
    std::string cmd = std::string(SHADERLAB_CLI) + " merge";
    for (const fs::path& in : inputs) cmd += " " + quoted(in);
    return runCommand(cmd + " --out " + quoted(out));
}

// The worker runs that a batch printed in its figures ("N worker runs"); -1 when it printed none.
int workerRuns(const std::string& output) {
    std::smatch m;
    return std::regex_search(output, m, std::regex("([0-9]+) worker runs")) ? std::stoi(m[1]) : -1;
}

// a, b, c, d and f.zip hold the same lab folder, e the starter code: two lab folders to grade.
fs::path makeClass(const fs::path& dir) {
    const fs::path subs = dir / "subs";
    for (const char* s : {"a", "b", "c", "d"}) copyReference(subs / s);
    for (const char* f : {"phong.vert", "phong.frag"})
        writeFile(subs / "e" / kLab / f, readFile(kSource / "labs" / kLab / f));
    writeZip(subs / "f.zip", referenceEntries("f/"));
    return subs;
}

TEST(BatchShards, IdenticalWorkIsGradedOnceAcrossShardsAndMergesAsOneBatch) {
    const fs::path dir = scratch("shards_once");
    const fs::path subs = makeClass(dir);
    const CommandRun whole = batch(subs, dir / "whole", "--cache " + quoted(dir / "whole-cache"));
    ASSERT_EQ(whole.exit_code, 0) << whole.output;
    EXPECT_EQ(workerRuns(whole.output), 3) << whole.output;  // the reference and two lab folders

    // One shard after the other: the second finds everything the first graded in the cache.
    const std::string cache = "--cache " + quoted(dir / "cache");
    const CommandRun one = batch(subs, dir / "shard-1", cache + " --shard 1/2");  // a, c, e
    ASSERT_EQ(one.exit_code, 0) << one.output;
    EXPECT_EQ(workerRuns(one.output), 3) << one.output;
    const CommandRun two = batch(subs, dir / "shard-2", cache + " --shard 2/2");  // b, d, f.zip
    ASSERT_EQ(two.exit_code, 0) << two.output;
    EXPECT_EQ(workerRuns(two.output), 0) << two.output;
    EXPECT_NE(two.output.find("1 lab folders found graded by an earlier run"), std::string::npos)
        << two.output;
    EXPECT_NE(two.output.find("shard 2/2: 3 of the 6 submissions"), std::string::npos) << two.output;

    const CommandRun merged = merge({dir / "shard-1", dir / "shard-2"}, dir / "all");
    ASSERT_EQ(merged.exit_code, 0) << merged.output;
    EXPECT_EQ(readFile(dir / "all" / "summary.json"), readFile(dir / "whole" / "summary.json"));
    EXPECT_EQ(readFile(dir / "all" / "summary.csv"), readFile(dir / "whole" / "summary.csv"));
    // The zip's report names the zip, in the merge as in the whole batch, never a shard's folder.
    const std::string f_report = readFile(dir / "all" / "f" / "report.json");
    EXPECT_EQ(f_report.find((dir / "shard-2").string()), std::string::npos) << f_report;
    const json f = json::parse(f_report, nullptr, false);
    ASSERT_TRUE(f.is_object());
    EXPECT_EQ(f["labs"][0]["folder"], (subs / "f.zip" / "f" / kLab).string());
    EXPECT_EQ(f["labs"][0]["status"], "passed");
    const json f_whole = json::parse(readFile(dir / "whole" / "f" / "report.json"), nullptr, false);
    ASSERT_TRUE(f_whole.is_object());
    EXPECT_EQ(f_whole["labs"][0]["folder"], f["labs"][0]["folder"]);

    // Both shards at the same time: a job the other is running is waited for, not run twice.
    const std::string shared = "--cache " + quoted(dir / "cache-together");
    CommandRun runs[2];
    std::thread first([&] { runs[0] = batch(subs, dir / "together-1", shared + " --shard 1/2"); });
    runs[1] = batch(subs, dir / "together-2", shared + " --shard 2/2");
    first.join();
    ASSERT_EQ(runs[0].exit_code, 0) << runs[0].output;
    ASSERT_EQ(runs[1].exit_code, 0) << runs[1].output;
    EXPECT_EQ(workerRuns(runs[0].output) + workerRuns(runs[1].output), 3) << runs[0].output << runs[1].output;
    ASSERT_EQ(merge({dir / "together-1", dir / "together-2"}, dir / "all-together").exit_code, 0);
    EXPECT_EQ(readFile(dir / "all-together" / "summary.csv"), readFile(dir / "whole" / "summary.csv"));
}

TEST(BatchShards, MergeRefusesAnIncompleteOrMixedSetNamingTheMissingShards) {
    const fs::path dir = scratch("shards_refused");
    const fs::path subs = dir / "subs";
    for (const char* s : {"s1", "s2", "s3"}) copyReference(subs / s);
    const std::string cache = "--cache " + quoted(dir / "cache");
    for (int k : {1, 3}) {
        const CommandRun r =
            batch(subs, dir / ("shard-" + std::to_string(k)), cache + " --shard " + std::to_string(k) + "/3");
        ASSERT_EQ(r.exit_code, 0) << r.output;
    }
    // Shard 2 never ran (a task cancelled while pending leaves no folder): no merge.
    CommandRun r = merge({dir / "shard-1", dir / "shard-3"}, dir / "all");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("incomplete: shard 2 of 3 is missing"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("sbatch --array=2 "), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir / "all" / "summary.csv"));
    r = merge({dir / "shard-1"}, dir / "all");
    EXPECT_NE(r.output.find("shards 2, 3 of 3 are missing"), std::string::npos) << r.output;

    r = batch(subs, dir / "shard-2", cache + " --shard 2/3");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    r = merge({dir / "shard-1", dir / "shard-2", dir / "shard-3"}, dir / "all");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("3 submissions from 3 results folders"), std::string::npos) << r.output;

    // The same shard twice; a shard of another count; a shard cut after a submission came in.
    ASSERT_EQ(batch(subs, dir / "again-1", cache + " --shard 1/3").exit_code, 0);
    r = merge({dir / "shard-1", dir / "again-1", dir / "shard-2", dir / "shard-3"}, dir / "twice");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("shard 1/3 is given twice"), std::string::npos) << r.output;
    ASSERT_EQ(batch(subs, dir / "half-1", cache + " --shard 1/2").exit_code, 0);
    r = merge({dir / "half-1", dir / "shard-2", dir / "shard-3"}, dir / "mixed");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("were not cut from one plan"), std::string::npos) << r.output;
    copyReference(subs / "s4");
    ASSERT_EQ(batch(subs, dir / "later-1", cache + " --shard 1/3").exit_code, 0);
    r = merge({dir / "later-1", dir / "shard-2", dir / "shard-3"}, dir / "later");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("were not cut from one plan"), std::string::npos) << r.output;
    // A shard with a whole batch; a shard folder whose batch never finished.
    ASSERT_EQ(batch(subs, dir / "whole", cache).exit_code, 0);
    r = merge({dir / "shard-1", dir / "whole"}, dir / "with-whole");
    EXPECT_NE(r.output.find("a whole batch's results"), std::string::npos) << r.output;
    fs::create_directories(dir / "dead");
    r = merge({dir / "shard-1", dir / "dead"}, dir / "with-dead");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("did not finish"), std::string::npos) << r.output;
}

}  // namespace
