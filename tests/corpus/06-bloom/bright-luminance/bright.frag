#version 330 core
// Bright pass: how bright a pixel is, is its luminance (Rec. 709 weights), so threshold that and
// keep the pixel's colour where it is bright.

in vec2 v_uv;

uniform sampler2D u_scene;
uniform float u_threshold_low;
uniform float u_threshold_high;

out vec4 o_color;

void main() {
    vec3 c = texture(u_scene, v_uv).rgb;
    float luminance = dot(c, vec3(0.2126, 0.7152, 0.0722));
    float keep = smoothstep(u_threshold_low, u_threshold_high, luminance);
    o_color = vec4(c * keep, 1.0);
}
