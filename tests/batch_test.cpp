// `shaderlab batch` and `merge` over the program (their building blocks have their own tests in
// framework/batch/tests/): submitted zips refused with one clear status, summaries, resuming after
// SIGKILL with no process left behind, identical work graded once, shards merged into the same
// summary.
// The batches grade 01-phong only, so that every test here stays within a few seconds of work.
#include "shaderlab/batch/batch.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <thread>

#include "batch_test_support.h"

namespace fs = std::filesystem;
using json = nlohmann::json;
using namespace shaderlab;
using namespace shaderlab::batch_testing;

namespace {

struct CliRun {
    int exit_code = -1;
    std::string output;
};

CliRun runCli(const std::string& args, const std::string& env = "") {
    CliRun r;
    const std::string cmd = env + " " + std::string(SHADERLAB_CLI) + " " + args + " 2>&1";
    FILE* pipe = popen(cmd.c_str(), "r");
    if (!pipe) return r;
    char buf[4096];
    while (std::fgets(buf, sizeof buf, pipe)) r.output += buf;
    const int status = pclose(pipe);
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

std::string batchArgs(const fs::path& subs, const fs::path& out, const std::string& more = "") {
    return "batch '" + subs.string() + "' --out '" + out.string() + "' --lab " + kLab + " --timeout 20 " +
           more;
}

json summaryOf(const fs::path& out) { return json::parse(readFile(out / "summary.json"), nullptr, false); }

const json* rowOf(const json& summary, const std::string& student) {
    for (const json& r : summary["submissions"])
        if (r["student"] == student) return &r;
    return nullptr;
}

// Processes whose environment holds `marker`: everything a batch started, wherever it was reparented.
std::vector<int> processesMarked(const std::string& marker) {
    std::vector<int> pids;
    std::error_code ec;
    for (const fs::directory_entry& e : fs::directory_iterator("/proc", ec)) {
        const std::string name = e.path().filename().string();
        if (name.find_first_not_of("0123456789") != std::string::npos) continue;
        const std::string env = readFile(e.path() / "environ");
        if (env.find(marker) != std::string::npos) pids.push_back(std::stoi(name));
    }
    return pids;
}

// ---- the command --------------------------------------------------------------------------------

TEST(BatchCli, RefusesAnUnwritableOrBusyResultsFolderBeforeAnyWork) {
    const fs::path dir = scratch("refuse");
    copyReference(dir / "subs" / "alice");
    writeFile(dir / "file", "not a folder");
    CliRun r = runCli(batchArgs(dir / "subs", dir / "file" / "out"));
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("cannot write the results"), std::string::npos) << r.output;
    fs::create_directories(dir / "out" / ".shaderlab");
    batch::FolderLock held;
    std::string err;
    ASSERT_TRUE(held.acquire((dir / "out" / ".shaderlab" / "lock").string(), &err)) << err;
    r = runCli(batchArgs(dir / "subs", dir / "out"));
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("another batch is writing into this folder"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir / "out" / "alice"));
    r = runCli(batchArgs(dir / "subs", dir / "out2", "--shard 3/2"));
    EXPECT_EQ(r.exit_code, 2) << r.output;
}

