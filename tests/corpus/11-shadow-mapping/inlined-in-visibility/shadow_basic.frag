#version 330 core
// Lab 11 (shadow mapping), pass "basic": the shadow test with a sampler2D. Task 1.
// Everything here, in one place: the projection into the light's view, the outside test, the bias
// and the comparison (shadow_common.glsl is left as it came).

#include "lighting.glsl"
#include "shadow_common.glsl"

in vec3 v_world_position;
in vec3 v_world_normal;

uniform sampler2D u_shadow_map;  // the light's depth buffer: .r is the depth the light saw (0..1)

out vec4 o_color;

float visibility(vec3 p, vec3 n, vec3 l) {
    vec4 clip = u_light_matrix * vec4(p, 1.0);
    vec3 s = clip.xyz / clip.w * 0.5 + 0.5;  // texture coordinates and depth, 0..1 in the view
    if (s.x < 0.0 || s.x > 1.0 || s.y < 0.0 || s.y > 1.0 || s.z < 0.0 || s.z > 1.0) {
        return 1.0;  // the map knows nothing here
    }
    // slope-scaled: about three texels' worth of depth change at the surface's slant
    float c = clamp(dot(n, l), 0.05, 1.0);
    float bias = clamp(0.002 * sqrt(1.0 - c * c) / c, 0.0002, 0.01);
    return s.z - bias > texture(u_shadow_map, s.xy).r ? 0.0 : 1.0;
}

void main() {
    vec3 n = normalize(v_world_normal);
    vec3 l = to_light(0, v_world_position);
    o_color = vec4(shade(v_world_position, n, visibility(v_world_position, n, l)), 1.0);
}
