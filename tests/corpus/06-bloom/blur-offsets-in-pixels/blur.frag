#version 330 core
// 7-tap Gaussian, sigma = 1.5 pixels: the taps are 1, 2 and 3 pixels away along u_direction.

in vec2 v_uv;

uniform sampler2D u_image;
uniform vec2 u_direction;

out vec4 o_color;

const float c_weights[4] = float[4](0.270682149, 0.216745321, 0.111280758, 0.036632845);

void main() {
    vec3 sum = c_weights[0] * texture(u_image, v_uv).rgb;
    for (int k = 1; k <= 3; ++k) {
        vec2 offset = float(k) * u_direction;  // k pixels along the blur direction
        sum += c_weights[k] * texture(u_image, v_uv + offset).rgb;
        sum += c_weights[k] * texture(u_image, v_uv - offset).rgb;
    }
    o_color = vec4(sum, 1.0);
}