// Folders and zips, well-formed and hostile, in one batch: each gets its status, a report, and a
// row in the summary; identical lab folders are graded once; Mesa writes nothing into $HOME; a
// second run skips every unchanged submission.
TEST(BatchCli, MixedSubmissionsEachGetOneClearStatus) {
    const fs::path dir = scratch("mixed");
    // The results go inside the submissions folder: they are not taken for a submission.
    const fs::path subs = dir / "subs", out = subs / "results", home = dir / "home";
    fs::create_directories(home);
    copyReference(subs / "alice");
    copyReference(subs / "dave");  // the same work as alice's
    for (const char* f : {"phong.vert", "phong.frag"})
        writeFile(subs / "bob" / kLab / f, readFile(kSource / "labs" / kLab / f));  // the starter
    writeZip(subs / "Zoë Ångström.zip", referenceEntries("Zoë Ångström/Assignment 1/"));
    writeZip(subs / "mallory.zip", {{"../../escaped.txt", "zip-slip"}});
    writeZip(subs / "bomb.zip", {{"zeros.bin", std::string(40u << 20, '\0')}});
    writeZip(subs / "hollow.zip", {});
    writeFile(subs / "nothing.zip", "");
    writeFile(subs / "garbage.zip", std::string(300, '\x07'));
    writeFile(subs / "stray.txt", "not a submission");
    // A lab folder that is a symlink to the root of the file system, and a symlink loop.
    fs::create_directories(subs / "eve");
    fs::create_directory_symlink("/", subs / "eve" / kLab);
    fs::create_directory_symlink(".", subs / "eve" / "loop");
    const std::string env = "HOME='" + home.string() + "' XDG_CACHE_HOME='" + home.string() + "/.cache'";
    CliRun r = runCli(batchArgs(subs, out), env + " env -u MESA_SHADER_CACHE_DISABLE");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const json summary = summaryOf(out);
    ASSERT_TRUE(summary.is_object()) << r.output;
    EXPECT_EQ(summary["submissions"].size(), 10u) << summary.dump(1);
    // Not a terminal: one plain line per submission, no bar, no escapes.
    EXPECT_NE(r.output.find("/10] alice: graded 10.00 / 10.00\n"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("\033["), std::string::npos) << r.output;
    const std::map<std::string, std::pair<std::string, std::string>> expected = {
        {"alice", {"graded", "passed"}},
        {"dave", {"graded", "passed"}},
        {"bob", {"graded", "not_attempted"}},
        {"Zoë Ångström", {"graded", "passed"}},
        {"mallory", {"unsafe_archive", ""}},
        {"bomb", {"too_large", ""}},
        {"hollow", {"empty", ""}},
        {"nothing", {"empty", ""}},
        {"garbage", {"bad_archive", ""}},
        {"eve", {"graded", "missing"}},
    };
    for (const auto& [student, want] : expected) {
        const json* row = rowOf(summary, student);
        ASSERT_NE(row, nullptr) << student;
        EXPECT_EQ((*row)["status"], want.first) << student << ": " << row->dump();
        EXPECT_EQ((*row)["labs"][kLab]["status"], want.second) << student << ": " << row->dump();
        // Every submission has its report, graded or not.
        const json report = json::parse(readFile(out / student / "report.json"), nullptr, false);
        ASSERT_TRUE(report.is_object()) << student;
        EXPECT_TRUE(fs::is_regular_file(out / student / "report.html")) << student;
        if (want.first != "graded") {
            EXPECT_FALSE((*row)["message"].get<std::string>().empty()) << student;
            EXPECT_EQ(report["labs"][0]["status"], "missing") << student;
        }
    }
    EXPECT_DOUBLE_EQ((*rowOf(summary, "alice"))["total"].get<double>(),
                     (*rowOf(summary, "alice"))["max_total"].get<double>());
    // The images are in each report folder, and each report names its own folder.
    EXPECT_TRUE(fs::is_regular_file(out / "dave" / kLab / "sphere" / "student.png"));
    const json dave = json::parse(readFile(out / "dave" / "report.json"));
    EXPECT_NE(dave["labs"][0]["folder"].get<std::string>().find("/dave/"), std::string::npos) << dave.dump();
    // alice, dave and Zoë submitted the same files, bob the starter, eve her symlink: three gradings.
    std::size_t graded = 0;
    for (const fs::directory_entry& e : fs::directory_iterator(out / ".shaderlab" / "labs" / kLab))
        graded += e.is_directory() ? 1 : 0;
    EXPECT_EQ(graded, 3u);
    EXPECT_FALSE(fs::exists(dir / "escaped.txt"));
    EXPECT_FALSE(fs::exists(home / ".cache")) << "something wrote a cache into $HOME";
    // Unchanged: nothing graded again. One changed submission: only it.
    r = runCli(batchArgs(subs, out));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("(0 graded, 10 unchanged since their report), 0 worker runs"), std::string::npos)
        << r.output;
    for (const char* f : {"phong.vert", "phong.frag"})
        writeFile(subs / "bob" / kLab / f, readFile(kSource / "reference_solutions" / kLab / f));
    r = runCli(batchArgs(subs, out));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("(1 graded, 9 unchanged since their report), 0 worker runs"), std::string::npos)
        << r.output;  // bob's lab folder is now alice's: its grading is reused
    EXPECT_EQ((*rowOf(summaryOf(out), "bob"))["labs"][kLab]["status"], "passed");
}

