#version 330 core
// 02-toon, task 1 (pass "steps"): cel shading by quantising the Lambert term.
// Instead of the smooth max(n.l, 0), every light contributes one of u_levels flat tones:
//   d    = max(n.l, 0)                      the Lambert term, in [0, 1]
//   k    = min(floor(d * L), L - 1)         which of the L equal bands d falls in: 0 .. L-1
//   tone = k / (L - 1)                      0 (shadow) .. 1 (full light), evenly spaced
//   colour = base colour * (u_ambient + sum over lights of light colour * tone)
// Read labs/02-toon/README.md first: it explains why, and what goes wrong. The function and main
// are graded each on its own: keep bandTone's name and parameters (README, "How it is graded").

in vec3 v_world_position;
in vec3 v_world_normal;

uniform int u_light_count;                     // how many entries below are in use
uniform vec4 u_light_position[SL_MAX_LIGHTS];  // w = 1: point light at xyz; w = 0: xyz points toward the light
uniform vec3 u_light_color[SL_MAX_LIGHTS];     // colour times intensity
uniform vec4 u_base_color;                     // the material's colour

uniform int u_levels;     // L: the number of tones, shadow tone included (2 or more; lab.json sets it per scene)
uniform float u_ambient;  // light every point gets, lit or not

out vec4 o_color;

// The tone of one light: its Lambert term d = max(n.l, 0) quantised into `levels` equal bands,
// 0 for the lowest band and 1 for the highest.
float bandTone(float n_dot_l, int levels) {
    float d = max(n_dot_l, 0.0);
    float steps = float(levels - 1);
    // Snap d to the nearest of the L tones 0, 1/(L-1), ..., 1.
    return round(d * steps) / steps;
}

void main() {
    vec3 n = normalize(v_world_normal);

    vec3 light = vec3(u_ambient);
    for (int i = 0; i < u_light_count; ++i) {
        vec4 lp = u_light_position[i];
        vec3 l = normalize(lp.xyz - v_world_position * lp.w);
        light += u_light_color[i] * bandTone(dot(n, l), u_levels);
    }

    o_color = vec4(u_base_color.rgb * light, 1.0);
}
