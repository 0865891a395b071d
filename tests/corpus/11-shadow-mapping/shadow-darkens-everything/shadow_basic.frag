#version 330 core
// Reference solution, lab 11 (shadow mapping), pass "basic": the shadow test with a sampler2D.
// A point is in shadow when the light saw something nearer along its ray: its depth in the
// light's view, less a bias, is greater than the depth the map stores there (Williams 1978).

#include "lighting.glsl"
#include "shadow_common.glsl"

in vec3 v_world_position;
in vec3 v_world_normal;

uniform sampler2D u_shadow_map;  // the light's depth buffer (raw depth in .r)

out vec4 o_color;

float visibility(vec3 p, vec3 n, vec3 l) {
    vec3 coord = shadow_coord(p);
    if (outside_shadow_map(coord)) {
        return 1.0;
    }
    float closest = texture(u_shadow_map, coord.xy).r;
    return coord.z - shadow_bias(n, l) > closest ? 0.0 : 1.0;
}

void main() {
    vec3 n = normalize(v_world_normal);
    vec3 l = to_light(0, v_world_position);
    // In shadow means dark: the whole colour times the visibility.
    float lit = visibility(v_world_position, n, l);
    o_color = vec4(shade(v_world_position, n, 1.0) * lit, 1.0);
}
