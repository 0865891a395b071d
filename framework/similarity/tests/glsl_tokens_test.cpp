// The lexer: comments and whitespace dropped, directives, numbers, operators, names normalised.
#include "shaderlab/similarity/glsl_tokens.h"

#include <gtest/gtest.h>

#include <random>

namespace shaderlab::similarity {
namespace {

std::vector<std::string> normalised(const std::string& text) {
    std::vector<std::string> out;
    for (const Token& t : lexGlsl(text)) out.push_back(normalisedToken(text, t));
    return out;
}

std::vector<std::string> spelled(const std::string& text) {
    std::vector<std::string> out;
    for (const Token& t : lexGlsl(text)) out.push_back(text.substr(t.begin, t.end - t.begin));
    return out;
}

TEST(GlslTokens, CommentsAndWhitespaceAreDropped) {
    const std::string text =
        "float a; // a comment with float b;\n"
        "/* a block\n   over lines, float c; */ float d;\n"
        "// a comment continued \\\n still the comment\n"
        "float e; /* left open";
    EXPECT_EQ(spelled(text),
              (std::vector<std::string>{"float", "a", ";", "float", "d", ";", "float", "e", ";"}));
    const std::vector<Token> tokens = lexGlsl(text);
    EXPECT_EQ(tokens[3].line, 3u);  // float d: after a block comment of two lines
    EXPECT_EQ(tokens[6].line, 6u);  // float e: after the continued line comment
}

TEST(GlslTokens, PreprocessorLines) {
    const std::string text =
        "#version 330 core\n  #  define  SCALE 2.0\nfloat x = a # b;\n#include \"common.glsl\"\n";
    EXPECT_EQ(normalised(text),
              (std::vector<std::string>{"#version", "#n:330", "$id", "#define", "$id", "#n:2", "float", "$id",
                                        "=", "$id", "$other", "$id", ";", "#include", "\"common.glsl\""}));
    const std::vector<Token> tokens = lexGlsl(text);
    EXPECT_EQ(tokens[0].kind, TokenKind::Preprocessor);
    EXPECT_EQ(tokens[3].kind, TokenKind::Preprocessor);
    EXPECT_EQ(tokens[3].line, 2u);
    EXPECT_EQ(tokens[10].kind, TokenKind::Other);  // '#' in the middle of a line is no directive
    EXPECT_EQ(tokens[14].kind, TokenKind::String);
}

TEST(GlslTokens, NumbersAreTheirValue) {
    EXPECT_EQ(spelled("1.0 1. .5 1e3 1.5e-3f 0x1F 017 3u 2.0lf 2.0LF 1e"),
              (std::vector<std::string>{"1.0", "1.", ".5", "1e3", "1.5e-3f", "0x1F", "017", "3u", "2.0lf",
                                        "2.0LF", "1", "e"}));
    EXPECT_EQ(normalised("1.0 1. 1.0f 1 0x1 1e0"), std::vector<std::string>(6, "#n:1"));
    EXPECT_EQ(normalised("017 0x1F 1.5e-3 .5"),
              (std::vector<std::string>{"#n:15", "#n:31", "#n:0.0015", "#n:0.5"}));
    EXPECT_NE(normalised("0.2126")[0], normalised("0.2127")[0]);
}

TEST(GlslTokens, OperatorsLongestFirst) {
    EXPECT_EQ(
        spelled("a<<=b>>c; i++; --j; p&&q||r^^s; x!=y; v.xy; m[0] ? 1 : 2;"),
        (std::vector<std::string>{"a",  "<<=", "b",  ">>", "c",  ";", "i", "++", ";",  "--", "j", ";", "p",
                                  "&&", "q",   "||", "r",  "^^", "s", ";", "x",  "!=", "y",  ";", "v", ".",
                                  "xy", ";",   "m",  "[",  "0",  "]", "?", "1",  ":",  "2",  ";"}));
}

TEST(GlslTokens, KeywordsAndBuiltinsStayNamesGoToOneClass) {
    EXPECT_EQ(
        normalised("void main() { vec3 n = normalize(v_normal); float d = dot(n, l); gl_FragColor = "
                   "texture(u_tex, uv); myFunction(d); }"),
        (std::vector<std::string>{"void",      "main",    "(",   ")",   "{",   "vec3",  "$id", "=",
                                  "normalize", "(",       "$id", ")",   ";",   "float", "$id", "=",
                                  "dot",       "(",       "$id", ",",   "$id", ")",     ";",   "gl_FragColor",
                                  "=",         "texture", "(",   "$id", ",",   "$id",   ")",   ";",
                                  "$id",       "(",       "$id", ")",   ";",   "}"}));
    EXPECT_TRUE(isGlslKeywordOrBuiltin("smoothstep"));
    EXPECT_TRUE(isGlslKeywordOrBuiltin("sampler2DShadow"));
    EXPECT_TRUE(isGlslKeywordOrBuiltin("gl_Position"));
    EXPECT_FALSE(isGlslKeywordOrBuiltin("u_light_position"));
    EXPECT_FALSE(isGlslKeywordOrBuiltin("normalise"));
}

TEST(GlslTokens, RenamingReformattingAndCommentsChangeNoHash) {
    const std::string a = "// Phong\nfloat lambert(vec3 n, vec3 l) {\n    return max(dot(n, l), 0.0);\n}\n";
    const std::string b =
        "float   diffuseTerm( vec3 normal,vec3 toLight ){ /* clamp */ return max(dot(normal,\n"
        "toLight), 0.);}";
    EXPECT_EQ(normalisedHashes(a, lexGlsl(a)), normalisedHashes(b, lexGlsl(b)));
    const std::string c = "float lambert(vec3 n, vec3 l) { return min(dot(n, l), 0.0); }";
    EXPECT_NE(normalisedHashes(a, lexGlsl(a)), normalisedHashes(c, lexGlsl(c)));
}

TEST(GlslTokens, AnyBytesGiveTokensInsideTheText) {
    std::mt19937 rng(7);
    for (int round = 0; round < 200; ++round) {
        std::string junk(1 + rng() % 3000, '\0');
        for (char& c : junk) c = static_cast<char>(rng() & 0xff);
        const std::vector<Token> tokens = lexGlsl(junk);
        std::uint32_t previous_end = 0;
        for (const Token& t : tokens) {
            ASSERT_LT(t.begin, t.end);
            ASSERT_LE(t.end, junk.size());
            ASSERT_GE(t.begin, previous_end);
            previous_end = t.end;
        }
        EXPECT_EQ(normalisedHashes(junk, tokens).size(), tokens.size());
    }
}

}  // namespace
}  // namespace shaderlab::similarity
