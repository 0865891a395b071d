// A reference file with a student's functions swapped in.
#include "shaderlab/glsl/glsl_compose.h"

#include <gtest/gtest.h>

#include "shaderlab/glsl/glsl_outline.h"

namespace shaderlab::glsl {
namespace {

const char* const kReference = R"(#version 330 core
in vec3 v_normal;
uniform float u_gain;
out vec4 o_color;
const float kScale = 1.0;

float clamp01(float x) { return clamp(x, 0.0, 1.0); }

float diffuse(vec3 n, vec3 l) {
    return clamp01(dot(n, l)) * kScale;
}

float highlight(vec3 n, vec3 l) {
    return pow(clamp01(dot(reflect(-l, n), vec3(0.0, 0.0, 1.0))), 8.0);
}

void main() {
    vec3 n = normalize(v_normal);
    vec3 l = normalize(vec3(1.0));
    o_color = vec4(vec3(diffuse(n, l) + highlight(n, l)) * u_gain, 1.0);
}
)";

const char* const kStarter = R"(#version 330 core
in vec3 v_normal;
uniform float u_gain;
out vec4 o_color;

float diffuse(vec3 n, vec3 l) {
    return 0.0;  // TODO(student)
}

float highlight(vec3 n, vec3 l) {
    return 0.0;  // TODO(student)
}

void main() {
    vec3 n = normalize(v_normal);
    vec3 l = normalize(vec3(1.0));
    o_color = vec4(vec3(diffuse(n, l) + highlight(n, l)) * u_gain, 1.0);
}
)";

Composed compose(const std::string& student, std::vector<std::string> take,
                 std::vector<std::string> keep = {}) {
    ComposeInput in;
    in.file = "lit.frag";
    in.reference = kReference;
    in.student = student;
    in.starter = kStarter;
    in.take = std::move(take);
    in.keep = std::move(keep);
    return composeFunctions(in);
}

// The body of function `name` in `text`, canonical.
std::string function(const std::string& text, const std::string& name) {
    const Outline o = outlineGlsl(text);
    for (const Declaration* d : declarationsNamed(o, name))
        if (d->kind == DeclKind::Function) return canonicalText(text, o, *d);
    return "(none)";
}

TEST(GlslCompose, TakesOnlyTheNamedFunction) {
    // The student's diffuse is wrong (no clamp) and so is their highlight; only diffuse is taken.
    const std::string student = R"(#version 330 core
in vec3 v_normal;
uniform float u_gain;
out vec4 o_color;
float diffuse(vec3 n, vec3 l) { return dot(n, l); }
float highlight(vec3 n, vec3 l) { return 1.0; }
void main() { o_color = vec4(diffuse(normalize(v_normal), vec3(1.0)) + highlight(v_normal, v_normal)); }
)";
    // (highlight and main are other goals' work: kept.)
    const Composed c = compose(student, {"diffuse"}, {"highlight", "main"});
    ASSERT_TRUE(c.ok) << c.note;
    EXPECT_EQ(function(c.text, "diffuse"), "float diffuse ( vec3 n , vec3 l ) { return dot ( n , l ) ; }");
    EXPECT_EQ(function(c.text, "highlight"), function(kReference, "highlight"));
    EXPECT_EQ(function(c.text, "main"), function(kReference, "main"));
    EXPECT_TRUE(c.imported.empty());
    EXPECT_TRUE(c.callers.empty());
}

TEST(GlslCompose, ChangedCodeNoGoalAsksForGoesWithTheWorkItCalls) {
    // main is given by the starter and no goal's work; this student broke it (the gain squared).
    const std::string student = R"(#version 330 core
in vec3 v_normal;
uniform float u_gain;
out vec4 o_color;
float diffuse(vec3 n, vec3 l) { return max(dot(n, l), 0.0); }
float highlight(vec3 n, vec3 l) { return 0.0; }
void main() {
    vec3 n = normalize(v_normal);
    vec3 l = normalize(vec3(1.0));
    o_color = vec4(vec3(diffuse(n, l) + highlight(n, l)) * u_gain * u_gain, 1.0);
}
)";
    // main calls diffuse, which is taken: it comes with it, and highlight stays the reference's.
    const Composed with_diffuse = compose(student, {"diffuse"}, {"highlight"});
    ASSERT_TRUE(with_diffuse.ok) << with_diffuse.note;
    EXPECT_EQ(with_diffuse.callers, (std::vector<std::string>{"main"}));
    EXPECT_EQ(function(with_diffuse.text, "main"), function(student, "main"));
    EXPECT_EQ(function(with_diffuse.text, "highlight"), function(kReference, "highlight"));
    // main as the starter gave it: nothing comes along.
    std::string given = student;
    given.replace(given.find(" * u_gain * u_gain"), 18, " * u_gain");
    const Composed untouched = compose(given, {"diffuse"}, {"highlight"});
    ASSERT_TRUE(untouched.ok) << untouched.note;
    EXPECT_TRUE(untouched.callers.empty());
    EXPECT_EQ(function(untouched.text, "main"), function(kReference, "main"));
    // A changed helper that a taken function calls comes along as an import, not as a caller.
    const std::string helper = R"(#version 330 core