// A worker that dies (here: an address-space cap too small for the program to start) costs its
// lab a "crashed" with the reason and the worker's log, exit code 1; the next run grades it.
TEST(BatchCli, AWorkerThatDiesIsNamedAndRetried) {
    const fs::path dir = scratch("worker_dies");
    copyReference(dir / "subs" / "alice");
    CliRun r =
        runCli(batchArgs(dir / "subs", dir / "out", "--no-reference"), "SHADERLAB_WORKER_ADDRESS_SPACE=16M");
    EXPECT_EQ(r.exit_code, 1) << r.output;
    const json report = json::parse(readFile(dir / "out" / "alice" / "report.json"), nullptr, false);
    ASSERT_TRUE(report.is_object()) << r.output;
    EXPECT_EQ(report["labs"][0]["status"], "crashed");
    const std::string message = report["labs"][0]["message"];
    EXPECT_NE(message.find("the grading process stopped"), std::string::npos) << message;
    EXPECT_NE(message.find("log: " + (dir / "out" / ".shaderlab" / "logs").string()), std::string::npos)
        << message;
    EXPECT_FALSE(fs::exists(dir / "out" / "alice" / "batch.json"));
    // Symlinks planted in the results folder are replaced, never written through.
    writeFile(dir / "victim" / "keep.txt", "keep");
    fs::remove_all(dir / "out" / "alice");
    fs::create_directory_symlink(dir / "victim", dir / "out" / "alice");
    fs::remove(dir / "out" / "summary.csv");
    fs::create_symlink(dir / "victim" / "keep.txt", dir / "out" / "summary.csv");
    r = runCli(batchArgs(dir / "subs", dir / "out", "--no-reference"));
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("(1 graded, 0 unchanged"), std::string::npos) << r.output;
    EXPECT_EQ((*rowOf(summaryOf(dir / "out"), "alice"))["labs"][kLab]["status"], "passed");
    EXPECT_EQ(readFile(dir / "victim" / "keep.txt"), "keep");
    EXPECT_EQ(std::distance(fs::directory_iterator(dir / "victim"), fs::directory_iterator()), 1);
    EXPECT_FALSE(fs::is_symlink(dir / "out" / "alice"));
    EXPECT_FALSE(fs::is_symlink(dir / "out" / "summary.csv"));
    // The batch's own folder planted as a symlink: refused before any work.
    fs::remove_all(dir / "out" / ".shaderlab");
    fs::create_directory_symlink(dir / "victim", dir / "out" / ".shaderlab");
    r = runCli(batchArgs(dir / "subs", dir / "out", "--no-reference"));
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("is a symlink"), std::string::npos) << r.output;
    EXPECT_EQ(std::distance(fs::directory_iterator(dir / "victim"), fs::directory_iterator()), 1);
}

// `j` without the times it holds (every "..._ms"), which differ from run to run.
json withoutTimes(const json& j) {
    if (j.is_array()) {
        json out = json::array();
        for (const json& v : j) out.push_back(withoutTimes(v));
        return out;
    }
    if (!j.is_object()) return j;
    json out = json::object();
    for (auto it = j.begin(); it != j.end(); ++it) {
        const std::string& key = it.key();
        if (key.size() < 3 || key.compare(key.size() - 3, 3, "_ms") != 0) out[key] = withoutTimes(it.value());
    }
    return out;
}

