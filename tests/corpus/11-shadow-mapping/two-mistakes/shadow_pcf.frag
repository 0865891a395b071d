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
    float z = coord.z - shadow_bias(n, l);
    vec2 texel = 1.0 / vec2(textureSize(u_shadow_map, 0));
    float lit = 0.0;
    for (int y = -1; y <= 1; ++y) {
        for (int x = -1; x <= 1; ++x) {
            lit += texture(u_shadow_map, vec3(coord.xy + vec2(x, y) * texel, z));
        }
    }
    return lit / 8.0;  // the centre and its eight neighbours
}

void main() {
    vec3 n = normalize(v_world_normal);
    vec3 l = to_light(0, v_world_position);
    o_color = vec4(shade(v_world_position, n, visibility(v_world_position, n, l)), 1.0);
}
