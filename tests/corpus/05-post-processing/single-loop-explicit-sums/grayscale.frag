#version 330 core
// Lab 05: grayscale, the BT.709 luma written out term by term.

in vec2 v_uv;

uniform sampler2D u_scene;

out vec4 o_color;

void main() {
    vec4 c = texture(u_scene, v_uv);
    float y = 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
    o_color = vec4(y, y, y, 1.0);
}
