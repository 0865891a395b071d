#version 330 core
// Reference solution, 06-bloom, pass "composite": the scene plus its glare, then tone mapping.
//
//   hdr   = scene + w_0 L_0 + w_1 L_1 + w_2 L_2        (L_i: the blurred level i, 1/2, 1/4, 1/8 size)
//   x     = exposure * hdr
//   color = x / (1 + x)                                  (per colour component)
//
// Summing blurs of growing radius approximates the wide, slowly falling glare of a real eye or lens
// (Spencer et al., SIGGRAPH 1995) with a few cheap small blurs (Kawase, "Frame Buffer
// Postprocessing Effects in DOUBLE-S.T.E.A.L (Wreckless)", GDC 2003). The light is added in HDR,
// BEFORE tone mapping: tone mapping is the last step that brings the sum into 0..1. x / (1 + x) is
// Reinhard's global operator (Reinhard, Stark, Shirley, Ferwerda, "Photographic Tone Reproduction
// for Digital Images", SIGGRAPH 2002, equation 3), applied here to each component.

in vec2 v_uv;

uniform sampler2D u_scene;
uniform sampler2D u_bloom0;  // level 0: half size
uniform sampler2D u_bloom1;  // level 1: quarter size
uniform sampler2D u_bloom2;  // level 2: eighth size
uniform vec3 u_level_weights;
uniform float u_exposure;

out vec4 o_color;

// The glare: the three blurred levels, each weighted by its entry of u_level_weights.
vec3 glare(vec2 uv) {
    return u_level_weights.x * texture(u_bloom0, uv).rgb + u_level_weights.y * texture(u_bloom1, uv).rgb +
           u_level_weights.z * texture(u_bloom2, uv).rgb;
}

// Reinhard's operator on the exposed HDR colour, per component: 0..inf onto 0..1.
vec3 toneMap(vec3 hdr) {
    vec3 x = u_exposure * hdr;
    return x / (1.0 + x);
}

void main() {
    vec3 scene = texture(u_scene, v_uv).rgb;
    o_color = vec4(toneMap(scene + glare(v_uv)), 1.0);
}
