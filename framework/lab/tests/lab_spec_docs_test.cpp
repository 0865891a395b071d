// Tests that docs/lab-format.md and docs/lab.schema.json stay true to the lab.json parser
// (framework/lab/src/lab_spec*.cpp): the complete, the smallest and the template examples of the
// docs parse; the compiled-in schema is the docs' file, accepts the example and refuses a mistake;
// the uniforms a lab may not set are those docs/student-contract.md lists as the framework's.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "lab_spec_fixture.h"
#include "shaderlab/lab/json_schema_check.h"
#include "shaderlab/lab/lab_spec.h"

namespace {

using namespace lab_spec_test;

std::string readText(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// =============================================================================================
// docs/lab-format.md and docs/lab.schema.json stay true

// The `n`th ```json block after the heading `heading` of docs/lab-format.md.
std::string jsonBlockOfTheDocs(const std::string& heading, int n) {
    const std::string doc = readText(fs::path(SHADERLAB_SOURCE_DIR) / "docs" / "lab-format.md");
    std::size_t at = doc.find("\n" + heading + "\n");
    if (at == std::string::npos) return "";
    for (int i = 0; i <= n; ++i) {
        at = doc.find("```json\n", at);
        if (at == std::string::npos) return "";
        at += 8;
        if (i < n) at = doc.find("```", at) + 3;
    }
    const std::size_t end = doc.find("```", at);
    return end == std::string::npos ? "" : doc.substr(at, end - at);
}

using LabSpecDocs = LabSpecFixture;

TEST_F(LabSpecDocs, TheCompleteExampleParses) {
    const std::string text = jsonBlockOfTheDocs("## A complete example", 0);
    ASSERT_FALSE(text.empty()) << "no ```json block under \"## A complete example\" in docs/lab-format.md";
    const json doc = json::parse(text);
    const fs::path lab = labs_ / doc.at("id").get<std::string>();
    // Every file it names, empty: the parser checks that files exist, not what they hold.
    auto create = [&](const std::string& path) {
        writeFile(path.rfind("shared/", 0) == 0 ? labs_ / path : lab / path, "");
    };
    auto programs = [&](const json& pass) {
        if (!pass.contains("program")) return;
        for (const auto& stage : pass["program"].items()) create(stage.value());
        if (pass.contains("inputs"))
            for (const auto& in : pass["inputs"].items())
                if (in.value().is_object() && in.value().contains("texture")) create(in.value()["texture"]);
    };
    for (const json& pass : doc.at("passes")) programs(pass);
    const json templates = doc.value("templates", json::object());
    for (const auto& t : templates.items()) programs(t.value());
    const json student_files = doc.value("student_files", json::array());
    for (const json& f : student_files) create(f);
    for (const json& scene : doc.at("scenes"))
        if (scene.contains("file")) writeFile(labs_ / scene["file"].get<std::string>(), "{}");
    writeFile(lab / "lab.json", text);

    const LabSpecResult r = shaderlab::parseLabSpec(lab.string());
    ASSERT_TRUE(r.ok) << allErrors(r);
    // What the prose around it says.
    const shaderlab::LabSpec& s = r.spec;
    EXPECT_EQ(s.id, "42-example");
    std::vector<std::string> scenes;
    for (const shaderlab::SceneSpec& sc : s.scenes) scenes.push_back(sc.name);
    EXPECT_EQ(scenes, (std::vector<std::string>{"teapot_t0", "teapot_t1", "grazing"}));  // two times
    const shaderlab::TargetSpec* half = s.findTarget("half_a");
    ASSERT_NE(half, nullptr);
    EXPECT_EQ(half->width, s.width / 2);  // half size
    const shaderlab::TargetSpec* gbuffer = s.findTarget("gbuffer");
    ASSERT_NE(gbuffer, nullptr);
    EXPECT_EQ(gbuffer->attachments.size(), 2u);  // two attachments
    EXPECT_EQ(s.findPass("blur_h")->program.fragment,
              s.findPass("blur_v")->program.fragment);  // one template
    EXPECT_EQ(s.findPass("combine")->draw, shaderlab::DrawKind::Fullscreen);
    EXPECT_EQ(s.goals.size(), 3u);
    EXPECT_FLOAT_EQ(s.grading.points, 10.0f);
    EXPECT_EQ(s.student_files, doc.at("student_files").get<std::vector<std::string>>());
}

TEST_F(LabSpecDocs, TheSmallestExampleParsesWithTheDefaults) {
    const std::string text = jsonBlockOfTheDocs("## A complete example", 1);
    ASSERT_FALSE(text.empty()) << "no second ```json block under \"## A complete example\"";
    EXPECT_EQ(json::parse(text),
              json::parse(kMinimalSpec));  // what MinimalSpecGetsTheDocumentedDefaults reads
    const LabSpecResult r = parseText(text);
    ASSERT_TRUE(r.ok) << allErrors(r);
    EXPECT_EQ(r.spec.passes[0].graded, (std::vector<std::string>{"color"}));
    EXPECT_EQ(r.spec.goals.size(), 1u);
}

TEST_F(LabSpecDocs, TheTemplateExampleIsAPartOfAValidLab) {
    // The bloom fragment under "Templates": its template, and its two complete pass lines after a
    // pass drawing "bright".
    const std::string text = jsonBlockOfTheDocs("### Templates", 0);
    ASSERT_FALSE(text.empty());
    json spec = json::parse(kMinimalSpec);
    json passes =
        json::parse(R"([{"name": "bright", "program": {"vertex": "phong.vert", "fragment": "post.frag"}}])");
    std::string templates = text.substr(0, text.find("\"passes\""));
    while (!templates.empty() &&
           (templates.back() == ',' || std::isspace(static_cast<unsigned char>(templates.back()))))
        templates.pop_back();
    spec["templates"] = json::parse("{" + templates + "}").at("templates");
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);) {
        line.erase(0, line.find_first_not_of(' '));
        while (!line.empty() && (line.back() == ',' || line.back() == ' ')) line.pop_back();
        if (line.rfind("{ \"name\":", 0) == 0) passes.push_back(json::parse(line));
    }
    ASSERT_EQ(passes.size(), 3u) << text;
    spec["passes"] = passes;
    spec["targets"] = {{"blur0_a", json::object()}, {"blur0_b", json::object()}};
    const LabSpecResult r = parseJson(spec);
    ASSERT_TRUE(r.ok) << allErrors(r);
    EXPECT_EQ(r.spec.passes[1].name, "blur0_h");
    EXPECT_EQ(r.spec.passes[2].program.fragment, "blur.frag");
    EXPECT_EQ(r.spec.passes[2].state.blend, shaderlab::BlendMode::None);
    EXPECT_EQ(r.spec.passes[2].draw, shaderlab::DrawKind::Fullscreen);
}

