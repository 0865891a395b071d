#version 330 core
// Reference solution, 05-post-processing: pixelize. The target is cut into square blocks of
// u_block_size texels, counted from the bottom-left corner; every fragment of a block shows the
// scene texel at the block's centre. (The block sizes are odd, so the centre is a texel's
// centre: with an even size it would be the corner between four texels.)

in vec2 v_uv;

uniform sampler2D u_scene;
uniform int u_block_size;  // in texels

out vec4 o_color;

void main() {
    vec2 size = vec2(textureSize(u_scene, 0));
    float block = float(u_block_size);
    vec2 pixel = v_uv * size;                      // this fragment, in texels (x.5 at centres)
    vec2 corner = floor(pixel / block) * block;    // the block's bottom-left corner
    vec2 centre = corner + 0.5 * block;            // and its centre
    o_color = vec4(texture(u_scene, centre / size).rgb, 1.0);
}
