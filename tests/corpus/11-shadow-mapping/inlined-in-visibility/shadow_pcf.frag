#version 330 core
// Lab 11 (shadow mapping), pass "pcf": percentage-closer filtering with a sampler2DShadow.
// Task 2, written out here like task 1: projection, outside test, bias, then the 3x3 kernel.

#include "lighting.glsl"
#include "shadow_common.glsl"

in vec3 v_world_position;
in vec3 v_world_normal;

uniform sampler2DShadow u_shadow_map;

out vec4 o_color;

float visibility(vec3 p, vec3 n, vec3 l) {
    vec4 clip = u_light_matrix * vec4(p, 1.0);
    vec3 s = clip.xyz / clip.w * 0.5 + 0.5;
    if (s.x < 0.0 || s.x > 1.0 || s.y < 0.0 || s.y > 1.0 || s.z < 0.0 || s.z > 1.0) {
        return 1.0;
    }
    float c = clamp(dot(n, l), 0.05, 1.0);
    float z = s.z - clamp(0.002 * sqrt(1.0 - c * c) / c, 0.0002, 0.01);
    vec2 texel = 1.0 / vec2(textureSize(u_shadow_map, 0));
    float lit = 0.0;
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            lit += texture(u_shadow_map, vec3(s.xy + vec2(dx, dy) * texel, z));
        }
    }
    return lit / 9.0;
}

void main() {
    vec3 n = normalize(v_world_normal);
    vec3 l = to_light(0, v_world_position);
    o_color = vec4(shade(v_world_position, n, visibility(v_world_position, n, l)), 1.0);
}
