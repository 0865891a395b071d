// Every lab proves that its grade follows its learning goals: `shaderlab corpus` grades the lab's
// reference (full marks), starter (renders and fails), known mistakes (each fails, with the goal
// it names not met) and correct alternatives (each passes), and this test fails when any of
// those expectations does not hold. It also holds each lab to the course's minimum: a corpus
// with at least six conceptual mistakes and three correct alternatives.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

const fs::path kRoot = SHADERLAB_SOURCE_DIR;

std::vector<std::string> labIds() {
    std::vector<std::string> ids;
    for (const auto& entry : fs::directory_iterator(kRoot / "labs"))
        if (entry.is_directory() && fs::exists(entry.path() / "lab.json"))
            ids.push_back(entry.path().filename());
    std::sort(ids.begin(), ids.end());
    return ids;
}

// `shaderlab ARGS` with stderr in the output; exit_code -1 when it did not exit by itself.
struct CliRun {
    int exit_code = -1;
    std::string output;
};

CliRun runCli(const std::string& args) {
    CliRun r;
    FILE* pipe = popen((std::string(SHADERLAB_CLI) + args + " 2>&1").c_str(), "r");
    if (pipe == nullptr) return r;
    char buf[4096];
    while (std::fgets(buf, sizeof buf, pipe)) r.output += buf;
    const int status = pclose(pipe);
    if (WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
    return r;
}

class LabCorpus : public ::testing::TestWithParam<std::string> {};

TEST_P(LabCorpus, HasEnoughMistakesAndAlternatives) {
    std::ifstream in(kRoot / "tests" / "corpus" / GetParam() / "cases.json");
    ASSERT_TRUE(in) << "tests/corpus/" << GetParam() << "/cases.json is missing";
    const json cases = json::parse(in, nullptr, false);
    ASSERT_FALSE(cases.is_discarded());
    int mistakes = 0, alternatives = 0;
    for (const json& c : cases["cases"]) {
        mistakes += c["kind"] == "mistake";
        alternatives += c["kind"] == "alternative";
    }
    EXPECT_GE(mistakes, 6) << GetParam();
    EXPECT_GE(alternatives, 3) << GetParam();
}

TEST_P(LabCorpus, EveryVerdictIsTheExpectedOne) {
    const fs::path out =
        fs::temp_directory_path() / ("shaderlab_corpus_" + GetParam() + "_" + std::to_string(::getpid()));
    fs::remove_all(out);
    const CliRun r = runCli(" corpus --lab " + GetParam() + " --out " + out.string());
    const std::string& output = r.output;
    EXPECT_EQ(r.exit_code, 0) << output;
    std::ifstream in(out / "corpus.json");
    const json summary = json::parse(in, nullptr, false);
    ASSERT_FALSE(summary.is_discarded()) << output;
    int reference = 0, starter = 0;
    for (const json& c : summary) {
        EXPECT_TRUE(c["ok"].get<bool>()) << c.dump(2);
        reference += c["kind"] == "reference";
        starter += c["kind"] == "starter";
    }
    EXPECT_EQ(reference, 1);
    EXPECT_EQ(starter, 1);
    std::printf("%s", output.c_str());
}

std::string testName(const ::testing::TestParamInfo<std::string>& param_info) {
    std::string n = param_info.param;
    for (char& c : n)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    return n;
}

INSTANTIATE_TEST_SUITE_P(Labs, LabCorpus, ::testing::ValuesIn(labIds()), testName);

// Coverage by mutation (`shaderlab mutants`, docs/authoring.md "Mutants"): every mutant of the
// reference that compiles either loses points or is declared equivalent, with the reason, in the
// lab's cases.json. The run's own summary line (mutants, killed, declared, not compiling) is
// printed, the figures the course reports per lab.
class LabMutants : public ::testing::TestWithParam<std::string> {};

TEST_P(LabMutants, NoUndeclaredSurvivor) {
    const fs::path out =
        fs::temp_directory_path() / ("shaderlab_mutants_" + GetParam() + "_" + std::to_string(::getpid()));
    fs::remove_all(out);
    const CliRun r = runCli(" mutants " + GetParam() + " --out " + out.string());
    const std::string& output = r.output;
    EXPECT_EQ(r.exit_code, 0) << output;
    std::ifstream in(out / "mutants.json");
    const json result = json::parse(in, nullptr, false);
    ASSERT_FALSE(result.is_discarded()) << output;
    ASSERT_EQ(result["labs"].size(), 1u) << output;
    const json& lab = result["labs"][0];
    EXPECT_EQ(lab["survivors"], 0) << output;
    // The mutants test something: most of them are killed, and none is left ungraded.
    EXPECT_GT(lab["killed"].get<int>(), lab["equivalent"].get<int>()) << output;
    EXPECT_EQ(lab["mutants"], lab["made"]) << output;
    EXPECT_TRUE(lab["stale_declarations"].empty()) << output;
    std::printf("%s", output.c_str());
    fs::remove_all(out);
}

INSTANTIATE_TEST_SUITE_P(Labs, LabMutants, ::testing::ValuesIn(labIds()), testName);

}  // namespace

namespace {

// The course index (labs/README.md) links every lab folder and nothing else, and every lab has
// its README: the list of labs cannot drift from the folders.
TEST(CourseIndex, ListsEveryLabAndOnlyThem) {
    std::ifstream in(kRoot / "labs" / "README.md");
    ASSERT_TRUE(in);
    const std::string index((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (const std::string& id : labIds()) {
        EXPECT_NE(index.find("[" + id + "](" + id + "/README.md)"), std::string::npos)
            << id << " is not indexed";
        EXPECT_TRUE(fs::is_regular_file(kRoot / "labs" / id / "README.md")) << id;
    }
    for (std::size_t at = index.find("/README.md)"); at != std::string::npos;
         at = index.find("/README.md)", at + 1)) {
        const std::size_t open = index.rfind('(', at);
        const std::string folder = index.substr(open + 1, at - open - 1);
        EXPECT_TRUE(fs::is_directory(kRoot / "labs" / folder)) << folder << " is linked but does not exist";
    }
}

}  // namespace
