#version 330 core
// Lab 05, step 5: pixelize with integer arithmetic. Integer division rounds down, so (p / n) * n
// is the first texel of the block; n / 2 more is the middle texel (n is odd: 7 / 2 = 3, the 4th of 7).

uniform sampler2D u_scene;
uniform int u_block_size;

out vec4 o_color;

void main() {
    ivec2 size = textureSize(u_scene, 0);
    ivec2 p = ivec2(gl_FragCoord.xy);
    ivec2 centre = (p / u_block_size) * u_block_size + u_block_size / 2;
    // The last block of a row can stick out of the image: its centre may too.
    centre = min(centre, size - 1);
    o_color = vec4(texelFetch(u_scene, centre, 0).rgb, 1.0);
}
