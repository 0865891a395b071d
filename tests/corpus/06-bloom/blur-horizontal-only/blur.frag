#version 330 core
// 7-tap Gaussian blur, sigma = 1.5; u_direction picks the axis.

in vec2 v_uv;

uniform sampler2D u_image;
uniform vec2 u_direction;

out vec4 o_color;

const float c_weights[4] = float[4](0.270682149, 0.216745321, 0.111280758, 0.036632845);

void main() {
    vec2 size = vec2(textureSize(u_image, 0));
    // one texel to the right, turned into the blur direction by u_direction
    vec2 texel = vec2(1.0 / size.x, 0.0) * u_direction;
    vec3 sum = c_weights[0] * texture(u_image, v_uv).rgb;
    for (int k = 1; k <= 3; ++k) {
        sum += c_weights[k] * texture(u_image, v_uv + float(k) * texel).rgb;
        sum += c_weights[k] * texture(u_image, v_uv - float(k) * texel).rgb;
    }
    o_color = vec4(sum, 1.0);
}
