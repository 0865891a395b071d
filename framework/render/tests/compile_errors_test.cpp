// The corpus of common student compile errors, tests/compile_errors/<case>/: each case is lab
// 01-phong's reference solution with one mistake (the case folder holds the files that differ),
// and expected.json says where the first diagnostic must point (file, line, optionally column)
// and a phrase its plain words must hold. Every case also checks that no parser jargon reaches
// the student, that one root cause gives at most one error, and that a caret stays on its line.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <regex>
#include <sstream>

#include "gl_test_support.h"
#include "shaderlab/feedback/glsl_explain.h"
#include "shaderlab/render/shader_program.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using shaderlab::Diagnostic;

const fs::path kCorpus = fs::path(SHADERLAB_SOURCE_DIR) / "tests" / "compile_errors";
const fs::path kReference = fs::path(SHADERLAB_SOURCE_DIR) / "reference_solutions" / "01-phong";

std::string readText(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

std::vector<std::string> caseNames() {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(kCorpus))
        if (fs::exists(e.path() / "expected.json")) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

std::string describe(const std::vector<Diagnostic>& diagnostics) {
    std::string s;
    for (const Diagnostic& d : diagnostics)
        s += "\n  " + d.file + ":" + std::to_string(d.line) + ":" + std::to_string(d.column) + ": " +
             d.severity + ": " + d.message + "\n    = " + d.explanation +
             "\n    driver: " + d.driver_message + "\n    follow-on: " + std::to_string(d.follow_on);
    return s;
}

class CompileErrorCorpus : public ::testing::TestWithParam<std::string> {};

TEST_P(CompileErrorCorpus, FirstDiagnosticTeaches) {
    std::string err;
    ASSERT_NE(shaderlab::testing::sharedContext(shaderlab::Backend::OSMesa, &err), nullptr) << err;
    const fs::path dir = kCorpus / GetParam();
    const json expected = json::parse(readText(dir / "expected.json"));
    auto source = [&](const std::string& name) {
        return readText(fs::exists(dir / name) ? dir / name : kReference / name);
    };
    shaderlab::ShaderProgram p;
    const bool built = p.build("phong.vert", source("phong.vert"), "phong.frag", source("phong.frag"));
    const std::vector<Diagnostic>& all = p.diagnostics();
    const std::string severity = expected.value("severity", "error");
    EXPECT_EQ(built, severity != "error") << describe(all);

    const Diagnostic* first = nullptr;
    int errors = 0;
    for (const Diagnostic& d : all) {
        if (!first && d.severity == severity) first = &d;
        errors += d.severity == "error";
    }
    ASSERT_NE(first, nullptr) << describe(all);
    EXPECT_EQ(first->file, expected.at("file").get<std::string>()) << describe(all);
    EXPECT_EQ(first->line, expected.at("line").get<int>()) << describe(all);
    if (expected.contains("column")) {
        EXPECT_EQ(first->column, expected["column"].get<int>()) << describe(all);
    }
    const std::string phrase = expected.at("phrase");
    EXPECT_NE((first->message + " " + first->explanation).find(phrase), std::string::npos)
        << "wanted \"" << phrase << "\"" << describe(all);
    EXPECT_LE(errors, 1) << "one root cause, one error" << describe(all);

    static const std::regex jargon(R"(_TOK\b|IDENTIFIER|CONSTANT\b|syntax error, unexpected|\$end)");
    for (const Diagnostic& d : all) {
        EXPECT_FALSE(std::regex_search(d.message, jargon)) << d.message;
        EXPECT_FALSE(std::regex_search(d.explanation, jargon)) << d.explanation;
        if (d.column > 0) {
            EXPECT_FALSE(d.source_line.empty()) << describe(all);
            EXPECT_LE(static_cast<std::size_t>(d.column), d.source_line.size() + 1) << describe(all);
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Cases, CompileErrorCorpus, ::testing::ValuesIn(caseNames()),
                         [](const ::testing::TestParamInfo<std::string>& param) {
                             std::string name = param.param;
                             std::replace(name.begin(), name.end(), '-', '_');
                             return name;
                         });

// Whatever the student types: a few hundred random edits of the reference never crash the
// explainer, never leak parser jargon and never put a caret off its line.
TEST(CompileErrorMutations, NeverLeakJargonOrStrayCarets) {
    std::string err;
    ASSERT_NE(shaderlab::testing::sharedContext(shaderlab::Backend::OSMesa, &err), nullptr) << err;
    const std::string vertex = readText(kReference / "phong.vert"),
                      fragment = readText(kReference / "phong.frag");
    ASSERT_FALSE(fragment.empty());
    const char* const junk[] = {
        ";",  "{",  "}",  "(",     ")",          "vec3",    "float", "x", ".", "=",    "#", "/*", "*/",
        "//", "\n", "\t", "1 / 2", "texture2D(", "varying", "error", "'", "`", "\xff", "[", "]"};
    std::mt19937 rng(1234);  // fixed: the same edits every run
    static const std::regex jargon(R"(_TOK\b|IDENTIFIER|CONSTANT\b|syntax error, unexpected|\$end)");
    for (int i = 0; i < 300; ++i) {
        std::string text = fragment;
        for (unsigned e = 0, edits = 1 + rng() % 4; e < edits; ++e) {
            const std::size_t at = rng() % text.size();
            if (rng() % 2)
                text.erase(at, 1 + rng() % 6);
            else
                text.insert(at, junk[rng() % (sizeof junk / sizeof *junk)]);
        }
        shaderlab::ShaderProgram p;
        p.build("phong.vert", vertex, "phong.frag", text);
        for (const Diagnostic& d : p.diagnostics()) {
            EXPECT_FALSE(d.message.empty()) << text;
            EXPECT_FALSE(std::regex_search(d.message, jargon)) << d.message;
            EXPECT_FALSE(std::regex_search(d.explanation, jargon)) << d.explanation;
            if (d.column > 0) {
                EXPECT_LE(static_cast<std::size_t>(d.column), d.source_line.size() + 1) << text;
            }
        }
    }
}

TEST(CompileErrorCorpusSize, HoldsAtLeastTenCases) { EXPECT_GE(caseNames().size(), 10u); }

// Mesa counts columns in the preprocessor's output, where each run of blanks and comments is
// one character (measured on Mesa 22.3: `zz` below is its column 33).
TEST(MesaColumns, MapBackToTheSourceLine) {
    const std::string line = "\tvec3  n  =   /* c */ normalize(v_normal) * zz;";
    EXPECT_EQ(shaderlab::sourceColumnOfMesa(line, 33), static_cast<int>(line.find("zz")) + 1);
    EXPECT_EQ(shaderlab::sourceColumnOfMesa(line, 2), static_cast<int>(line.find("vec3")) + 1);
    EXPECT_EQ(shaderlab::sourceColumnOfMesa(line, 1), 0);  // the leading tab: no token
    EXPECT_EQ(shaderlab::sourceColumnOfMesa("o_color = c;", 1), 1);
    EXPECT_EQ(shaderlab::sourceColumnOfMesa("  vec3 m=n/**/+yy;", 12), 16);
    EXPECT_EQ(shaderlab::sourceColumnOfMesa("x;", 40), 0);
}

}  // namespace
