#version 330 core
// Separable Gaussian blur, one direction per pass. Weights straight from the Gaussian
// exp(-x^2 / (2 sigma^2)) with sigma = 1.5.

in vec2 v_uv;

uniform sampler2D u_image;
uniform vec2 u_direction;

out vec4 o_color;

const float SIGMA = 1.5;

void main() {
    vec2 texel = 1.0 / vec2(textureSize(u_image, 0));
    vec3 sum = vec3(0.0);
    for (int k = -3; k <= 3; ++k) {
        float x = float(k);
        float w = exp(-(x * x) / (2.0 * SIGMA * SIGMA));  // 1 at the centre, falls off outwards
        sum += w * texture(u_image, v_uv + x * texel * u_direction).rgb;
    }
    o_color = vec4(sum, 1.0);
}
