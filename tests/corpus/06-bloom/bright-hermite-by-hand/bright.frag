#version 330 core
// Lab 06 (bloom), pass "bright": keep only what is brighter than the threshold.
//
// Input: u_scene, the Phong scene in a float target, with values above 1 where it is very bright.
// Output: the part of each pixel that should glow, in HDR (do not clamp it: a highlight of 6
// must glow more than one of 1.5).
//
// For EACH colour component c (not for the pixel's luminance: a saturated red light is dark in
// luminance but must glow red):
//     bright = c * smoothstep(u_threshold_low, u_threshold_high, c)
// smoothstep is 0 below the low edge, 1 above the high edge, and a smooth ramp between them.

in vec2 v_uv;

uniform sampler2D u_scene;
uniform float u_threshold_low;   // 1.0: nothing below this glows
uniform float u_threshold_high;  // 2.0: everything above this glows fully

out vec4 o_color;

void main() {
    vec3 c = texture(u_scene, v_uv).rgb;
    vec3 t = clamp((c - u_threshold_low) / (u_threshold_high - u_threshold_low), 0.0, 1.0);
    vec3 ramp = t * t * (3.0 - 2.0 * t);
    o_color = vec4(c.r * ramp.r, c.g * ramp.g, c.b * ramp.b, 1.0);
}
