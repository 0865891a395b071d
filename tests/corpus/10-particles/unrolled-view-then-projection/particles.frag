#version 330 core
// Lab 10 (particles), pass "draw" (fragment stage): the colour of one point. lab.json blends
// additively (src + dst), so where particles crowd the picture brightens.

in vec3 v_color;

uniform float u_intensity;

out vec4 o_color;

void main() {
    if (distance(gl_PointCoord, vec2(0.5)) > 0.5) discard;  // outside the inscribed disc
    o_color = vec4(u_intensity * v_color, 1.0);
}
