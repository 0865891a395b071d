#version 330 core
// Lab 05: pixelize. Block index from the pixel position, then the centre of that block, in uv.
// This pass's target has the scene's size, so u_resolution is the scene's size as well.

uniform sampler2D u_scene;
uniform vec2 u_resolution;
uniform int u_block_size;

out vec4 o_color;

void main() {
    float n = float(u_block_size);
    vec2 block = floor(gl_FragCoord.xy / n);
    vec2 centre_uv = (block * n + n * 0.5) / u_resolution;
    o_color = vec4(texture(u_scene, centre_uv).rgb, 1.0);
}
