#version 330 core
// Lab 10 (particles), pass "draw" (fragment stage): a round sprite. gl_PointCoord runs 0..1
// across the point's square, (0.5, 0.5) at its centre; fragments outside the inscribed disc are
// discarded. lab.json blends additively (src + dst), so where particles crowd the picture
// brightens.

in vec3 v_color;

uniform float u_intensity;

out vec4 o_color;

void main() {
    vec2 d = 2.0 * gl_PointCoord - 1.0;  // -1..1 across the point
    if (dot(d, d) > 1.0) discard;
    o_color = vec4(u_intensity * v_color, 1.0);
}
