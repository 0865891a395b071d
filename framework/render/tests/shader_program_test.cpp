// Compile logs become diagnostics that point at the student's own file and line, whatever the
// framework injected before it.
#include "shaderlab/render/shader_program.h"

#include <gtest/gtest.h>

#include "gl_test_support.h"

namespace {

using shaderlab::Backend;

constexpr const char* kVertex =
    "#version 330 core\n"
    "layout(location = 0) in vec3 a_position;\n"
    "void main() { gl_Position = vec4(a_position, 1.0); }\n";

class ShaderProgramTest : public ::testing::Test {
  protected:
    void SetUp() override {
        std::string err;
        if (!shaderlab::testing::sharedContext(Backend::OSMesa, &err)) FAIL() << err;
    }
};

TEST(PrepareSource, KeepsVersionAndMapsLines) {
    const auto p =
        shaderlab::prepareSource("// header comment\n#version 410 core\nvoid main() {}\n", "#define X 1\n");
    EXPECT_EQ(p.text.rfind("// header comment\n#version 410 core\n#define X 1\n#line 3 0\nvoid main", 0), 0u)
        << p.text;
    EXPECT_EQ(p.first_student_line, 3);
}

TEST(PrepareSource, AddsVersionWhenMissing) {
    const auto p = shaderlab::prepareSource("void main() {}\n", "");
    EXPECT_EQ(p.text, "#version 330 core\n#line 1 0\nvoid main() {}\n");
}

TEST(PrepareSource, IgnoresVersionAfterCode) {
    const auto p = shaderlab::prepareSource("/* a\n b */ float x;\n#version 330\n", "");
    EXPECT_EQ(p.text.rfind("#version 330 core\n#line 1 0\n", 0), 0u) << p.text;
}

TEST(ParseInfoLog, UnderstandsCommonDriverFormats) {
    const auto mesa = shaderlab::parseInfoLog("0:12(5): error: `foo' undeclared\n", "a.frag");
    ASSERT_EQ(mesa.size(), 1u);
    EXPECT_EQ(mesa[0].line, 12);
    EXPECT_EQ(mesa[0].column, 5);
    EXPECT_EQ(mesa[0].severity, "error");
    EXPECT_EQ(mesa[0].file, "a.frag");
    const auto nv =
        shaderlab::parseInfoLog("0(7) : warning C7050: \"x\" might be used before set\n", "a.frag");
    ASSERT_EQ(nv.size(), 1u);
    EXPECT_EQ(nv[0].line, 7);
    EXPECT_EQ(nv[0].severity, "warning");
    const auto khr = shaderlab::parseInfoLog("ERROR: 0:3: 'y' : undeclared identifier\n", "b.vert");
    ASSERT_EQ(khr.size(), 1u);
    EXPECT_EQ(khr[0].line, 3);
    const auto other = shaderlab::parseInfoLog("something odd happened\n", "b.vert");
    ASSERT_EQ(other.size(), 1u);
    EXPECT_EQ(other[0].line, 0);
    EXPECT_EQ(other[0].message, "something odd happened");
}

// The error is on line 6 of the student's file; the prelude adds lines before it.
TEST_F(ShaderProgramTest, CompileErrorPointsAtStudentLine) {
    const std::string frag =
        "#version 330 core\n"            // 1
        "out vec4 o_color;\n"            // 2
        "uniform float u_gain;\n"        // 3
        "void main() {\n"                // 4
        "    float x = u_gain;\n"        // 5
        "    o_color = vec4(y, 1.0);\n"  // 6: y is undeclared
        "}\n";
    shaderlab::ShaderProgram p;
    EXPECT_FALSE(p.build("tri.vert", kVertex, "tri.frag", frag));
    EXPECT_FALSE(p.compiled());
    ASSERT_FALSE(p.diagnostics().empty());
    bool found = false;
    for (const auto& d : p.diagnostics()) {
        if (d.severity == "error" && d.line == 6 && d.file == "tri.frag") found = true;
    }
    EXPECT_TRUE(found) << p.stages().back().info_log;
}

TEST_F(ShaderProgramTest, CompileErrorWithoutVersionLine) {
    const std::string frag =
        "out vec4 o_color;\n"
        "void main() {\n"
        "    o_color = vec4(1.0) * undefined_thing;\n"  // line 3
        "}\n";
    shaderlab::ShaderProgram p;
    EXPECT_FALSE(p.build("tri.vert", kVertex, "tri.frag", frag));
    ASSERT_FALSE(p.diagnostics().empty());
    EXPECT_EQ(p.diagnostics().front().line, 3) << p.stages().back().info_log;
}

TEST_F(ShaderProgramTest, LinkErrorIsReportedAsLinkError) {
    // The stages disagree on the type of a varying: each compiles, the pair does not link.
    const std::string vert =
        "#version 330 core\n"
        "layout(location = 0) in vec3 a_position;\n"
        "out vec3 v_value;\n"
        "void main() { v_value = a_position; gl_Position = vec4(a_position, 1.0); }\n";
    const std::string frag =
        "#version 330 core\n"
        "in vec4 v_value;\n"
        "out vec4 o_color;\n"
        "void main() { o_color = v_value; }\n";
    shaderlab::ShaderProgram p;
    EXPECT_FALSE(p.build("tri.vert", vert, "tri.frag", frag));
    EXPECT_TRUE(p.compiled());
    EXPECT_FALSE(p.linked());
    EXPECT_FALSE(p.linkLog().empty());
    // One diagnostic, at the fragment stage's declaration, naming both files and both types.
    ASSERT_EQ(p.diagnostics().size(), 1u) << p.linkLog();
    const shaderlab::Diagnostic& d = p.diagnostics()[0];
    EXPECT_EQ(d.file, "tri.frag");
    EXPECT_EQ(d.line, 2);
    EXPECT_EQ(d.column, 9);
    EXPECT_EQ(d.source_line, "in vec4 v_value;");
    EXPECT_EQ(d.message, "`v_value` is a vec3 in tri.vert but a vec4 in tri.frag");
    EXPECT_FALSE(d.driver_message.empty());
}

// Mesa prints a link warning once per link step, each followed by a line holding ".": one
// diagnostic remains, placed at the input that nothing writes.
TEST_F(ShaderProgramTest, LinkWarningsAreNotRepeatedOrGarbled) {
    const std::string frag =
        "#version 330 core\n"
        "in vec3 v_missing;\n"
        "out vec4 o_color;\n"
        "void main() { o_color = vec4(v_missing, 1.0); }\n";
    shaderlab::ShaderProgram p;
    ASSERT_TRUE(p.build("tri.vert", kVertex, "tri.frag", frag)) << p.linkLog();
    ASSERT_EQ(p.diagnostics().size(), 1u) << p.linkLog();
    const shaderlab::Diagnostic& d = p.diagnostics()[0];
    EXPECT_EQ(d.severity, "warning");
    EXPECT_EQ(d.file, "tri.frag");
    EXPECT_EQ(d.line, 2);
    EXPECT_NE(d.message.find("tri.vert has no output of that name"), std::string::npos) << d.message;
    EXPECT_EQ(d.message.find('\n'), std::string::npos) << d.message;
    EXPECT_EQ(d.driver_message, "warning: fragment shader varying v_missing not written by vertex shader");
}

// Inputs declared and never used are often a step forgotten; a use inside a macro counts.
TEST_F(ShaderProgramTest, WarnsAboutAFragmentInputNeverUsed) {
    const std::string frag =
        "#version 330 core\n"
        "in vec3 v_a;\n"
        "in vec3 v_b;\n"
        "#define B normalize(v_b)\n"
        "out vec4 o_color;\n"
        "void main() { o_color = vec4(B, 1.0); }\n";
    shaderlab::ShaderProgram p;
    ASSERT_TRUE(p.build("tri.vert", kVertex, "tri.frag", frag)) << p.linkLog();
    int unused = 0;
    for (const shaderlab::Diagnostic& d : p.diagnostics()) {
        if (d.message.find("never used") == std::string::npos) continue;
        ++unused;
        EXPECT_EQ(d.line, 2);
        EXPECT_NE(d.message.find("v_a"), std::string::npos) << d.message;
    }
    EXPECT_EQ(unused, 1);
}

TEST_F(ShaderProgramTest, ReflectsUniformsAndOutputs) {
    const std::string frag =
        "#version 330 core\n"
        "uniform int u_levels;\n"
        "uniform vec3 u_tint[2];\n"
        "out vec4 o_color;\n"
        "void main() { o_color = vec4(u_tint[1] * float(u_levels), 1.0); }\n";
    shaderlab::ShaderProgram p;
    ASSERT_TRUE(p.build("tri.vert", kVertex, "tri.frag", frag)) << p.linkLog();
    ASSERT_NE(p.uniform("u_levels"), nullptr);
    EXPECT_EQ(p.uniform("u_levels")->size, 1);
    ASSERT_NE(p.uniform("u_tint"), nullptr);
    EXPECT_EQ(p.uniform("u_tint")->size, 2);
    EXPECT_EQ(p.uniform("u_not_there"), nullptr);
    ASSERT_TRUE(p.outputsKnown());
    ASSERT_EQ(p.outputs().size(), 1u);
    EXPECT_EQ(p.outputs()[0].name, "o_color");
    EXPECT_EQ(p.outputs()[0].location, 0);
}

}  // namespace

