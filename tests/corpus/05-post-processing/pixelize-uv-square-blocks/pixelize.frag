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
    // The block's side in uv: u_block_size texels of the texture's width.
    float block = float(u_block_size) / float(textureSize(u_scene, 0).x);
    vec2 corner = floor(v_uv / block) * block;   // the block's bottom-left corner, in uv
    vec2 centre = corner + 0.5 * block;          // and its centre
    o_color = vec4(texture(u_scene, centre).rgb, 1.0);
}
