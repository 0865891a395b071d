// Mutants of a reference file: each operator's change, stable ids, repeats made once.
#include "shaderlab/authoring/mutants.h"

#include <gtest/gtest.h>

#include <map>
#include <set>

namespace shaderlab::authoring {
namespace {

const char* const kShader = R"(uniform float u_k;
vec3 shade(vec3 n, vec3 l) {
    float d = max(dot(n, l), 0.0);
    vec3 c = u_k * (d + 0.5) - n.xyz;
    return normalize(c) * -d;
}
void main() {
    vec3 sum = vec3(0.0);
    float w = 2.0;
    for (int i = 0; i < 4; ++i) {
        sum += shade(vec3(0.0), vec3(1.0)) * w;
        w = w * 0.5;
    }
}
)";

std::map<std::string, std::string> changes(const std::vector<Mutant>& all) {
    std::map<std::string, std::string> out;
    for (const Mutant& m : all) out[m.id] = m.change;
    return out;
}

TEST(Mutants, EachOperatorChangesOnePlace) {
    const std::vector<Mutant> all = mutateFile("lit.frag", kShader);
    const std::map<std::string, std::string> c = changes(all);
    EXPECT_EQ(c.at("lit.frag:shade:constant#1"), "`0.0` -> `1.0`");
    EXPECT_EQ(c.at("lit.frag:shade:constant#2"), "`0.5` -> `1.0`");
    EXPECT_EQ(c.at("lit.frag:shade:call#1"), "`max(dot(n, l), 0.0)` -> `(dot(n, l))`");
    EXPECT_EQ(c.at("lit.frag:shade:call#2"), "`normalize(c)` -> `(c)`");
    EXPECT_EQ(c.at("lit.frag:shade:swizzle#1"), "`xyz` -> `zyx`");
    EXPECT_EQ(c.at("lit.frag:shade:distribute#1"), "`* (d + 0.5)` without its brackets");
    EXPECT_EQ(c.at("lit.frag:shade:sign#1"), "`-` -> ``");
    EXPECT_EQ(c.at("lit.frag:shade:term-dropped#1"), "`+ 0.5` -> ``");
    EXPECT_EQ(c.at("lit.frag:shade:term-dropped#2"), "`- n.xyz` -> ``");
    EXPECT_EQ(c.at("lit.frag:shade:term-doubled#2"), "`- n.xyz` twice");
    EXPECT_EQ(c.at("lit.frag:main:operator#1"), "`<` -> `<=`");
    EXPECT_EQ(c.at("lit.frag:main:out-of-loop#1"), "`w = w * 0.5;` moved after the loop");
    EXPECT_EQ(c.at("lit.frag:main:into-loop#1"), "`float w = 2.0;` moved into the loop");
    // Nothing outside a function body is touched.
    for (const Mutant& m : all) EXPECT_EQ(m.text.substr(0, 19), "uniform float u_k;\n") << m.id;
}

// A minus after a gl_ variable is binary: swapped as an operator, never dropped as a sign (which
// would not compile).
TEST(Mutants, AMinusAfterAGlVariableIsBinary) {
    const std::map<std::string, std::string> c = changes(mutateFile(
        "p.frag",
        "out vec4 o;\nvoid main() {\n    vec2 d = gl_PointCoord - 1.0;\n    o = vec4(d, 0.0, 1.0);\n}\n"));
    EXPECT_EQ(c.at("p.frag:main:operator#1"), "`-` -> `+`");
    for (const auto& [id, change] : c) EXPECT_EQ(id.find(":sign#"), std::string::npos) << id << " " << change;
}

TEST(Mutants, TheTextIsTheFileWithOneChange) {
    for (const Mutant& m : mutateFile("lit.frag", kShader)) {
        if (m.id != "lit.frag:shade:distribute#1") continue;
        EXPECT_NE(m.text.find("vec3 c = u_k * d + 0.5 - n.xyz;"), std::string::npos) << m.text;
        EXPECT_EQ(m.line, 4);
    }
    for (const Mutant& m : mutateFile("lit.frag", kShader)) {
        if (m.id != "lit.frag:main:out-of-loop#1") continue;
        EXPECT_NE(m.text.find("* w;\n        \n    }\n    w = w * 0.5;\n}"), std::string::npos) << m.text;
    }
}

TEST(Mutants, IdsStayWithTheirPlaceAndRepeatsAreMadeOnce) {
    // Two identical statements: dropping either term gives different files; both stay.
    const std::string text = "void f() { float a = 1.0 + 2.0; float b = 1.0 + 2.0; }\n";
    const std::vector<Mutant> all = mutateFile("x.frag", text);
    std::set<std::string> texts;
    for (const Mutant& m : all) EXPECT_TRUE(texts.insert(m.text).second) << m.id << " repeats another";
    const std::map<std::string, std::string> c = changes(all);
    EXPECT_EQ(c.count("x.frag:f:term-dropped#1"), 1u);
    EXPECT_EQ(c.count("x.frag:f:term-dropped#2"), 1u);
    // Garbage in: no mutant, no crash.
    for (const char* junk : {"", "void f() {", "}}}", "void f() { for ( }", "void f() { x * ( }"})
        for (const Mutant& m : mutateFile("j.frag", junk)) EXPECT_FALSE(m.text.empty());
}

}  // namespace
}  // namespace shaderlab::authoring
