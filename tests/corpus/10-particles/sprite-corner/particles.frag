#version 330 core
// Lab 10 (particles), pass "draw" (fragment stage): the colour of one point. lab.json blends
// additively (src + dst), so where particles crowd the picture brightens.

in vec3 v_color;

uniform float u_intensity;

out vec4 o_color;

void main() {
    // Keep the fragments within the point's radius.
    if (length(gl_PointCoord) > 1.0) discard;
    o_color = vec4(u_intensity * v_color, 1.0);
}
