#version 330 core
// Reference solution, 02-toon, task 1: the Lambert term quantised into u_levels flat tones.
//   d = max(n.l, 0),  k = min(floor(d * L), L - 1),  tone = k / (L - 1)
//   colour = C * (ambient + sum_i L_i * tone_i)
// Hard-edged bands of flat colour are the cel animator's "shadow" and "light" paint
// (Decaudin, "Cartoon-Looking Rendering of 3D-Scenes", INRIA research report 2919, 1996).

in vec3 v_world_position;
in vec3 v_world_normal;

uniform int u_light_count;
uniform vec4 u_light_position[SL_MAX_LIGHTS];  // w = 1: point light; w = 0: direction toward the light
uniform vec3 u_light_color[SL_MAX_LIGHTS];
uniform vec4 u_base_color;

uniform int u_levels;      // number of tones, shadow tone included (at least 2)
uniform float u_ambient;   // light every point gets, lit or not

out vec4 o_color;

float bandTone(float n_dot_l, int levels) {
    float d = max(n_dot_l, 0.0);
    float count = float(levels);
    // floor picks the band d falls in
    float k = floor(d * count);
    return k / (count - 1.0);
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