namespace {

// The same mistake on line 6, under every way of starting the file.
class LineMappingTest : public ::testing::TestWithParam<const char*> {};

TEST_P(LineMappingTest, ErrorOnLineSixIsReportedOnLineSix) {
    std::string err;
    ASSERT_NE(shaderlab::testing::sharedContext(shaderlab::Backend::OSMesa, &err), nullptr) << err;
    const std::string frag = std::string(GetParam()) +        // line 1
                             "out vec4 o_color;\n"            // 2
                             "uniform float u_gain;\n"        // 3
                             "void main() {\n"                // 4
                             "    float x = u_gain;\n"        // 5
                             "    o_color = vec4(y, 1.0);\n"  // 6
                             "}\n";
    shaderlab::ShaderProgram p;
    EXPECT_FALSE(p.build("tri.vert", kVertex, "tri.frag", frag));
    ASSERT_FALSE(p.diagnostics().empty());
    EXPECT_EQ(p.diagnostics().front().line, 6) << p.stages().back().info_log;
}

// Mesa notices a missing ';' at the next token; the diagnostic points at the line lacking it,
// whatever the version's #line rule.
TEST_P(LineMappingTest, MissingSemicolonOnLineFiveIsReportedOnLineFive) {
    std::string err;
    ASSERT_NE(shaderlab::testing::sharedContext(shaderlab::Backend::OSMesa, &err), nullptr) << err;
    const std::string frag = std::string(GetParam()) +              // line 1
                             "out vec4 o_color;\n"                  // 2
                             "uniform float u_gain;\n"              // 3
                             "void main() {\n"                      // 4
                             "    float x = u_gain\n"               // 5: no ';'
                             "    o_color = vec4(x, x, x, 1.0);\n"  // 6: where Mesa notices
                             "}\n";
    shaderlab::ShaderProgram p;
    EXPECT_FALSE(p.build("tri.vert", kVertex, "tri.frag", frag));
    ASSERT_FALSE(p.diagnostics().empty());
    const shaderlab::Diagnostic& d = p.diagnostics().front();
    EXPECT_EQ(d.line, 5) << p.stages().back().info_log;
    EXPECT_EQ(d.column, 21);  // just after `u_gain`
    EXPECT_EQ(d.source_line, "    float x = u_gain");
    EXPECT_EQ(d.message, "missing `;` at the end of this line");
}

INSTANTIATE_TEST_SUITE_P(Versions, LineMappingTest,
                         ::testing::Values("#version 330 core\n", "#version 450 core\n", "#version 150\n",
                                           "#version 140\n", "\xEF\xBB\xBF#version 330 core\n",
                                           "// no version directive\n"));

// Mesa lists a call's candidates as indented messages at the call's position: they belong to it.
TEST(ParseInfoLog, FoldsMesaCandidateLines) {
    const auto d = shaderlab::parseInfoLog(
        "0:6(12): error: no matching function for call to `dot(vec3)'; candidates are:\n"
        "0:6(12): error:    float dot(float, float)\n"
        "0:6(12): error:    float dot(vec3, vec3)\n"
        "0:7(3): error: `x' undeclared\n",
        "a.frag");
    ASSERT_EQ(d.size(), 2u);
    EXPECT_NE(d[0].message.find("\nfloat dot(vec3, vec3)"), std::string::npos) << d[0].message;
    EXPECT_EQ(d[1].line, 7);
}

TEST(ParseInfoLog, MesaPreprocessorErrorsKeepTheirLine) {
    const auto d = shaderlab::parseInfoLog("0:4(1): preprocessor error: #error boom\n", "a.frag");
    ASSERT_EQ(d.size(), 1u);
    EXPECT_EQ(d[0].line, 4);
    EXPECT_EQ(d[0].severity, "error");
}

}  // namespace
