#version 330 core
// Bright pass, per colour component, with a smooth threshold. The result is a colour, so keep it
// in the valid 0..1 range.

in vec2 v_uv;

uniform sampler2D u_scene;
uniform float u_threshold_low;
uniform float u_threshold_high;

out vec4 o_color;

void main() {
    vec3 c = texture(u_scene, v_uv).rgb;
    vec3 bright = c * smoothstep(vec3(u_threshold_low), vec3(u_threshold_high), c);
    o_color = vec4(clamp(bright, 0.0, 1.0), 1.0);
}
