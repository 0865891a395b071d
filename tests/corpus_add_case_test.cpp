// The corpus format (docs/corpus.schema.json) and `shaderlab corpus add-case`, run as an
// instructor runs it on a copy of the course's 08-gooch lab and corpus in the temp directory:
// only the student files that differ from the reference are stored, the case is one more line of
// cases.json in the file's own layout, and every refusal writes nothing. Also: every bundled
// cases.json names the schema and is valid by it, as the program reads it.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.h"
#include "shaderlab/lab/json_schema_check.h"

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

const fs::path kRoot = SHADERLAB_SOURCE_DIR;
const char* const kLab = "08-gooch";

using shaderlab_test::CliRun;

CliRun run(const std::string& cmd) { return shaderlab_test::runShell(cmd); }

std::string readText(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

void writeText(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

std::vector<std::string> schemaProblems(const json& doc) {
    static const json schema = json::parse(readText(kRoot / "docs" / "corpus.schema.json"));
    static const shaderlab::JsonSchemaChecker checker(schema);
    std::vector<std::string> out;
    for (const shaderlab::SchemaProblem& p : checker.check(doc)) out.push_back(p.path + ": " + p.problem);
    return out;
}

// A course in the temp directory with the lab, its reference, its corpus and the docs' schema;
// `from` starts as a copy of the reference solution.
class CorpusAddCase : public ::testing::Test {
  protected:
    void SetUp() override {
        tmp_ = fs::temp_directory_path() / ("shaderlab_add_case_" + std::to_string(::getpid()) + "_" +
                                            ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(tmp_);
        for (const char* dir : {"labs", "reference_solutions", "tests/corpus", "docs"})
            fs::create_directories(tmp_ / dir);
        for (const char* part : {kLab, "scenes", "shared"})
            fs::copy(kRoot / "labs" / part, tmp_ / "labs" / part, fs::copy_options::recursive);
        fs::copy(kRoot / "reference_solutions" / kLab, tmp_ / "reference_solutions" / kLab,
                 fs::copy_options::recursive);
        fs::copy(kRoot / "tests" / "corpus" / kLab, corpus(), fs::copy_options::recursive);
        fs::copy_file(kRoot / "docs" / "corpus.schema.json", tmp_ / "docs" / "corpus.schema.json");
        fs::copy(tmp_ / "reference_solutions" / kLab, from(), fs::copy_options::recursive);
        before_ = readText(cases());
    }
    void TearDown() override { fs::remove_all(tmp_); }

    fs::path corpus() const { return tmp_ / "tests" / "corpus" / kLab; }
    fs::path cases() const { return corpus() / "cases.json"; }
    fs::path from() const { return tmp_ / "from"; }

    CliRun addCase(const std::string& name, const std::string& options) const {
        return run(std::string(SHADERLAB_CLI) + " corpus add-case " + kLab + " " + name + " " + options +
                   " --from " + from().string() + " --labs " + (tmp_ / "labs").string());
    }

    // A refusal: exit code 2, the reason said, nothing written.
    void expectRefused(const CliRun& r, const std::string& name, const std::string& reason) const {
        EXPECT_EQ(r.exit_code, 2) << r.output;
        EXPECT_NE(r.output.find(reason), std::string::npos) << r.output;
        EXPECT_EQ(readText(cases()), before_);
        EXPECT_FALSE(fs::exists(corpus() / name)) << name;
        for (const auto& e : fs::directory_iterator(corpus()))
            EXPECT_NE(e.path().filename().string().rfind(".cases.json", 0), 0u) << e.path();
    }

    void changeLine(const std::string& file, const std::string& from_text, const std::string& to_text) const {
        std::string text = readText(from() / file);
        const std::size_t at = text.find(from_text);
        ASSERT_NE(at, std::string::npos) << from_text;
        writeText(from() / file, text.replace(at, from_text.size(), to_text));
    }

    fs::path tmp_;
    std::string before_;
};

TEST_F(CorpusAddCase, StoresOnlyTheFilesThatDifferAndAppendsOneCaseLine) {
    changeLine("gooch.frag", "u_beta * k_d", "0.5 * k_d");
    const CliRun r = addCase("beta-halved", "--kind mistake --fails tone --about \"beta replaced by 0.5\"");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    // The changed file alone, as it is in `from`.
    std::vector<std::string> stored;
    for (const auto& e : fs::recursive_directory_iterator(corpus() / "beta-halved"))
        stored.push_back(fs::relative(e.path(), corpus() / "beta-halved").string());
    EXPECT_EQ(stored, std::vector<std::string>{"gooch.frag"});
    EXPECT_EQ(readText(corpus() / "beta-halved" / "gooch.frag"), readText(from() / "gooch.frag"));
    // The file as it was, with the case as one more entry in its layout.
    const std::string after = readText(cases());
    // The cases array's last entry (an "equivalent_mutants" array may follow it).
    const std::size_t last = before_.rfind('}', before_.find("\n  ]", before_.find("\"cases\"")));
    EXPECT_EQ(after, before_.substr(0, last + 1) +
                         ",\n    { \"name\": \"beta-halved\", \"kind\": \"mistake\", \"fails\": [\"tone\"],\n"
                         "      \"about\": \"beta replaced by 0.5\" }" +
                         before_.substr(last + 1));
    const json doc = json::parse(after);
    EXPECT_TRUE(schemaProblems(doc).empty());
    EXPECT_EQ(doc["cases"].back(),
              json::parse(R"({"name": "beta-halved", "kind": "mistake", "fails": ["tone"],
                              "about": "beta replaced by 0.5"})"));
    EXPECT_NE(r.output.find("shaderlab corpus --lab 08-gooch"), std::string::npos) << r.output;
}

TEST_F(CorpusAddCase, CorpusSaysTheNewCaseHasNoHintsYetAndKeepsTheLabsPoints) {
    changeLine("gooch.frag", "u_beta * k_d", "0.5 * k_d");
    ASSERT_EQ(
        addCase("beta-halved", "--kind mistake --fails tone --about \"beta replaced by 0.5\"").exit_code, 0);
    // Its pictures are not among the lab's hints until `goldens` runs: the hints are stale, and
    // the summary still counts the lab's points (it once printed "10.00 / 0.00").
    const CliRun r =
        run(std::string(SHADERLAB_CLI) + " corpus --lab " + kLab + " --labs " + (tmp_ / "labs").string() +
            " --corpus " + (tmp_ / "tests" / "corpus").string() + " --reference " +
            (tmp_ / "reference_solutions").string() + " --out " + (tmp_ / "out").string());
    EXPECT_NE(r.exit_code, 0) << r.output;
    // On another renderer than the goldens' (a newer Mesa) stored hints are matched by name and
    // a fresh picture without a stored twin is no fault: stale only on the goldens' own.
    if (r.output.find("compared within") == std::string::npos) {
        EXPECT_NE(r.output.find("FAIL known-mistake hints"), std::string::npos) << r.output;
    }
    EXPECT_NE(r.output.find("worst correct solution 10.00 / 10.00"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("beta-halved"), std::string::npos) << r.output;
}

TEST_F(CorpusAddCase, ABrokenCaseDeletesTheFilesItLacks) {
    fs::remove(from() / "lines.frag");
    const CliRun r = addCase("no-lines", "--kind broken --status missing --about \"no lines.frag\"");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_FALSE(fs::exists(corpus() / "no-lines"));  // nothing differs: no folder
    const json doc = json::parse(readText(cases()));
    EXPECT_EQ(doc["cases"].back(), json::parse(R"({"name": "no-lines", "kind": "broken", "status": "missing",
                                                   "delete": ["lines.frag"], "about": "no lines.frag"})"));
}

TEST_F(CorpusAddCase, RefusesWhenNoFileDiffers) {
    expectRefused(addCase("same", "--kind alternative --about same"), "same", "there is no case to add");
}

TEST_F(CorpusAddCase, RefusesANameTaken) {
    changeLine("gooch.frag", "u_beta * k_d", "0.5 * k_d");
    const CliRun taken = addCase("raw-depth", "--kind mistake --fails tone --about x");
    EXPECT_EQ(taken.exit_code, 2) << taken.output;
    EXPECT_NE(taken.output.find("has a case \"raw-depth\" already"), std::string::npos) << taken.output;
    EXPECT_EQ(readText(corpus() / "raw-depth" / "lines.frag"),
              readText(kRoot / "tests/corpus/08-gooch/raw-depth/lines.frag"));
    fs::create_directories(corpus() / "left-over");
    const CliRun r = addCase("left-over", "--kind mistake --fails tone --about x");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("left-over exists already"), std::string::npos) << r.output;
    EXPECT_EQ(readText(cases()), before_);
}

TEST_F(CorpusAddCase, RefusesAnUnknownGoalWithASuggestion) {
    changeLine("gooch.frag", "u_beta * k_d", "0.5 * k_d");
    expectRefused(addCase("beta-halved", "--kind mistake --fails tones --about x"), "beta-halved",
                  "08-gooch has no goal \"tones\" (did you mean \"tone\"?)");
}

TEST_F(CorpusAddCase, RefusesALinkPointingOutsideTheFolder) {
    changeLine("gooch.frag", "u_beta * k_d", "0.5 * k_d");
    fs::remove(from() / "lines.frag");
    fs::create_symlink("/etc/passwd", from() / "lines.frag");
    expectRefused(addCase("linked", "--kind mistake --fails tone --about x"), "linked",
                  "is a link to outside");
}

TEST_F(CorpusAddCase, RefusesWhatAKindDoesNotTake) {
    changeLine("gooch.frag", "u_beta * k_d", "0.5 * k_d");
    expectRefused(addCase("alt", "--kind alternative --fails tone --about x"), "alt", "takes no --fails");
    expectRefused(addCase("mis", "--kind mistake --about x"), "mis", "a mistake names with --fails");
    expectRefused(addCase("brk", "--kind broken --about x"), "brk", "names with --status");
}

// The new file is checked whole against the schema: what it refuses, nothing is written for.
TEST_F(CorpusAddCase, RefusesWhatTheSchemaRefuses) {
    changeLine("gooch.frag", "u_beta * k_d", "0.5 * k_d");
    const std::size_t index = json::parse(before_)["cases"].size();
    expectRefused(addCase("empty-about", "--kind mistake --fails tone --about \"\""), "empty-about",
                  "cases.json: cases[" + std::to_string(index) + "].about: must not be empty");
}

TEST_F(CorpusAddCase, RefusesToAddToAnInvalidCorpus) {
    changeLine("gooch.frag", "u_beta * k_d", "0.5 * k_d");
    std::string text = before_;
    text.replace(text.find("\"kind\": \"alternative\""), 21, "\"kind\": \"alternativ\"");
    writeText(cases(), text);
    before_ = text;
    expectRefused(
        addCase("beta-halved", "--kind mistake --fails tone --about x"), "beta-halved",
        "cases[0].kind: expected one of \"mistake\", \"alternative\" or \"broken\", got \"alternativ\"");
}

// Every bundled corpus names the schema, is valid by it, and is read by the program as valid (a
// case from the reference itself is refused only because nothing differs).
TEST(CorpusFormat, EveryBundledCasesFileIsValidByTheSchema) {
    int files = 0;
    for (const auto& lab : fs::directory_iterator(kRoot / "tests" / "corpus")) {
        const fs::path file = lab.path() / "cases.json";
        if (!fs::exists(file)) continue;
        ++files;
        const json doc = json::parse(readText(file), nullptr, false);
        ASSERT_FALSE(doc.is_discarded()) << file;
        EXPECT_EQ(doc.value("$schema", ""), "../../../docs/corpus.schema.json") << file;
        for (const std::string& p : schemaProblems(doc)) ADD_FAILURE() << file << ": " << p;
        const std::string id = lab.path().filename().string();
        const CliRun r =
            run(std::string(SHADERLAB_CLI) + " corpus add-case " + id +
                " probe --kind alternative --about probe --from " +
                (kRoot / "reference_solutions" / id).string() + " --labs " + (kRoot / "labs").string());
        EXPECT_EQ(r.exit_code, 2) << r.output;
        EXPECT_NE(r.output.find("there is no case to add"), std::string::npos) << id << ": " << r.output;
    }
    EXPECT_GE(files, 11);
}

TEST(CorpusFormat, TheSchemaIsDraft7AndDocumentsEveryField) {
    const json schema = json::parse(readText(kRoot / "docs" / "corpus.schema.json"));
    EXPECT_EQ(schema.at("$schema"), "http://json-schema.org/draft-07/schema#");
    for (const auto& [field, node] : schema.at("definitions").at("case").at("properties").items())
        EXPECT_TRUE(node.contains("description") || node.contains("$ref")) << field;
    EXPECT_NE(readText(kRoot / "docs" / "grading.md").find("corpus.schema.json"), std::string::npos);
}

}  // namespace