// The labs of one submission go to one worker, whose one render child draws them all; each lab
// lands in its own folder holding that lab alone, and the report says what a worker per lab says.
TEST(BatchCli, OneWorkerGradesTheLabsOfASubmissionAsAWorkerEachWould) {
    const fs::path dir = scratch("worker_groups");
    const std::vector<std::string> labs = {"01-phong", "09-procedural-antialiasing", "08-gooch"};
    for (const std::string& lab : labs) {
        fs::create_directories(dir / "subs" / "alice" / lab);
        fs::copy(kSource / "reference_solutions" / lab, dir / "subs" / "alice" / lab,
                 fs::copy_options::recursive);
    }
    std::string flags = "--no-reference --timeout 20 --jobs 1";
    for (const std::string& lab : labs) flags += " --lab " + lab;
    const CliRun together =
        runCli("batch '" + (dir / "subs").string() + "' --out '" + (dir / "out").string() + "' " + flags);
    ASSERT_EQ(together.exit_code, 0) << together.output;
    EXPECT_NE(together.output.find(", 1 worker runs ("), std::string::npos) << together.output;
    const json report = json::parse(readFile(dir / "out" / "alice" / "report.json"), nullptr, false);
    ASSERT_TRUE(report.is_object()) << together.output;
    ASSERT_EQ(report["labs"].size(), labs.size());
    // Each landed result holds its own lab, with its pictures.
    std::size_t landed = 0;
    for (const fs::directory_entry& e :
         fs::recursive_directory_iterator(dir / "out" / ".shaderlab" / "labs")) {
        if (e.path().filename() != "report.json") continue;
        const json one = json::parse(readFile(e.path()), nullptr, false);
        ASSERT_EQ(one["labs"].size(), 1u) << e.path();
        const std::string lab = one["labs"][0]["id"];
        EXPECT_EQ(one["score"], one["labs"][0]["score"]);
        EXPECT_TRUE(fs::is_directory(e.path().parent_path() / lab)) << e.path();
        ++landed;
    }
    EXPECT_EQ(landed, labs.size());
    // A batch per lab (a worker and a render child each) says the same of every lab.
    for (std::size_t i = 0; i < labs.size(); ++i) {
        const fs::path out = dir / ("alone-" + labs[i]);
        const CliRun alone = runCli("batch '" + (dir / "subs").string() + "' --out '" + out.string() +
                                    "' --no-reference --timeout 20 --lab " + labs[i]);
        ASSERT_EQ(alone.exit_code, 0) << alone.output;
        EXPECT_NE(alone.output.find(", 1 worker runs ("), std::string::npos) << alone.output;
        const json a = json::parse(readFile(out / "alice" / "report.json"), nullptr, false)["labs"][0];
        EXPECT_TRUE(withoutTimes(a) == withoutTimes(report["labs"][i])) << labs[i];
    }
}

