#version 330 core
// Lab 05, step 1: passthrough. Show the scene exactly as the scene pass drew it.
//
// This is a fullscreen pass: shared/fullscreen.vert draws one triangle over the whole target and
// hands you v_uv, which runs from (0, 0) at the bottom-left corner to (1, 1) at the top-right.
// u_scene is the texture the scene pass drew into; it has the same size as this pass's target.

in vec2 v_uv;  // (0, 0) bottom-left .. (1, 1) top-right: the centre of this fragment's texel
// (Reading texelFetch(u_scene, ivec2(gl_FragCoord.xy), 0) instead? Then delete this line and what
// reads it: the grader warns about an input a shader never uses.)

uniform sampler2D u_scene;

out vec4 o_color;

void main() {
    vec2 uv = v_uv;  // this fragment's texture coordinate
    // Textures are stored top row first, so flip v to get the picture the right way up.
    uv = vec2(uv.x, 1.0 - uv.y);
    o_color = vec4(texture(u_scene, uv).rgb, 1.0);
}
