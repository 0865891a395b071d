#version 330 core
// Lab 05: passthrough.

in vec2 v_uv;

uniform sampler2D u_scene;

out vec4 o_color;

void main() {
    // Textures are stored top row first, so flip v to get the picture the right way up.
    vec2 uv = vec2(v_uv.x, 1.0 - v_uv.y);
    o_color = vec4(texture(u_scene, uv).rgb, 1.0);
}
