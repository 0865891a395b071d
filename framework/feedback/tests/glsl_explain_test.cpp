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

}  // namespace
