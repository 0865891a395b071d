// printableText: control characters, broken UTF-8 and bidirectional overrides written out
// visibly, long text cut with a count of what was left out.
#include "grader/base/untrusted_text.h"

#include <gtest/gtest.h>

namespace grader {
namespace {

TEST(UntrustedText, EscapesTerminalSequencesAndControlCharacters) {
    EXPECT_EQ(printableText("\x1b[2J\x1b[31mPWNED\x07"), "\\x1B[2J\\x1B[31mPWNED\\x07");
    EXPECT_EQ(printableText(std::string("a\0b", 3)), "a\\x00b");
    EXPECT_EQ(printableText("tab\tline\nnext\r"), "tab\tline\\x0Anext\\x0D");
    EXPECT_EQ(printableText("line\nnext", 100, true), "line\nnext");
    EXPECT_EQ(printableText("del\x7f"), "del\\x7F");
    EXPECT_EQ(printableText("\xc2\x9b"
                            "31m"),
              "\\u009B31m");  // C1 CSI
}

TEST(UntrustedText, KeepsValidUtf8AndEscapesBrokenBytesAndBidiOverrides) {
    EXPECT_EQ(printableText("n·l, Größe, 光"), "n·l, Größe, 光");
    EXPECT_EQ(printableText("\xff\xfe ok"), "\\xFF\\xFE ok");
    EXPECT_EQ(printableText("\xe2\x82"), "\\xE2\\x82");  // cut sequence
    EXPECT_EQ(printableText("\xc0\xaf"), "\\xC0\\xAF");  // overlong '/'
    EXPECT_EQ(printableText("a\xe2\x80\xae"
                            "b"),
              "a\\u202Eb");  // right-to-left override
}

TEST(UntrustedText, CutsLongTextAndSaysHowMuch) {
    const std::string cut = printableText(std::string(50000, 'A'), 100);
    EXPECT_EQ(cut.substr(0, 100), std::string(100, 'A'));
    EXPECT_NE(cut.find("[... 49900 more bytes left out]"), std::string::npos) << cut;
    EXPECT_LT(cut.size(), 140u);
    EXPECT_EQ(printableText("short", 100), "short");
    // Never cut inside a character.
    const std::string wide = printableText("ééééé", 3);
    EXPECT_EQ(wide.substr(0, 4), "éé");
}

}  // namespace
}  // namespace grader
