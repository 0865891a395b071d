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

// One texel in uv units (see blur_box.frag).
vec2 texelSize() {
    return 1.0 / vec2(textureSize(u_scene, 0));
}

vec3 gaussianBlur(vec2 uv, vec2 texel, int radius, float sigma) {
    float two_sigma_sq = 2.0 * sigma * sigma;
    vec3 sum = vec3(0.0);
    float weight_sum = 0.0;
    for (int y = -radius; y <= radius; ++y) {
        for (int x = -radius; x <= radius; ++x) {
            float w = exp(-float(x * x + y * y) / two_sigma_sq);
            sum += w * texture(u_scene, uv + vec2(x, y) * texel).rgb;
            weight_sum += w;
        }
    }
    return sum / weight_sum;
}

void main() {
    o_color = vec4(gaussianBlur(v_uv, texelSize(), u_gauss_radius, u_gauss_sigma), 1.0);
}
