#version 330 core
// Lab 05: pixelize.

in vec2 v_uv;

uniform sampler2D u_scene;
uniform int u_block_size;

out vec4 o_color;

void main() {
    // Size of one block in uv units, then round the uv down to the start of its block.
    vec2 block = float(u_block_size) / vec2(textureSize(u_scene, 0));
    vec2 uv = floor(v_uv / block) * block;
    o_color = vec4(texture(u_scene, uv).rgb, 1.0);
}
