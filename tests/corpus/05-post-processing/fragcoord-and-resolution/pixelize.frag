#version 330 core
// Lab 05, step 5: pixelize. Cut the picture into square blocks of u_block_size x u_block_size
// texels, counted from the bottom-left corner, and fill each block with the scene's colour at the
// block's centre.


uniform sampler2D u_scene;
uniform vec2 u_resolution;
uniform int u_block_size;  // in texels; odd in every scene, so a block has a middle texel

out vec4 o_color;

void main() {
    float n = float(u_block_size);
    vec2 block = floor(gl_FragCoord.xy / n);
    vec2 centre_uv = (block * n + n * 0.5) / u_resolution;
    o_color = vec4(texture(u_scene, centre_uv).rgb, 1.0);
}
