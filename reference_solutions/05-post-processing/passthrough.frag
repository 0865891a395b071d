#version 330 core
// Reference solution, 05-post-processing: passthrough. Every fragment of a fullscreen pass reads
// the scene texel under it: v_uv runs 0..1 across the target, and the target has the scene's
// size, so v_uv lands on the centre of "its" texel. The y axis needs no flip: the scene was drawn
// by OpenGL into a texture, and both put row 0 at the bottom (t = 0).

in vec2 v_uv;

uniform sampler2D u_scene;

out vec4 o_color;

void main() {
    o_color = vec4(texture(u_scene, v_uv).rgb, 1.0);
}
