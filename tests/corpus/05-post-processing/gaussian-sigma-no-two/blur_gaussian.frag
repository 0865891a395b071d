#version 330 core
// Lab 05: Gaussian blur, weights e^(-d^2 / sigma^2) normalised by their sum.

in vec2 v_uv;

uniform sampler2D u_scene;
uniform int u_gauss_radius;
uniform float u_gauss_sigma;

out vec4 o_color;

void main() {
    vec2 texel = 1.0 / vec2(textureSize(u_scene, 0));
    vec3 sum = vec3(0.0);
    float total = 0.0;
    for (int y = -u_gauss_radius; y <= u_gauss_radius; ++y) {
        for (int x = -u_gauss_radius; x <= u_gauss_radius; ++x) {
            float d2 = float(x * x + y * y);
            float w = exp(-d2 / (u_gauss_sigma * u_gauss_sigma));
            sum += w * texture(u_scene, v_uv + vec2(x, y) * texel).rgb;
            total += w;
        }
    }
    o_color = vec4(sum / total, 1.0);
}
