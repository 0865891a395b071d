#version 330 core
// Lab 05: pixelize.

in vec2 v_uv;

uniform sampler2D u_scene;
uniform int u_block_size;  // in texels

out vec4 o_color;

void main() {
    // The block's side in uv: u_block_size texels of the texture's width.
    float block = float(u_block_size) / float(textureSize(u_scene, 0).x);
    vec2 corner = floor(v_uv / block) * block;     // the block's bottom-left corner, in uv
    vec2 centre = corner + 0.5 * block;            // and its centre
    o_color = vec4(texture(u_scene, centre).rgb, 1.0);
}
