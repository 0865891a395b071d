#version 330 core
// Outline colour: pure black looks flat, so use a dark version of the object's own colour,
// shaded a little by the light so the outline follows the form.

uniform int u_light_count;
uniform vec4 u_light_position[SL_MAX_LIGHTS];
uniform vec4 u_base_color;

out vec4 o_color;

void main() {
    // No normal here, so just take how much light there is overall.
    float light = 0.0;
    for (int i = 0; i < u_light_count; ++i) light += 0.5;
    o_color = vec4(u_base_color.rgb * 0.35 * light, 1.0);
}
