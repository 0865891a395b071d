#version 330 core
// Lab 05: Gaussian blur.
// G(x, y) = 1 / (2 pi sigma^2) * exp(-(x^2 + y^2) / (2 sigma^2)), the 2D Gaussian; its
// integral is 1, so the weights already sum to one and need no extra division.

in vec2 v_uv;

uniform sampler2D u_scene;
uniform int u_gauss_radius;
uniform float u_gauss_sigma;

out vec4 o_color;

const float PI = 3.14159265358979;

void main() {
    vec2 texel = 1.0 / vec2(textureSize(u_scene, 0));
    float s2 = u_gauss_sigma * u_gauss_sigma;
    vec3 sum = vec3(0.0);
    for (int y = -u_gauss_radius; y <= u_gauss_radius; ++y) {
        for (int x = -u_gauss_radius; x <= u_gauss_radius; ++x) {
            float w = exp(-float(x * x + y * y) / (2.0 * s2)) / (2.0 * PI * s2);
            sum += w * texture(u_scene, v_uv + vec2(x, y) * texel).rgb;
        }
    }
    o_color = vec4(sum, 1.0);
}
