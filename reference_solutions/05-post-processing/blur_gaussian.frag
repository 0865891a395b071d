#version 330 core
// Reference solution, 05-post-processing: Gaussian blur. Each tap at offset (x, y) texels weighs
//   w(x, y) = exp(-(x^2 + y^2) / (2 sigma^2))
// the 2D normal distribution without its constant 1 / (2 pi sigma^2) (Gonzalez and Woods,
// "Digital Image Processing", 4th ed., 2018, section 3.5). The constant makes the *continuous*
// Gaussian integrate to one; a kernel cut off at radius r sums to less than that, so the taps
// are divided by their own sum instead, which is exactly one whatever r and sigma are.

in vec2 v_uv;

uniform sampler2D u_scene;
uniform int u_gauss_radius;   // r, in texels: taps from -r to r on each axis
uniform float u_gauss_sigma;  // standard deviation, in texels

out vec4 o_color;

void main() {
    vec2 texel = 1.0 / vec2(textureSize(u_scene, 0));
    float two_sigma_sq = 2.0 * u_gauss_sigma * u_gauss_sigma;
    vec3 sum = vec3(0.0);
    float weight_sum = 0.0;
    for (int y = -u_gauss_radius; y <= u_gauss_radius; ++y) {
        for (int x = -u_gauss_radius; x <= u_gauss_radius; ++x) {
            float w = exp(-float(x * x + y * y) / two_sigma_sq);
            sum += w * texture(u_scene, v_uv + vec2(x, y) * texel).rgb;
            weight_sum += w;
        }
    }
    o_color = vec4(sum / weight_sum, 1.0);
}
