#version 330 core
// Lab 05: passthrough with the uv computed from the fragment's position: gl_FragCoord.xy is the
// pixel centre in pixels, u_resolution the target's size, so their ratio is the texel centre.

uniform sampler2D u_scene;
uniform vec2 u_resolution;

out vec4 o_color;

void main() {
    vec2 uv = gl_FragCoord.xy / u_resolution;
    o_color = vec4(texture(u_scene, uv).rgb, 1.0);
}