TEST(LabSchema, TheSchemaFileParsesAndIsTheCompiledInCopy) {
    const std::string text = readText(fs::path(SHADERLAB_SOURCE_DIR) / "docs" / "lab.schema.json");
    ASSERT_FALSE(text.empty());
    const json schema = json::parse(text);  // throws, failing the test, if it is not JSON
    EXPECT_EQ(schema.at("$schema"), "http://json-schema.org/draft-07/schema#");
    EXPECT_EQ(schema.at("required"), json::parse(R"(["schema", "id", "passes", "scenes"])"));
    EXPECT_EQ(shaderlab::labSchemaText(), text);
}

TEST(LabSchema, ItAcceptsTheDocsExampleAndRefusesAMistake) {
    const json schema = json::parse(shaderlab::labSchemaText());
    const shaderlab::JsonSchemaChecker checker(schema);
    json doc = json::parse(jsonBlockOfTheDocs("## A complete example", 0));
    EXPECT_TRUE(checker.check(doc).empty());
    doc["passes"][0]["state"]["cull"] = "sideways";
    const std::vector<shaderlab::SchemaProblem> problems = checker.check(doc);
    ASSERT_EQ(problems.size(), 1u);
    EXPECT_EQ(problems[0].path, "passes[0].state.cull");
}

// The uniforms a lab may not set are those docs/student-contract.md lists as the framework's
// (a `u_has_*_texture` there stands for the names it matches).
TEST(LabSchema, TheRefusedUniformNamesAreTheFrameworksInTheStudentContract) {
    const std::string contract = readText(fs::path(SHADERLAB_SOURCE_DIR) / "docs" / "student-contract.md");
    const std::size_t begin = contract.find("## Uniforms the framework provides");
    const std::size_t end = contract.find("\n## ", begin + 1);
    ASSERT_NE(begin, std::string::npos);
    const std::string section = contract.substr(begin, end - begin);
    std::set<std::string> documented, patterns;
    const std::regex row(R"(\n\|[^\n]*)"), name(R"(`(u_[A-Za-z0-9_*]+)`)");
    for (auto r = std::sregex_iterator(section.begin(), section.end(), row); r != std::sregex_iterator();
         ++r) {
        const std::string line = r->str();
        for (auto it = std::sregex_iterator(line.begin(), line.end(), name); it != std::sregex_iterator();
             ++it)
            ((*it)[1].str().find('*') == std::string::npos ? documented : patterns).insert((*it)[1]);
    }
    const json schema = json::parse(shaderlab::labSchemaText());
    std::set<std::string> refused;
    for (const json& part : schema.at("definitions").at("lab_uniform_name").at("allOf"))
        if (part.contains("not"))
            for (const json& n : part.at("not").at("enum")) refused.insert(n.get<std::string>());
    auto matches = [](const std::string& pattern, const std::string& n) {
        return std::regex_match(
            n, std::regex(std::regex_replace(pattern, std::regex(R"(\*)"), "[A-Za-z0-9_]+")));
    };
    EXPECT_GE(documented.size(), 10u);
    for (const std::string& d : documented)
        EXPECT_TRUE(refused.count(d)) << d << " is documented, not refused";
    for (const std::string& p : patterns)
        EXPECT_TRUE(
            std::any_of(refused.begin(), refused.end(), [&](const std::string& n) { return matches(p, n); }))
            << p << " is documented and matches no refused name";
    for (const std::string& n : refused)
        EXPECT_TRUE(documented.count(n) || std::any_of(patterns.begin(), patterns.end(),
                                                       [&](const std::string& p) { return matches(p, n); }))
            << n << " is refused but not in docs/student-contract.md";
}

}  // namespace
