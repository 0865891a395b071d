#version 330 core
// Bright pass per component, smoothstep written out: t = (c - low) / (high - low) clamped to 0..1,
// then the Hermite ramp 3t^2 - 2t^3.

in vec2 v_uv;

uniform sampler2D u_scene;
uniform float u_threshold_low;
uniform float u_threshold_high;

out vec4 o_color;

void main() {
    vec3 c = texture(u_scene, v_uv).rgb;
    vec3 t = clamp((c - u_threshold_low) / (u_threshold_high - u_threshold_low), 0.0, 1.0);
    vec3 ramp = t * t * (3.0 - 2.0 * t);
    o_color = vec4(c.r * ramp.r, c.g * ramp.g, c.b * ramp.b, 1.0);
}
