#version 330 core
// Lab 05: grayscale.

in vec2 v_uv;

uniform sampler2D u_scene;

out vec4 o_color;

void main() {
    vec3 color = texture(u_scene, v_uv).rgb;
    // Gray = the average of the three channels, so none of them is favoured.
    float gray = (color.r + color.g + color.b) / 3.0;
    o_color = vec4(vec3(gray), 1.0);
}
