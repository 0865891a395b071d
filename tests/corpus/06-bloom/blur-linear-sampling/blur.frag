#version 330 core
// The same 7-tap Gaussian (sigma 1.5) with 5 texture reads instead of 7: the taps at 1 and 2
// texels share one bilinear read placed between them, at (1 w1 + 2 w2) / (w1 + w2), weighted
// w1 + w2 (the "linear sampling" trick, D. Rakos, "Efficient Gaussian blur with linear sampling",
// 2010; exact when the pixel centre is on a texel centre, close enough when it is not).

in vec2 v_uv;

uniform sampler2D u_image;
uniform vec2 u_direction;

out vec4 o_color;

const float W0 = 0.270682149;
const float W1 = 0.216745321;
const float W2 = 0.111280758;
const float W3 = 0.036632845;

void main() {
    vec2 texel = u_direction / vec2(textureSize(u_image, 0));
    float w12 = W1 + W2;
    vec2 o12 = texel * (W1 + 2.0 * W2) / w12;
    vec3 sum = W0 * texture(u_image, v_uv).rgb;
    sum += w12 * (texture(u_image, v_uv + o12).rgb + texture(u_image, v_uv - o12).rgb);
    sum += W3 * (texture(u_image, v_uv + 3.0 * texel).rgb + texture(u_image, v_uv - 3.0 * texel).rgb);
    o_color = vec4(sum, 1.0);
}
