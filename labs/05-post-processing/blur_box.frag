#version 330 core
// Lab 05, step 3: box blur. Each output pixel is the plain average of the (2r+1) x (2r+1) scene
// texels centred on it, r = u_box_radius (it changes from scene to scene).

in vec2 v_uv;  // (0, 0) bottom-left .. (1, 1) top-right: the centre of this fragment's texel
// (Reading by texelFetch from ivec2(gl_FragCoord.xy) instead? Clamp every index to the texture,
// as the README says, and delete this line and what reads it: the grader warns about an input a
// shader never uses.)

uniform sampler2D u_scene;
uniform int u_box_radius;  // r, in texels

out vec4 o_color;

void main() {
    // TODO(student): the size of one texel in uv units. uv runs 0..1 over the whole texture;
    // textureSize(u_scene, 0) tells you how many texels that is.

    // TODO(student): sum the texels at offsets (x, y), x and y from -r to r, and divide by the
    // number of taps so that the weights sum to one.
    o_color = vec4(texture(u_scene, v_uv).rgb, 1.0);
}
