#version 330 core
// Lab 05, step 1: passthrough. Show the scene exactly as the scene pass drew it.
//
// This is a fullscreen pass: shared/fullscreen.vert draws one triangle over the whole target and
// hands you v_uv, which runs from (0, 0) at the bottom-left corner to (1, 1) at the top-right.
// u_scene is the texture the scene pass drew into; it has the same size as this pass's target.


uniform sampler2D u_scene;
uniform vec2 u_resolution;

out vec4 o_color;

void main() {
    vec2 uv = gl_FragCoord.xy / u_resolution;
    o_color = vec4(texture(u_scene, uv).rgb, 1.0);
}
