#version 330 core
// Bright pass, per colour component: fade in between the two thresholds.

in vec2 v_uv;

uniform sampler2D u_scene;
uniform float u_threshold_low;
uniform float u_threshold_high;

out vec4 o_color;

void main() {
    vec3 c = texture(u_scene, v_uv).rgb;
    vec3 keep = smoothstep(u_threshold_high, u_threshold_low, c);
    o_color = vec4(c * keep, 1.0);
}
