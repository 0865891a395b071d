#version 330 core
// Lab 05, step 1: passthrough, with integer texel coordinates. gl_FragCoord.xy is the pixel
// centre (i + 0.5, j + 0.5); converting it to ivec2 gives the texel (i, j) of the same-sized scene.

uniform sampler2D u_scene;

out vec4 o_color;

void main() {
    o_color = vec4(texelFetch(u_scene, ivec2(gl_FragCoord.xy), 0).rgb, 1.0);
}
