#version 330 core
// 7-tap Gaussian blur along u_direction; one texel is 1 / u_resolution.

in vec2 v_uv;

uniform sampler2D u_image;
uniform vec2 u_direction;
uniform vec2 u_resolution;  // size of the image in pixels

out vec4 o_color;

const float c_weights[4] = float[4](0.270682149, 0.216745321, 0.111280758, 0.036632845);

void main() {
    vec2 texel = 1.0 / u_resolution;
    vec3 sum = c_weights[0] * texture(u_image, v_uv).rgb;
    for (int k = 1; k <= 3; ++k) {
        vec2 offset = float(k) * texel * u_direction;
        sum += c_weights[k] * texture(u_image, v_uv + offset).rgb;
        sum += c_weights[k] * texture(u_image, v_uv - offset).rgb;
    }
    o_color = vec4(sum, 1.0);
}
