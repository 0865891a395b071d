// `shaderlab new-lab` and `shaderlab lab-check`, run as an instructor runs them on a course in the
// temp directory (the scenes, the shared folder, the course index and one lab copied from the
// repository, which is never written): the scaffold parses, renders and passes every check but
// the two that need a corpus; --like copies a lab with its id changed; a taken id, a bad name and
// an unknown lab are refused with nothing written; lab-check finds a stale README table (and
// --fix repairs it), a missing course index row and a stale golden.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.h"

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

const fs::path kRoot = SHADERLAB_SOURCE_DIR;
const char* const kLike = "05-post-processing";
const char* const kNew = "12-normal-mapping";

using shaderlab_test::CliRun;

std::string readText(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

void writeText(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

std::string replaced(std::string text, const std::string& from, const std::string& to) {
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

// The status lab-check printed for one check ("ok", "FAIL", "note", "fixed", "skip"), "" if none.
std::string statusOf(const std::string& output, const std::string& check) {
    std::istringstream lines(output);
    for (std::string line; std::getline(lines, line);) {
        std::smatch m;
        if (std::regex_match(line, m, std::regex("  (\\S+) +(.+?) +[0-9.]+ s  .*")) && m[2] == check)
            return m[1];
    }
    return "";
}

// Every file below `dir`, relative, for "nothing was written".
std::set<std::string> tree(const fs::path& dir) {
    std::set<std::string> out;
    for (const auto& e : fs::recursive_directory_iterator(dir))
        out.insert(fs::relative(e.path(), dir).string());
    return out;
}

class LabAuthoring : public ::testing::Test {
  protected:
    void SetUp() override {
        tmp_ = fs::temp_directory_path() / ("shaderlab_lab_authoring_" + std::to_string(::getpid()) + "_" +
                                            ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(tmp_);
        for (const char* dir : {"labs", "reference_solutions", "tests/corpus", "docs"})
            fs::create_directories(tmp_ / dir);
        for (const char* part : {kLike, "scenes", "shared"})
            fs::copy(kRoot / "labs" / part, labs() / part, fs::copy_options::recursive);
        fs::copy_file(kRoot / "labs" / "README.md", labs() / "README.md");
        fs::copy_file(kRoot / "docs" / "corpus.schema.json", tmp_ / "docs" / "corpus.schema.json");
    }
    void TearDown() override { fs::remove_all(tmp_); }

    fs::path labs() const { return tmp_ / "labs"; }
    fs::path lab() const { return labs() / kNew; }

    CliRun shaderlab(const std::string& args) const {
        return shaderlab_test::runShell(std::string(SHADERLAB_CLI) + " " + args + " --labs " +
                                        labs().string());
    }
    CliRun labCheck(const std::string& options = "") const {
        return shaderlab("lab-check " + std::string(kNew) + " --out " + (tmp_ / "out").string() + options);
    }
    // The scaffold with its goldens: what an instructor has after the first two commands.
    void scaffold() const {
        const CliRun made = shaderlab("new-lab " + std::string(kNew));
        ASSERT_EQ(made.exit_code, 0) << made.output;
        const CliRun goldens = shaderlab("goldens --lab " + std::string(kNew));
        ASSERT_EQ(goldens.exit_code, 0) << goldens.output;
    }

    fs::path tmp_;
};

TEST_F(LabAuthoring, TheScaffoldPassesLabCheckButForItsCorpus) {
    const CliRun made = shaderlab("new-lab " + std::string(kNew));
    ASSERT_EQ(made.exit_code, 0) << made.output;
    for (const char* step :
         {"shaderlab goldens --lab 12-normal-mapping", "shaderlab corpus add-case 12-normal-mapping",
          "shaderlab lab-check 12-normal-mapping"})
        EXPECT_NE(made.output.find(step), std::string::npos) << step << "\n" << made.output;

    const json lab_json = json::parse(readText(lab() / "lab.json"));
    EXPECT_EQ(lab_json["$schema"], "../../docs/lab.schema.json");
    EXPECT_EQ(lab_json["schema"], 2);
    EXPECT_EQ(lab_json["id"], kNew);
    EXPECT_EQ(lab_json["title"], "Normal mapping");
    EXPECT_EQ(readText(tmp_ / "reference_solutions" / kNew / "shade.frag"), readText(lab() / "shade.frag"));
    const json cases = json::parse(readText(tmp_ / "tests" / "corpus" / kNew / "cases.json"));
    EXPECT_EQ(cases["$schema"], "../../../docs/corpus.schema.json");
    EXPECT_EQ(cases["lab"], kNew);
    EXPECT_TRUE(cases["cases"].empty());
    const std::string index = readText(labs() / "README.md");
    EXPECT_NE(index.find("| [12-normal-mapping](12-normal-mapping/README.md) | "), std::string::npos)
        << index;
    // Among the lab rows, after the last of them: the course's order.
    EXPECT_LT(index.find("[11-shadow-mapping]("), index.find("[12-normal-mapping]("));
    const std::string readme = readText(lab() / "README.md");
    for (const char* section :
         {"# Lab 12: Normal mapping", "## The idea", "## What to implement", "## Pitfalls",
          "## Learning goals", "## How it is graded", "## Try it",
          "<!-- generated by shaderlab lab-check --fix: goals -->",
          "<!-- generated by shaderlab lab-check --fix: scenes -->", "<!-- end generated -->",
          "| `teapot` | `scenes/teapot.gltf` | `second_idea` | `shade` |"})
        EXPECT_NE(readme.find(section), std::string::npos) << section << "\n" << readme;

    // Before its goldens: every check but the goldens' and the corpus's.
    const CliRun before = labCheck();
    EXPECT_EQ(before.exit_code, 1) << before.output;
    EXPECT_EQ(statusOf(before.output, "goldens fresh"), "FAIL") << before.output;
    EXPECT_NE(before.output.find("labs/12-normal-mapping/golden/ is missing"), std::string::npos)
        << before.output;

    const CliRun goldens = shaderlab("goldens --lab " + std::string(kNew));
    ASSERT_EQ(goldens.exit_code, 0) << goldens.output;
    const CliRun r = labCheck();
    EXPECT_EQ(r.exit_code, 1) << r.output;
    for (const char* check :
         {"lab.json", "starter", "reference", "course index", "README tables", "goldens fresh"})
        EXPECT_EQ(statusOf(r.output, check), "ok") << check << "\n" << r.output;
    // No mistakes or alternatives yet, and the starter is the reference (nothing solved): it passes.
    EXPECT_EQ(statusOf(r.output, "minimum corpus"), "FAIL") << r.output;
    EXPECT_NE(r.output.find("0 mistakes (at least 6), 0 alternatives (at least 3)"), std::string::npos)
        << r.output;
    EXPECT_EQ(statusOf(r.output, "corpus verdicts"), "FAIL") << r.output;
    EXPECT_NE(r.output.find("starter (starter): must render and fail"), std::string::npos) << r.output;
    // Nothing solved: the reference is the starter, whose code mutants leaves alone.
    EXPECT_EQ(statusOf(r.output, "mutants"), "FAIL") << r.output;
    EXPECT_NE(r.output.find("no mutants: the reference's student files are the starter's"), std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("lab-check 12-normal-mapping: 6 of 9 checks passed, 3 failed"), std::string::npos)
        << r.output;
}

TEST_F(LabAuthoring, LikeCopiesALabWithItsIdAndTitleChanged) {
    const CliRun r = shaderlab("new-lab 13-filters --like " + std::string(kLike) + " --title \"My filters\"");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const fs::path like = labs() / kLike, copy = labs() / "13-filters";
    json expected = json::parse(readText(like / "lab.json"));
    expected["id"] = "13-filters";
    expected["title"] = "My filters";
    EXPECT_EQ(json::parse(readText(copy / "lab.json")), expected);
    // Written as the original is, but for the two values.
    const std::string original = readText(like / "lab.json");
    EXPECT_EQ(
        readText(copy / "lab.json"),
        replaced(replaced(original, "\"id\": \"05-post-processing\"", "\"id\": \"13-filters\""),
                 "\"title\": " + json(json::parse(original)["title"]).dump(), "\"title\": \"My filters\""));
    const json spec = json::parse(readText(like / "lab.json"));
    for (const json& f : spec["student_files"]) {
        EXPECT_EQ(readText(copy / f.get<std::string>()), readText(like / f.get<std::string>())) << f;
        EXPECT_EQ(readText(tmp_ / "reference_solutions" / "13-filters" / f.get<std::string>()),
                  readText(like / f.get<std::string>()))
            << f;
    }
    EXPECT_EQ(readText(copy / "scene.vert"), readText(like / "scene.vert"));  // the lab's own shaders too
    EXPECT_FALSE(fs::exists(copy / "golden"));
    EXPECT_FALSE(fs::exists(copy / "hints"));
    // The README's headings are the original's, its goals and scenes tables the copy's.
    const std::string readme = readText(copy / "README.md");
    for (const char* heading :
         {"# Lab 13: My filters", "### Texels, texel centres and the texel size", "### Sobel edges",
          "## Learning goals", "## How it is graded", "| `cube_flat` | `scenes/cube_flat.gltf` | "})
        EXPECT_NE(readme.find(heading), std::string::npos) << heading << "\n" << readme;
    for (const json& g : spec["goals"])
        EXPECT_NE(readme.find("(`" + g["id"].get<std::string>() + "`) | "), std::string::npos) << g << "\n"
                                                                                               << readme;
    const CliRun check = shaderlab("lab-check 13-filters --out " + (tmp_ / "out").string());
    EXPECT_EQ(statusOf(check.output, "lab.json"), "ok") << check.output;
    EXPECT_EQ(statusOf(check.output, "README tables"), "ok") << check.output;
}

TEST_F(LabAuthoring, RefusesATakenIdABadNameAndAnUnknownLabWritingNothing) {
    const std::string index = readText(labs() / "README.md");
    auto refused = [&](const std::string& args, const std::string& reason) {
        const std::set<std::string> before = tree(tmp_);
        const CliRun r = shaderlab(args);
        EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.output;
        EXPECT_NE(r.output.find(reason), std::string::npos) << args << "\n" << r.output;
        EXPECT_EQ(tree(tmp_), before) << args;
        EXPECT_EQ(readText(labs() / "README.md"), index) << args;
    };
    refused("new-lab " + std::string(kLike),
            "labs/05-post-processing exists already: 05-post-processing is taken");
    refused("new-lab shared", "shared exists already");
    fs::create_directories(tmp_ / "tests" / "corpus" / "14-left-over");
    refused("new-lab 14-left-over", "tests/corpus/14-left-over exists already");
    fs::remove(tmp_ / "tests" / "corpus" / "14-left-over");
    refused("new-lab \"12 normal mapping\"",
            "ID \"12 normal mapping\" must be 1 to 64 letters, digits, '_' or '-'");
    refused("new-lab ../12-up", "ID \"../12-up\" must be");
    refused("new-lab 12-x --like 05-post-procesing", "--like 05-post-procesing: there is no such lab in " +
                                                         labs().string() +
                                                         " (did you mean \"05-post-processing\"?)");
    refused("lab-check 05-post-procesing", "there is no lab \"05-post-procesing\" in " + labs().string() +
                                               " (did you mean \"05-post-processing\"?)");
}

TEST_F(LabAuthoring, LabCheckFindsAStaleReadmeTableAndFixRewritesIt) {
    scaffold();
    const fs::path readme = lab() / "README.md";
    // A goal renamed and its points moved: the goals table no longer says what lab.json does.
    std::string lab_json = readText(lab() / "lab.json");
    lab_json = replaced(lab_json, "TODO: a second idea: the parts put together\", \"points\": 5",
                        "Shading put together\", \"points\": 6");
    lab_json = replaced(lab_json, "a student learns, in a few words\", \"points\": 5",
                        "a student learns, in a few words\", \"points\": 4");
    writeText(lab() / "lab.json", lab_json);
    const std::string stale = readText(readme);
    const CliRun r = labCheck();
    EXPECT_EQ(statusOf(r.output, "README tables"), "FAIL") << r.output;
    EXPECT_NE(
        r.output.find("labs/12-normal-mapping/README.md: the goals table is not what lab.json says: run "
                      "`shaderlab lab-check 12-normal-mapping --fix`"),
        std::string::npos)
        << r.output;
    EXPECT_EQ(readText(readme), stale);  // without --fix nothing is written

    const CliRun fixed = labCheck(" --fix");
    EXPECT_EQ(statusOf(fixed.output, "README tables"), "fixed") << fixed.output;
    std::string expected = replaced(
        stale, "TODO: a second idea: the parts put together (`second_idea`) | `main` in shade.frag | 5",
        "Shading put together (`second_idea`) | `main` in shade.frag | 6");
    expected = replaced(expected, "(`first_idea`) | `lightAt` in shade.frag | 5",
                        "(`first_idea`) | `lightAt` in shade.frag | 4");
    EXPECT_EQ(readText(readme), expected);  // the text outside the markers as it was
    EXPECT_EQ(statusOf(labCheck().output, "README tables"), "ok");

    // Markers that do not pair up: said, with the line; nothing fixed.
    writeText(readme, "# x\n\n<!-- generated by shaderlab lab-check --fix: goals -->\n| goal |\n");
    const CliRun open = labCheck(" --fix");
    EXPECT_EQ(statusOf(open.output, "README tables"), "FAIL") << open.output;
    EXPECT_NE(open.output.find("README.md: line 3: the generated block \"goals\" is not closed"),
              std::string::npos)
        << open.output;
    EXPECT_EQ(readText(readme), "# x\n\n<!-- generated by shaderlab lab-check --fix: goals -->\n| goal |\n");
    // A README without markers is the instructor's own: a note, not a failure.
    writeText(readme, "# Lab 12: Normal mapping\n\nWritten by hand.\n");
    const CliRun hand = labCheck(" --fix");
    EXPECT_EQ(statusOf(hand.output, "README tables"), "note") << hand.output;
    EXPECT_EQ(readText(readme), "# Lab 12: Normal mapping\n\nWritten by hand.\n");
}

TEST_F(LabAuthoring, LabCheckFindsAMissingCourseIndexRow) {
    scaffold();
    const std::string index = readText(labs() / "README.md");
    const std::size_t row = index.find("| [12-normal-mapping](");
    ASSERT_NE(row, std::string::npos);
    writeText(labs() / "README.md", index.substr(0, row) + index.substr(index.find('\n', row) + 1));
    const CliRun r = labCheck();
    EXPECT_EQ(statusOf(r.output, "course index"), "FAIL") << r.output;
    EXPECT_NE(
        r.output.find("labs/README.md has no row linking [12-normal-mapping](12-normal-mapping/README.md)"),
        std::string::npos)
        << r.output;
}

TEST_F(LabAuthoring, LabCheckFindsAStaleGolden) {
    scaffold();
    const fs::path golden = lab() / "golden";
    fs::copy_file(golden / "teapot.png", golden / "sphere.png", fs::copy_options::overwrite_existing);
    const CliRun r = labCheck();
    EXPECT_EQ(r.exit_code, 1) << r.output;
    EXPECT_EQ(statusOf(r.output, "goldens fresh"), "FAIL") << r.output;
    EXPECT_NE(
        r.output.find("labs/12-normal-mapping/golden/sphere.png is stale: not what the reference draws now "
                      "(run `shaderlab goldens --lab 12-normal-mapping`)"),
        std::string::npos)
        << r.output;
    // A changed reference makes every golden it draws differently stale.
    const CliRun again = shaderlab("goldens --lab " + std::string(kNew));
    ASSERT_EQ(again.exit_code, 0) << again.output;
    EXPECT_EQ(statusOf(labCheck().output, "goldens fresh"), "ok");
    const fs::path solved = tmp_ / "reference_solutions" / kNew / "shade.frag";
    writeText(solved,
              replaced(readText(solved), "o_color = vec4(color, 1.0);", "o_color = vec4(color + 0.3, 1.0);"));
    const CliRun changed = labCheck();
    EXPECT_EQ(statusOf(changed.output, "goldens fresh"), "FAIL") << changed.output;
    EXPECT_NE(changed.output.find("golden/sphere.png is stale"), std::string::npos) << changed.output;
}

}  // namespace
