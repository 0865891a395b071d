#version 330 core
// Lab 05: Sobel edges on luma.

in vec2 v_uv;

uniform sampler2D u_scene;

out vec4 o_color;

float luma(vec2 uv) {
    return dot(texture(u_scene, uv).rgb, vec3(0.2126, 0.7152, 0.0722));
}

void main() {
    vec2 t = 1.0 / vec2(textureSize(u_scene, 0));
    // Horizontal kernel: right column minus left column.
    //  -1 0 1
    //  -1 0 1
    //  -1 0 1
    float gx = 0.0;
    float gy = 0.0;
    for (int j = -1; j <= 1; ++j) {
        gx += luma(v_uv + vec2(1, j) * t) - luma(v_uv + vec2(-1, j) * t);
        gy += luma(v_uv + vec2(j, 1) * t) - luma(v_uv + vec2(j, -1) * t);
    }
    o_color = vec4(vec3(sqrt(gx * gx + gy * gy)), 1.0);
}
