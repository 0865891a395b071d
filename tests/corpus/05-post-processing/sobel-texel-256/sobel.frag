#version 330 core
// Lab 05: Sobel edges on luma.

in vec2 v_uv;

uniform sampler2D u_scene;

out vec4 o_color;

const vec3 W = vec3(0.2126, 0.7152, 0.0722);
const float TEXEL = 1.0 / 256.0;  // the renders are 256 x 256

float L(float dx, float dy) {
    return dot(texture(u_scene, v_uv + vec2(dx, dy) * TEXEL).rgb, W);
}

void main() {
    float gx = (L(1, 1) + 2.0 * L(1, 0) + L(1, -1)) - (L(-1, 1) + 2.0 * L(-1, 0) + L(-1, -1));
    float gy = (L(-1, 1) + 2.0 * L(0, 1) + L(1, 1)) - (L(-1, -1) + 2.0 * L(0, -1) + L(1, -1));
    o_color = vec4(vec3(sqrt(gx * gx + gy * gy)), 1.0);
}
