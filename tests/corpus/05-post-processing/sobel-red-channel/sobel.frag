#version 330 core
// Lab 05: Sobel edges.

in vec2 v_uv;

uniform sampler2D u_scene;

out vec4 o_color;

// The picture's intensity at an offset of (x, y) pixels.
float intensity(vec2 texel, float x, float y) {
    return texture(u_scene, v_uv + vec2(x, y) * texel).r;
}

void main() {
    vec2 texel = 1.0 / vec2(textureSize(u_scene, 0));
    float gx = -intensity(texel, -1.0, 1.0) - 2.0 * intensity(texel, -1.0, 0.0) - intensity(texel, -1.0, -1.0)
               + intensity(texel, 1.0, 1.0) + 2.0 * intensity(texel, 1.0, 0.0) + intensity(texel, 1.0, -1.0);
    float gy = intensity(texel, -1.0, 1.0) + 2.0 * intensity(texel, 0.0, 1.0) + intensity(texel, 1.0, 1.0)
               - intensity(texel, -1.0, -1.0) - 2.0 * intensity(texel, 0.0, -1.0) - intensity(texel, 1.0, -1.0);
    float g = sqrt(gx * gx + gy * gy);
    o_color = vec4(g, g, g, 1.0);
}
