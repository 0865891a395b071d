#version 330 core
// Lab 05: grayscale.

in vec2 v_uv;

uniform sampler2D u_scene;

out vec4 o_color;

void main() {
    vec3 color = texture(u_scene, v_uv).rgb;
    // The usual luminance formula (the one in every image-processing tutorial).
    float gray = 0.299 * color.r + 0.587 * color.g + 0.114 * color.b;
    o_color = vec4(vec3(gray), 1.0);
}
