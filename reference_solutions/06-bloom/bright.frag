#version 330 core
// Reference solution, 06-bloom, pass "bright": keep what is brighter than the threshold.
//
// Each colour component on its own:  b = c * smoothstep(t_low, t_high, c)
// Below t_low nothing passes, above t_high everything does, and in between the Hermite ramp
// 3x^2 - 2x^3 fades it in, so a surface that slowly brightens does not grow a hard-edged halo.
// Per component, so a saturated red light (R far above 1, G and B near 0) blooms red even though
// its luminance is low. The values are NOT clamped: a highlight of 6 must bloom more than one of 1.5
// (Spencer, Shirley, Zimmerman, Greenberg, "Physically-Based Glare Effects for Digital Images",
// SIGGRAPH 1995: the glare added around a pixel is proportional to its radiance).

in vec2 v_uv;

uniform sampler2D u_scene;  // the HDR scene
uniform float u_threshold_low;
uniform float u_threshold_high;

out vec4 o_color;

void main() {
    vec3 c = texture(u_scene, v_uv).rgb;
    vec3 keep = smoothstep(vec3(u_threshold_low), vec3(u_threshold_high), c);
    o_color = vec4(c * keep, 1.0);
}
