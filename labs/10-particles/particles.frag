#version 330 core
// Lab 10 (particles), pass "draw" (fragment stage): the colour of one point. lab.json blends
// additively (src + dst), so where particles crowd the picture brightens.
// This file is one goal of the lab, graded on its own with the reference's particles.vert (README,
// "How it is graded"): keep the input v_color as it is.

in vec3 v_color;

uniform float u_intensity;

out vec4 o_color;

void main() {
    // TODO(student): a round sprite: gl_PointCoord runs 0..1 across the point's square; discard
    // the fragments outside the disc inscribed in it.
    o_color = vec4(u_intensity * v_color, 1.0);
}
