#version 330 core
// Separable Gaussian blur, 7 taps, sigma = 1.5 texels. The weights come from the Gaussian formula
// and are divided by their sum, so they add up to one whatever sigma is.

in vec2 v_uv;

uniform sampler2D u_image;
uniform vec2 u_direction;

out vec4 o_color;

const float SIGMA = 1.5;
const int RADIUS = 3;

float gaussian(float x) {
    return exp(-(x * x) / (2.0 * SIGMA * SIGMA));
}

void main() {
    vec2 step_uv = u_direction / vec2(textureSize(u_image, 0));
    vec3 sum = vec3(0.0);
    float total = 0.0;
    for (int k = -RADIUS; k <= RADIUS; ++k) {
        float w = gaussian(float(k));
        sum += w * texture(u_image, v_uv + float(k) * step_uv).rgb;
        total += w;
    }
    o_color = vec4(sum / total, 1.0);
}
