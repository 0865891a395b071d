#version 330 core
// The debug view's fragment stage (framework/render/src/debug_view.cpp): one vertex attribute
// as a colour. Directions are unit vectors shown as n * 0.5 + 0.5; handedness is green for +1,
// red for -1 and black between (where a triangle's corners disagree); texture coordinates are
// (s, t, 0) as shaders receive them in a_texcoord, or a checker of 8 cells per unit over
// (fract(s), fract(t), 0) so that wrapped and mirrored coordinates show. The renderer defines
// which view after the #version line (one program per view); view 0 draws the grey of a mesh
// that lacks the attribute. It sets no uniform a lab could mistake for its own.
#ifndef SL_DEBUG_VIEW
#define SL_DEBUG_VIEW 1
#endif
#ifndef SL_DEBUG_NEUTRAL
#define SL_DEBUG_NEUTRAL 0.35
#endif
in vec3 v_normal;
in vec3 v_tangent;
in vec3 v_bitangent;
in float v_handedness;
in vec2 v_texcoord;

// DebugView in framework/render/include/shaderlab/render/renderer.h.
const int kNormals = 1, kTangents = 2, kBitangents = 3, kHandedness = 4, kUv = 5, kUvChecker = 6;
const int kView = SL_DEBUG_VIEW;

out vec4 o_color;

vec3 encode(vec3 direction) { return normalize(direction) * 0.5 + 0.5; }

void main() {
    vec3 color = vec3(SL_DEBUG_NEUTRAL);
    if (kView == kNormals) {
        color = encode(v_normal);
    } else if (kView == kTangents) {
        color = encode(v_tangent);
    } else if (kView == kBitangents) {
        color = encode(v_bitangent);
    } else if (kView == kHandedness) {
        color = vec3(clamp(-v_handedness, 0.0, 1.0), clamp(v_handedness, 0.0, 1.0), 0.0);
    } else if (kView == kUv) {
        color = vec3(v_texcoord, 0.0);
    } else if (kView == kUvChecker) {
        vec2 cell = floor(v_texcoord * 8.0);
        float light = mod(cell.x + cell.y, 2.0);
        vec3 ramp = vec3(fract(v_texcoord), 0.0);
        color = mix(ramp * 0.5, ramp * 0.5 + 0.5, light);
    }
    o_color = vec4(color, 1.0);
}
