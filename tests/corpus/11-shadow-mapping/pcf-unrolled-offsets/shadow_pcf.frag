#version 330 core
// Reference solution, lab 11 (shadow mapping), pass "pcf": percentage-closer filtering (Reeves,
// Salesin, Cook, "Rendering Antialiased Shadows with Depth Maps", SIGGRAPH 1987). Filtering the
// stored depths would average depths of different surfaces and still give a yes-or-no answer;
// PCF filters the ANSWERS instead: the fraction of nearby texels whose depth test the point
// passes. A sampler2DShadow does one test per texture() call: it returns 1 where
// coord.z <= stored depth (GL_LEQUAL), else 0.

#include "lighting.glsl"
#include "shadow_common.glsl"

in vec3 v_world_position;
in vec3 v_world_normal;

uniform sampler2DShadow u_shadow_map;  // the light's depth buffer, compared by the hardware

out vec4 o_color;

float visibility(vec3 p, vec3 n, vec3 l) {
    vec3 coord = shadow_coord(p);
    if (outside_shadow_map(coord)) {
        return 1.0;
    }
    vec3 c = vec3(coord.xy, coord.z - shadow_bias(n, l));
    // textureOffset takes constant texel offsets: the 3x3 kernel written out
    float lit = textureOffset(u_shadow_map, c, ivec2(-1, -1)) + textureOffset(u_shadow_map, c, ivec2(0, -1)) +
                textureOffset(u_shadow_map, c, ivec2(1, -1)) + textureOffset(u_shadow_map, c, ivec2(-1, 0)) +
                texture(u_shadow_map, c) + textureOffset(u_shadow_map, c, ivec2(1, 0)) +
                textureOffset(u_shadow_map, c, ivec2(-1, 1)) + textureOffset(u_shadow_map, c, ivec2(0, 1)) +
                textureOffset(u_shadow_map, c, ivec2(1, 1));
    return lit / 9.0;
}

void main() {
    vec3 n = normalize(v_world_normal);
    vec3 l = to_light(0, v_world_position);
    o_color = vec4(shade(v_world_position, n, visibility(v_world_position, n, l)), 1.0);
}
