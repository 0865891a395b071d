#version 330 core
// Lab 05: Gaussian blur. The 2D Gaussian is a product of two 1D ones,
// exp(-(x^2 + y^2) / 2s^2) = exp(-x^2 / 2s^2) * exp(-y^2 / 2s^2), so I compute the 1D weights
// once, normalise them to sum to one, and weigh each tap by wx * wy (whose sum is then 1 * 1).

in vec2 v_uv;

uniform sampler2D u_scene;
uniform int u_gauss_radius;
uniform float u_gauss_sigma;

out vec4 o_color;

const int kMaxRadius = 16;

void main() {
    float w[2 * kMaxRadius + 1];
    float total = 0.0;
    for (int i = -u_gauss_radius; i <= u_gauss_radius; ++i) {
        w[i + kMaxRadius] = exp(-float(i * i) / (2.0 * u_gauss_sigma * u_gauss_sigma));
        total += w[i + kMaxRadius];
    }
    for (int i = -u_gauss_radius; i <= u_gauss_radius; ++i) {
        w[i + kMaxRadius] /= total;
    }

    vec2 texel = 1.0 / vec2(textureSize(u_scene, 0));
    vec3 result = vec3(0.0);
    for (int y = -u_gauss_radius; y <= u_gauss_radius; ++y) {
        vec3 row = vec3(0.0);
        for (int x = -u_gauss_radius; x <= u_gauss_radius; ++x) {
            row += w[x + kMaxRadius] * texture(u_scene, v_uv + vec2(x, y) * texel).rgb;
        }
        result += w[y + kMaxRadius] * row;
    }
    o_color = vec4(result, 1.0);
}
