#version 330 core
// Lab 05: Gaussian blur.

in vec2 v_uv;

uniform sampler2D u_scene;
uniform int u_gauss_radius;   // r, in texels: taps from -r to r on each axis
uniform float u_gauss_sigma;  // standard deviation, in texels

out vec4 o_color;

void main() {
    vec2 texel = 1.0 / vec2(textureSize(u_scene, 0));
    float two_sigma_sq = 2.0 * u_gauss_sigma * u_gauss_sigma;
    // 3 sigma holds 99.7 % of the Gaussian: that is far enough.
    int radius = int(ceil(3.0 * u_gauss_sigma));
    vec3 sum = vec3(0.0);
    float weight_sum = 0.0;
    for (int y = -radius; y <= radius; ++y) {
        for (int x = -radius; x <= radius; ++x) {
            float w = exp(-float(x * x + y * y) / two_sigma_sq);
            sum += w * texture(u_scene, v_uv + vec2(x, y) * texel).rgb;
            weight_sum += w;
        }
    }
    o_color = vec4(sum / weight_sum, 1.0);
}
