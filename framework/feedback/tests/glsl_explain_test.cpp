// The explanations on their own, without a driver: Mesa's words as it writes them, the student's
// text as prepareSource numbers it. The driver's real logs, compiled by llvmpipe, are the render
// library's tests (framework/render/tests/compile_errors_test.cpp).
#include "shaderlab/feedback/glsl_explain.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace {

using shaderlab::Diagnostic;
using shaderlab::StageText;

StageText stage(const std::string& kind, const std::string& file, const std::string& text) {
    return StageText{kind, {file}, {text}};
}

TEST(GlslExplain, MesaColumnsCountARunOfBlanksAsOne) {
    // glcpp writes "  float  x" as " float x": Mesa's column 8 is the 'x'.
    EXPECT_EQ(shaderlab::sourceColumnOfMesa("  float  x = 1.0;", 8), 10);
    EXPECT_EQ(shaderlab::sourceColumnOfMesa("float x;", 1), 1);
    EXPECT_EQ(shaderlab::sourceColumnOfMesa("x;", 40), 0) << "past the end is unknown";
}

TEST(GlslExplain, LegacyGlslIsAWarningAtItsLine) {
    const StageText frag = stage("fragment", "toon.frag",
                                 "#version 330 core\n"
                                 "uniform sampler2D u_ramp;\n"
                                 "void main() {\n"
                                 "    gl_FragColor = texture2D(u_ramp, vec2(0.5));\n"
                                 "}\n");
    const std::vector<Diagnostic> found = shaderlab::scanStage(frag);
    ASSERT_EQ(found.size(), 2u);
    for (const Diagnostic& d : found) {
        EXPECT_EQ(d.severity, "warning");
        EXPECT_EQ(d.file, "toon.frag");
        EXPECT_EQ(d.line, 4);
        EXPECT_NE(d.message.find("old GLSL"), std::string::npos) << d.message;
        EXPECT_EQ(d.source_line, "    gl_FragColor = texture2D(u_ramp, vec2(0.5));");
    }
    EXPECT_NE(found[0].message.find("gl_FragColor"), std::string::npos) << found[0].message;
    EXPECT_NE(found[1].explanation.find("texture(...)"), std::string::npos) << found[1].explanation;
}

TEST(GlslExplain, AFragmentInputWithoutAnOutputIsPlacedAtItsDeclarationWithAGuess) {
    const StageText vert = stage("vertex", "phong.vert",
                                 "#version 330 core\n"
                                 "out vec3 v_normal;\n"
                                 "void main() { v_normal = vec3(0.0); gl_Position = vec4(0.0); }\n");
    const StageText frag = stage("fragment", "phong.frag",
                                 "#version 330 core\n"
                                 "in vec3 v_normals;\n"
                                 "out vec4 o_color;\n"
                                 "void main() { o_color = vec4(v_normals, 1.0); }\n");
    const std::string log =
        "error: fragment shader input `v_normals' has no matching output in the previous stage\n";
    const std::vector<Diagnostic> found = shaderlab::explainLinkLog(log, vert, frag);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].severity, "error");
    EXPECT_EQ(found[0].file, "phong.frag");
    EXPECT_EQ(found[0].line, 2);
    EXPECT_NE(found[0].message.find("did you mean `v_normal`?"), std::string::npos) << found[0].message;
    EXPECT_NE(found[0].driver_message.find("v_normals"), std::string::npos) << found[0].driver_message;
}

TEST(GlslExplain, AnUnknownLinkMessagePassesThroughWithItsWords) {
    const StageText vert = stage("vertex", "a.vert", "#version 330 core\nvoid main() {}\n");
    const StageText frag = stage("fragment", "a.frag", "#version 330 core\nvoid main() {}\n");
    const std::vector<Diagnostic> found =
        shaderlab::explainLinkLog("error: something no one has seen before\n", vert, frag);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_NE(found[0].message.find("something no one has seen before"), std::string::npos)
        << found[0].message;
}

// Mesa's "size mismatch for matrix multiplication" names no operator and no type: the caret goes
// under the `*` whose sides do not agree, and the message names both sides with their types.
TEST(GlslExplain, AMatrixProductOfTheWrongSizesNamesBothTypesAtTheOperator) {
    const std::string line = "    gl_Position = u_view_projection * u_model * a_position;";
    const StageText vert = stage("vertex", "phong.vert",
                                 "#version 330 core\n"
                                 "layout(location = 0) in vec3 a_position;\n"
                                 "uniform mat4 u_model;\n"
                                 "uniform mat4 u_view_projection;\n"
                                 "void main() {\n" +
                                     line +
                                     "\n"
                                     "}\n");
    const std::vector<Diagnostic> parsed = {
        {"phong.vert", 6, 19, "error", "size mismatch for matrix multiplication"}};
    const std::vector<Diagnostic> found = shaderlab::explainCompileLog(parsed, vert, nullptr);
    ASSERT_EQ(found.size(), 1u);
    const Diagnostic& d = found[0];
    EXPECT_EQ(d.line, 6);
    EXPECT_EQ(d.source_line, line);
    // The second `*`: the product of the two matrices is a mat4, the position a vec3.
    EXPECT_EQ(d.column, static_cast<int>(line.rfind('*')) + 1) << d.message;
    EXPECT_NE(d.message.find("`u_view_projection * u_model` is a mat4"), std::string::npos) << d.message;
    EXPECT_NE(d.message.find("`a_position` a vec3"), std::string::npos) << d.message;
    EXPECT_NE(d.explanation.find("vec4(a_position, 1.0)"), std::string::npos) << d.explanation;
    EXPECT_EQ(d.driver_message, "size mismatch for matrix multiplication");
}

TEST(GlslExplain, AVectorOnTheLeftOfAMatrixAndSwizzlesAreTyped) {
    const std::string line = "    vec3 n = v_normal.xyz * u_normal_matrix;";
    const StageText frag = stage("fragment", "phong.frag",
                                 "#version 330 core\n"
                                 "in vec4 v_normal;\n"
                                 "uniform mat3x4 u_normal_matrix;\n"
                                 "void main() {\n" +
                                     line + "\n}\n");
    const std::vector<Diagnostic> found = shaderlab::explainCompileLog(
        {{"phong.frag", 5, 14, "error", "size mismatch for matrix multiplication"}}, frag, nullptr);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].column, static_cast<int>(line.find('*')) + 1);
    EXPECT_NE(found[0].message.find("`v_normal.xyz` is a vec3 and `u_normal_matrix` a mat3x4"),
              std::string::npos)
        << found[0].message;
    EXPECT_NE(found[0].explanation.find("row"), std::string::npos) << found[0].explanation;
}

TEST(GlslExplain, AMatrixProductItCannotTypeStaysGeneralWithoutGuessing) {
    const StageText vert = stage("vertex", "a.vert",
                                 "#version 330 core\n"
                                 "struct S { mat4 m; };\n"
                                 "uniform S u_s;\n"
                                 "void main() { gl_Position = (u_s.m) * vec3(1.0); }\n");
    const std::vector<Diagnostic> found = shaderlab::explainCompileLog(
        {{"a.vert", 4, 27, "error", "size mismatch for matrix multiplication"}}, vert, nullptr);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].message, "the sizes in this matrix product do not agree");
    EXPECT_NE(found[0].explanation.find("mat4 * vec3"), std::string::npos) << found[0].explanation;
}

}  // namespace