in vec3 v_normal;
uniform float u_gain;
out vec4 o_color;
const float kScale = 1.0;
float clamp01(float x) { return max(x, 0.0); }
float diffuse(vec3 n, vec3 l) { return clamp01(dot(n, l)) * kScale; }
float highlight(vec3 n, vec3 l) { return pow(clamp01(dot(reflect(-l, n), vec3(0.0, 0.0, 1.0))), 8.0); }
void main() {
    vec3 n = normalize(v_normal);
    vec3 l = normalize(vec3(1.0));
    o_color = vec4(vec3(diffuse(n, l) + highlight(n, l)) * u_gain, 1.0);
}
)";
    const Composed h = compose(helper, {"highlight"}, {"diffuse", "main"});
    ASSERT_TRUE(h.ok) << h.note;
    EXPECT_TRUE(h.callers.empty());
    EXPECT_EQ(h.imported, (std::vector<std::string>{"clamp01_student"}));
}

TEST(GlslCompose, AMainWithTheWorkWrittenIntoItGoesWithWhatIsTaken) {
    // main computes the diffuse term itself and calls no function of the lab; the student's
    // diffuse is done too, so the work is not the starter's.
    const std::string student = R"(#version 330 core
in vec3 v_normal;
uniform float u_gain;
out vec4 o_color;
float diffuse(vec3 n, vec3 l) { return max(dot(n, l), 0.0); }
float highlight(vec3 n, vec3 l) { return 0.0; }
void main() {
    vec3 n = normalize(v_normal);
    o_color = vec4(vec3(dot(n, vec3(0.577))) * u_gain, 1.0);
}
)";
    const Composed c = compose(student, {"diffuse"}, {"highlight"});
    ASSERT_TRUE(c.ok) << c.note;
    EXPECT_EQ(c.callers, (std::vector<std::string>{"main"}));
    // With diffuse still the starter's, it is the case the composer refuses: the work is elsewhere.
    std::string stub = student;
    const std::string done = "return max(dot(n, l), 0.0);";
    stub.replace(stub.find(done), done.size(), "return 0.0;");
    const Composed refused = compose(stub, {"diffuse"}, {"highlight"});
    EXPECT_FALSE(refused.ok);
    EXPECT_TRUE(refused.starter_untouched) << refused.note;
}

TEST(GlslCompose, HelpersComeAlongRenamedWhereTheyClash) {
    // The student's own clamp01 differs from the reference's (it does not clamp at 1), and a
    // helper the reference does not have comes along under its own name.
    const std::string student = R"(#version 330 core
in vec3 v_normal;
uniform float u_gain;
out vec4 o_color;
const float kScale = 0.5;
float clamp01(float x) { return max(x, 0.0); }
float twice(float x) { return 2.0 * x; }
float diffuse(vec3 n, vec3 l) { return twice(clamp01(dot(n, l))) * kScale; }
float highlight(vec3 n, vec3 l) { return clamp01(1.0); }
void main() { o_color = vec4(diffuse(v_normal, v_normal) * u_gain); }
)";
    const Composed c = compose(student, {"diffuse"});
    ASSERT_TRUE(c.ok) << c.note;
    EXPECT_EQ(c.imported, (std::vector<std::string>{"kScale_student", "clamp01_student", "twice"}));
    EXPECT_EQ(function(c.text, "diffuse"),
              "float diffuse ( vec3 n , vec3 l ) { return twice ( clamp01_student ( dot ( n , l ) ) ) * "
              "kScale_student ; }");
    // The reference's own helper is untouched, and its highlight still calls it.
    EXPECT_EQ(function(c.text, "clamp01"), function(kReference, "clamp01"));
    EXPECT_EQ(function(c.text, "highlight"), function(kReference, "highlight"));
    EXPECT_NE(c.text.find("const float kScale_student = 0.5;"), std::string::npos) << c.text;
    // Imports stand before the first function taken, after the reference's globals.
    EXPECT_LT(c.text.find("kScale_student = 0.5"), c.text.find("float diffuse"));
}

TEST(GlslCompose, KeptFunctionsStayTheReferences) {
    // main is the work (the glue); the student's diffuse is wrong but is another goal's work.
    const std::string student = R"(#version 330 core
in vec3 v_normal;
uniform float u_gain;
out vec4 o_color;
float diffuse(vec3 n, vec3 l) { return 0.25; }
float highlight(vec3 n, vec3 l) { return 0.0; }
void main() {
    vec3 n = normalize(v_normal);
    o_color = vec4(vec3(diffuse(n, n) + highlight(n, n)), 1.0);  // forgot u_gain
}
)";
    const Composed c = compose(student, {"main"}, {"diffuse", "highlight"});
    ASSERT_TRUE(c.ok) << c.note;
    EXPECT_EQ(function(c.text, "diffuse"), function(kReference, "diffuse"));
    EXPECT_EQ(function(c.text, "main"), function(student, "main"));
}

