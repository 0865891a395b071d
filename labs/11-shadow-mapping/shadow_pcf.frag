#version 330 core
// Lab 11 (shadow mapping), pass "pcf": percentage-closer filtering with a sampler2DShadow.
// Task 2. The lighting is done for you (lighting.glsl): your part is visibility(), the fraction
// of a 3x3 neighbourhood of shadow-map texels whose depth test the point passes. It is graded on
// its own (README, "How it is graded"): keep its name and parameters.

#include "lighting.glsl"
#include "shadow_common.glsl"

in vec3 v_world_position;
in vec3 v_world_normal;

// The light's depth buffer, compared by the hardware: texture(u_shadow_map, vec3(uv, z)) returns
// 1.0 where z <= the stored depth at uv, else 0.0.
uniform sampler2DShadow u_shadow_map;

out vec4 o_color;

float visibility(vec3 p, vec3 n, vec3 l) {
    // TODO(student): find p in the shadow map; a point outside the light's view is lit.
    // TODO(student): the point's depth less the bias is the reference value z to compare.
    // TODO(student): one texel of the map in texture coordinates (textureSize), and the mean of
    // the 3x3 comparisons at offsets -1, 0, +1 texels in x and y.
    return 1.0;
}

void main() {
    vec3 n = normalize(v_world_normal);
    vec3 l = to_light(0, v_world_position);
    o_color = vec4(shade(v_world_position, n, visibility(v_world_position, n, l)), 1.0);
}
