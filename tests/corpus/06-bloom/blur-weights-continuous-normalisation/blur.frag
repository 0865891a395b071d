#version 330 core
// Separable Gaussian blur, 7 taps, sigma = 1.5 texels, with the normalised Gaussian
// g(x) = exp(-x^2 / (2 sigma^2)) / (sigma sqrt(2 pi)), whose integral is 1.

in vec2 v_uv;

uniform sampler2D u_image;
uniform vec2 u_direction;

out vec4 o_color;

const float SIGMA = 1.5;
const float PI = 3.14159265;

float gaussian(float x) {
    return exp(-(x * x) / (2.0 * SIGMA * SIGMA)) / (SIGMA * sqrt(2.0 * PI));
}

void main() {
    vec2 texel = 1.0 / vec2(textureSize(u_image, 0));
    vec3 sum = vec3(0.0);
    for (int k = -3; k <= 3; ++k) {
        sum += gaussian(float(k)) * texture(u_image, v_uv + float(k) * texel * u_direction).rgb;
    }
    o_color = vec4(sum, 1.0);
}
