// A message shown with the lines around it, read from the student's folder only when the file
// still says what the message quotes, and never from outside that folder.
#include "shaderlab/live/diagnostic_view.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;
using shaderlab::Diagnostic;
using shaderlab::viewer::DiagnosticView;

namespace {

fs::path scratch(const std::string& name) {
    const fs::path p =
        fs::temp_directory_path() / ("shaderlab_live_" + name + "_" + std::to_string(getpid()));
    fs::remove_all(p);
    fs::create_directories(p);
    return p;
}

void write(const fs::path& p, const std::string& text) {
    std::ofstream out(p, std::ios::binary);
    out << text;
}

const char* kFrag =
    "#version 330 core\n"
    "in vec3 v_world_normal;\n"
    "out vec4 o_color;\n"
    "void main() {\n"
    "    vec3 n = normalize(v_world_normal)\n"
    "    o_color = vec4(n, 1.0);\n"
    "}\n";

Diagnostic missingSemicolon() {
    Diagnostic d{"phong.frag", 5, 39, "error", "a `;` is missing at the end of this line"};
    d.explanation = "Every statement ends with `;`.";
    d.source_line = "    vec3 n = normalize(v_world_normal)";
    return d;
}

TEST(DiagnosticView, TheLinesAroundTheErrorWithTheCaretUnderItsLine) {
    const fs::path dir = scratch("around");
    write(dir / "phong.frag", kFrag);
    const DiagnosticView v = shaderlab::viewer::viewDiagnostic(missingSemicolon(), dir.string(), 2);
    ASSERT_EQ(v.context.size(), 5u);
    EXPECT_EQ(v.context.front().number, 3);
    EXPECT_EQ(v.context.back().number, 7);
    EXPECT_EQ(v.context[2].text, "    vec3 n = normalize(v_world_normal)");
    EXPECT_EQ(v.path, fs::canonical(dir / "phong.frag").string());
    EXPECT_EQ(shaderlab::viewer::formatWithContext(v),
              "phong.frag:5: error: a `;` is missing at the end of this line\n"
              " 3 | out vec4 o_color;\n"
              " 4 | void main() {\n"
              " 5 |     vec3 n = normalize(v_world_normal)\n"
              "   |                                       ^\n"
              " 6 |     o_color = vec4(n, 1.0);\n"
              " 7 | }\n"
              "   = Every statement ends with `;`.");
}

TEST(DiagnosticView, AFileSavedAgainSinceTheRenderGivesNoLinesButTheQuotedOne) {
    const fs::path dir = scratch("moved");
    write(dir / "phong.frag", std::string("// a new first line\n") + kFrag);
    const DiagnosticView v = shaderlab::viewer::viewDiagnostic(missingSemicolon(), dir.string());
    EXPECT_TRUE(v.context.empty());
    const std::string text = shaderlab::viewer::formatWithContext(v);
    EXPECT_NE(text.find(" 5 |     vec3 n = normalize(v_world_normal)\n"), std::string::npos) << text;
    EXPECT_EQ(text.find(" 4 |"), std::string::npos) << text;
}

TEST(DiagnosticView, NothingIsReadFromOutsideTheLabFolder) {
    const fs::path dir = scratch("outside");
    const fs::path lab = dir / "lab";
    fs::create_directories(lab);
    write(dir / "secret.frag", kFrag);
    fs::create_symlink(dir / "secret.frag", lab / "phong.frag");
    Diagnostic d = missingSemicolon();
    EXPECT_TRUE(shaderlab::viewer::viewDiagnostic(d, lab.string()).path.empty())
        << "a symlink out of the folder";
    d.file = "../secret.frag";
    EXPECT_TRUE(shaderlab::viewer::viewDiagnostic(d, lab.string()).context.empty());
    d.file = (dir / "secret.frag").string();
    EXPECT_TRUE(shaderlab::viewer::viewDiagnostic(d, lab.string()).path.empty()) << "an absolute path";
}

TEST(DiagnosticView, EditorCommandAndLinkNameTheFileAndLine) {
    const fs::path dir = scratch("editor dir");
    write(dir / "phong.frag", kFrag);
    const DiagnosticView v = shaderlab::viewer::viewDiagnostic(missingSemicolon(), dir.string());
    setenv("EDITOR", "code -g", 1);
    EXPECT_EQ(shaderlab::viewer::editorCommand(v), "code -g +5 '" + v.path + "'");
    unsetenv("EDITOR");
    EXPECT_EQ(shaderlab::viewer::editorCommand(v), "vi +5 '" + v.path + "'");
    const std::string link = shaderlab::viewer::editorLink(v);
    EXPECT_EQ(link.rfind("vscode://file/", 0), 0u) << link;
    EXPECT_NE(link.find("editor%20dir"), std::string::npos) << link;
    EXPECT_EQ(link.substr(link.size() - 5), ":5:39") << link;
    EXPECT_TRUE(shaderlab::viewer::editorLink(DiagnosticView{}).empty());
}

}  // namespace
