#version 330 core
// Lab 11 (shadow mapping), pass "basic": the shadow test with a sampler2D. Task 1.
// The lighting is done for you (lighting.glsl): your part is visibility(), 1 where the first
// light reaches the point and 0 where something nearer to the light hides it. It is graded on its
// own (README, "How it is graded"): keep its name and parameters.

#include "lighting.glsl"
#include "shadow_common.glsl"

in vec3 v_world_position;
in vec3 v_world_normal;

uniform sampler2D u_shadow_map;  // the light's depth buffer: .r is the depth the light saw (0..1)

out vec4 o_color;

float visibility(vec3 p, vec3 n, vec3 l) {
    // TODO(student): find p in the shadow map (shadow_coord); a point outside the light's view
    // is lit.
    // TODO(student): read the depth the light saw there, and compare it with the point's own
    // depth less the bias (shadow_bias): the point is in shadow when it is farther from the light
    // than what the light saw.
    return 1.0;
}

void main() {
    vec3 n = normalize(v_world_normal);
    vec3 l = to_light(0, v_world_position);
    o_color = vec4(shade(v_world_position, n, visibility(v_world_position, n, l)), 1.0);
}
