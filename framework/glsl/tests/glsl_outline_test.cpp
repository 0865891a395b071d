// A shader's top-level declarations: kinds, names, uses, signatures.
#include "shaderlab/glsl/glsl_outline.h"

#include <gtest/gtest.h>

namespace shaderlab::glsl {
namespace {

const Declaration& only(const Outline& o, const std::string& name) {
    const std::vector<const Declaration*> d = declarationsNamed(o, name);
    EXPECT_EQ(d.size(), 1u) << name;
    static const Declaration none;
    return d.empty() ? none : *d.front();
}

const char* const kShader = R"(#version 330 core
#define TWO_PI 6.2831853
// a comment { with a brace
in vec3 v_normal;
layout(location = 0) out vec4 o_color;
uniform vec4 u_light_position[SL_MAX_LIGHTS];
uniform float u_a, u_b;
const float k = 2.0 * TWO_PI, m = 1.0;
vec3 g_scratch;
struct Light { vec3 position; float power; } g_light;
uniform Block { mat4 u_model; vec3 u_eye; };
precision highp float;

float helper(float x);

vec3 shade(in vec3 n, const vec3 l, out float d, inout vec2 arr[2]) {
    float a = max(dot(n, l), 0.0), b;
    for (int i = 0; i < 3; ++i) { b += helper(a) * k; }
    g_light.power = b;
    d = a;
    return n * u_a + u_eye.xyz;
}

float helper(float x) { return x * x; }

void main() {
    float d;
    vec2 arr[2];
    o_color = vec4(shade(normalize(v_normal), vec3(0.0), d, arr), 1.0);
}
)";

TEST(GlslOutline, KindsAndNames) {
    const Outline o = outlineGlsl(kShader);
    EXPECT_EQ(o.error, "");
    EXPECT_EQ(only(o, "TWO_PI").kind, DeclKind::Directive);
    EXPECT_EQ(only(o, "TWO_PI").directive, "define");
    EXPECT_EQ(only(o, "v_normal").storage, "in");
    EXPECT_EQ(only(o, "o_color").storage, "out");
    EXPECT_EQ(only(o, "u_light_position").storage, "uniform");
    EXPECT_EQ(only(o, "u_b").names, (std::vector<std::string>{"u_a", "u_b"}));
    // The initialiser's names are uses, not declarations.
    EXPECT_EQ(only(o, "k").names, (std::vector<std::string>{"k", "m"}));
    EXPECT_EQ(only(o, "k").storage, "const");
    EXPECT_EQ(only(o, "k").uses, (std::vector<std::string>{"TWO_PI"}));
    EXPECT_EQ(only(o, "g_scratch").storage, "");
    EXPECT_EQ(only(o, "Light").kind, DeclKind::Struct);
    EXPECT_EQ(only(o, "Light").names, (std::vector<std::string>{"Light", "g_light"}));
    // A block without an instance name declares its members globally.
    EXPECT_EQ(only(o, "u_eye").kind, DeclKind::Block);
    EXPECT_EQ(only(o, "u_eye").storage, "uniform");
    EXPECT_EQ(declarationsNamed(o, "helper").size(), 2u);
    EXPECT_EQ(declarationsNamed(o, "helper")[0]->kind, DeclKind::Prototype);
    EXPECT_EQ(declarationsNamed(o, "helper")[1]->kind, DeclKind::Function);
    EXPECT_EQ(only(o, "main").kind, DeclKind::Function);
}

TEST(GlslOutline, FunctionSignaturesAndUses) {
    const Outline o = outlineGlsl(kShader);
    const Declaration shade = only(o, "shade");  // a copy: GCC 14 takes the name's temporary for its owner
    EXPECT_EQ(shade.return_type, "vec3");
    EXPECT_EQ(shade.parameter_types,
              (std::vector<std::string>{"vec3", "vec3", "out float", "inout vec2[2]"}));
    EXPECT_EQ(shade.head, "vec3 shade(in vec3 n, const vec3 l, out float d, inout vec2 arr[2])");
    // Parameters, locals and members are not uses; globals and called functions are.
    EXPECT_EQ(shade.uses, (std::vector<std::string>{"helper", "k", "g_light", "u_a", "u_eye"}));
    EXPECT_EQ(only(o, "main").parameter_types.size(), 0u);
    EXPECT_EQ(only(o, "main").uses, (std::vector<std::string>{"o_color", "shade", "v_normal"}));
}

TEST(GlslOutline, CanonicalTextIgnoresLayout) {
    const std::string a = "float f(float x) {\n  return x*2.0; // twice\n}\n";
    const std::string b = "float f( float x ) { return x * 2.0; }";
    const Outline oa = outlineGlsl(a), ob = outlineGlsl(b);
    EXPECT_EQ(canonicalText(a, oa, only(oa, "f")), canonicalText(b, ob, only(ob, "f")));
    const std::string c = "float f(float x) { return x * 3.0; }";
    const Outline oc = outlineGlsl(c);
    EXPECT_NE(canonicalText(a, oa, only(oa, "f")), canonicalText(c, oc, only(oc, "f")));
}

TEST(GlslOutline, UnbalancedBracesAreSaidNotFatal) {
    const Outline o = outlineGlsl("void main() {\n  if (true) {\n}\n");
    EXPECT_NE(o.error, "");
    for (const std::string text : {"", "}}}", "((", "#define", "float", "void f(", "struct {", ";;;"}) {
        const Outline any = outlineGlsl(text);
        for (const Declaration& d : any.declarations) EXPECT_LE(d.begin, d.end) << text;
    }
}

}  // namespace
}  // namespace shaderlab::glsl