TEST(GlslCompose, PrototypesForFunctionsDefinedLater) {
    // The student's diffuse calls highlight, which the reference defines after diffuse.
    const std::string student = std::string(kStarter).replace(
        std::string(kStarter).find("return 0.0;  // TODO(student)"), 29, "return highlight(n, l);");
    const Composed c = compose(student, {"diffuse"}, {"highlight"});
    ASSERT_TRUE(c.ok) << c.note;
    EXPECT_LT(c.text.find("float highlight(vec3 n, vec3 l);"), c.text.find("float diffuse("));
}

TEST(GlslCompose, RefusesWithAReason) {
    // Missing, another signature, still the starter's, a global main sets, #if blocks.
    const std::string missing = "void main() {}";
    Composed c = compose(missing, {"diffuse"});
    EXPECT_FALSE(c.ok);
    EXPECT_EQ(c.note, "lit.frag has no function `float diffuse(vec3 n, vec3 l)`");

    c = compose("float diffuse(vec3 n) { return 1.0; } void main() {}", {"diffuse"});
    EXPECT_FALSE(c.ok);
    EXPECT_EQ(c.note,
              "`diffuse` in lit.frag takes (vec3) and returns float, but the lab asks for "
              "`float diffuse(vec3 n, vec3 l)`");

    c = compose(kStarter, {"diffuse"});
    EXPECT_FALSE(c.ok);
    EXPECT_TRUE(c.starter_untouched);
    EXPECT_EQ(c.note, "`diffuse` in lit.frag is still as the starter had it");
    // main, which the starter gives whole, is no work left undone: the note does not name it.
    c = compose(kStarter, {"diffuse", "main"});
    EXPECT_TRUE(c.starter_untouched);
    EXPECT_EQ(c.note, "`diffuse` in lit.frag is still as the starter had it");

    const std::string global = R"(vec3 g_n;
float diffuse(vec3 n, vec3 l) { return dot(g_n, l); }
void main() { g_n = normalize(vec3(1.0)); }
)";
    c = compose(global, {"diffuse"}, {"main"});
    EXPECT_FALSE(c.ok);
    EXPECT_EQ(c.note, "`diffuse` in lit.frag reads the global variable `g_n`, which `main` sets");
    // Where no goal asks for main, the student's main comes along, and with it the value.
    c = compose(global, {"diffuse"});
    EXPECT_TRUE(c.ok) << c.note;
    EXPECT_EQ(c.callers, (std::vector<std::string>{"main"}));

    c = compose("#ifdef X\nfloat diffuse(vec3 n, vec3 l) { return 1.0; }\n#endif\n", {"diffuse"});
    EXPECT_FALSE(c.ok);
    EXPECT_EQ(c.note, "lit.frag has #ifdef blocks, so its functions cannot be taken alone");
}

TEST(GlslCompose, AGlobalOnlyTheTakenCodeWritesComesAlong) {
    const std::string student = R"(float g_calls;
float diffuse(vec3 n, vec3 l) { g_calls += 1.0; return max(dot(n, l), 0.0); }
void main() {}
)";
    const Composed c = compose(student, {"diffuse"});
    ASSERT_TRUE(c.ok) << c.note;
    EXPECT_EQ(c.imported, (std::vector<std::string>{"g_calls"}));
}

TEST(GlslCompose, TheReferenceItselfComposesToItself) {
    const Composed c = compose(kReference, {"diffuse", "highlight"});
    ASSERT_TRUE(c.ok) << c.note;
    EXPECT_EQ(c.text, kReference);
}

// main with the functions it calls, all taken: they are defined before main, so no prototype is
// needed (12-normal-mapping's world_space goal takes world_normal, world_tangent and main).
TEST(GlslCompose, NoPrototypeForATakenFunctionDefinedBeforeItsCaller) {
    const Composed c = compose(kReference, {"diffuse", "highlight", "main"});
    ASSERT_TRUE(c.ok) << c.note;
    EXPECT_EQ(c.text, kReference);
}

TEST(GlslCompose, AUniformOfAnotherTypeIsTheStudents) {
    // The lab feeds a shadow map to a sampler2D or a sampler2DShadow, whichever is declared.
    const std::string reference = R"(uniform sampler2DShadow u_map;
uniform float u_bias;
float visibility(vec3 p) { return texture(u_map, p); }
void main() {}
)";
    const std::string student = R"(uniform sampler2D u_map;
uniform float u_bias;
float visibility(vec3 p) { return step(p.z - u_bias, texture(u_map, p.xy).r); }
void main() {}
)";
    ComposeInput in;
    in.file = "shadow.frag";
    in.reference = reference;
    in.student = student;
    in.take = {"visibility"};
    const Composed c = composeFunctions(in);
    ASSERT_TRUE(c.ok) << c.note;
    EXPECT_EQ(c.text.substr(0, 26), "uniform sampler2D u_map;\nu");
    EXPECT_NE(c.text.find("uniform float u_bias;"), std::string::npos);
}

}  // namespace
}  // namespace shaderlab::glsl