// A batch killed with SIGKILL half-way leaves no process; run again it finishes what was missing
// and ends with the summary of a run never interrupted. Two shards merged give it too.
TEST(BatchCli, InterruptedResumedAndShardedRunsAgree) {
    const fs::path dir = scratch("resume");
    const fs::path subs = dir / "subs", cache = dir / "cache";
    // Distinct work (a comment each), so that every submission is a grading of its own.
    for (int i = 0; i < 6; ++i)
        copyReference(subs / ("s" + std::to_string(i)), "\n// " + std::to_string(i) + "\n");
    for (const char* f : {"phong.vert", "phong.frag"})
        writeFile(subs / "starter" / kLab / f, readFile(kSource / "labs" / kLab / f));
    const std::string common = "--jobs 2 --cache '" + cache.string() + "'";

    const CliRun whole = runCli(batchArgs(subs, dir / "whole", common));
    ASSERT_EQ(whole.exit_code, 0) << whole.output;
    const std::string expected = readFile(dir / "whole" / "summary.json");

    // The run to kill has a cache of its own: in the whole run's, every lab is graded already.
    const fs::path killed_cache = dir / "cache-killed";
    const std::string marker = "SHADERLAB_BATCH_TEST_" + std::to_string(getpid());
    const pid_t pid = fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
        setenv(marker.c_str(), "1", 1);
        const std::string out = (dir / "killed").string();
        std::freopen("/dev/null", "w", stdout);
        execl(SHADERLAB_CLI, SHADERLAB_CLI, "batch", subs.c_str(), "--out", out.c_str(), "--lab",
              kLab.c_str(), "--timeout", "20", "--jobs", "2", "--cache", killed_cache.c_str(),
              static_cast<char*>(nullptr));
        _exit(127);
    }
    // Kill it once the first report is there (and before the last).
    bool some = false;
    for (int i = 0; i < 1500 && !some; ++i) {
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        std::error_code ec;
        for (const fs::directory_entry& e : fs::directory_iterator(dir / "killed", ec))
            some = some || fs::exists(e.path() / "batch.json");
    }
    ASSERT_TRUE(some);
    // The batch writes a report (batch.json last) after reaping its worker and before starting the
    // next; the first two jobs start together and often end together, so the first batch.json can
    // appear while no worker runs (met once in the ASan build, where writing reports is slower).
    // Wait briefly for the next worker rather than look once.
    std::size_t marked = processesMarked(marker).size();
    for (int i = 0; i < 100 && marked <= 1; ++i) {
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
        marked = processesMarked(marker).size();
    }
    EXPECT_GT(marked, 1u) << "the batch should have workers running";
    kill(pid, SIGKILL);
    int status = 0;
    waitpid(pid, &status, 0);
    EXPECT_FALSE(fs::exists(dir / "killed" / "summary.json")) << "the batch finished before it was killed";
    std::vector<int> left = processesMarked(marker);
    for (int i = 0; i < 100 && !left.empty(); ++i) {  // PR_SET_PDEATHSIG is prompt, not instant
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        left = processesMarked(marker);
    }
    EXPECT_TRUE(left.empty()) << left.size() << " processes of the killed batch are still running";

    const CliRun resumed =
        runCli(batchArgs(subs, dir / "killed", "--jobs 2 --cache '" + killed_cache.string() + "'"));
    ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
    EXPECT_EQ(resumed.output.find("(7 graded"), std::string::npos)
        << "everything graded again: " << resumed.output;
    EXPECT_EQ(readFile(dir / "killed" / "summary.json"), expected);

    for (int k = 1; k <= 2; ++k) {
        const CliRun shard = runCli(batchArgs(subs, dir / ("shard" + std::to_string(k)),
                                              common + " --shard " + std::to_string(k) + "/2"));
        ASSERT_EQ(shard.exit_code, 0) << shard.output;
    }
    const CliRun merged = runCli("merge '" + (dir / "shard1").string() + "' '" + (dir / "shard2").string() +
                                 "' --out '" + (dir / "merged").string() + "'");
    ASSERT_EQ(merged.exit_code, 0) << merged.output;
    EXPECT_EQ(readFile(dir / "merged" / "summary.json"), expected);
    EXPECT_EQ(readFile(dir / "merged" / "summary.csv"), readFile(dir / "whole" / "summary.csv"));
    EXPECT_TRUE(fs::is_regular_file(dir / "merged" / "s3" / "report.html"));
    // A student in two shards is an error, not a silent pick.
    const CliRun twice = runCli("merge '" + (dir / "shard1").string() + "' '" + (dir / "whole").string() +
                                "' --out '" + (dir / "merged2").string() + "'");
    EXPECT_EQ(twice.exit_code, 2) << twice.output;
}

}  // namespace
