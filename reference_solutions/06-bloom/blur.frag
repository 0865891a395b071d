#version 330 core
// Reference solution, 06-bloom, passes "blur<level>_h" and "blur<level>_v": one direction of a
// separable 7-tap Gaussian blur. Run once with u_direction = (1, 0) and once with (0, 1).
//
// A 2D Gaussian G(x, y) = exp(-(x^2 + y^2) / (2 sigma^2)) / (2 pi sigma^2) is the product
// g(x) g(y) of two 1D Gaussians, so blurring the rows and then the columns equals the 2D blur at
// 2 * 7 taps instead of 7 * 7 (separable filtering: Szeliski, "Computer Vision: Algorithms and
// Applications", Springer, 2nd ed. 2022, section 3.2). The taps sit at offsets -3..3 texels,
// with sigma = 1.5 texels:
//   w_k = exp(-k^2 / (2 sigma^2)) / sum_{j=-3..3} exp(-j^2 / (2 sigma^2))
// They are normalised over the 7 taps (not by 1 / (sigma sqrt(2 pi)), which is the normalisation
// of the infinite kernel), so they sum to exactly 1 and a flat image stays as bright as it was.
//
// The step is one texel of the INPUT: the first pass of each level reads an image twice its own
// size (u_resolution is the size of the target, not of the input).

in vec2 v_uv;

uniform sampler2D u_image;
uniform vec2 u_direction;  // (1, 0): horizontal; (0, 1): vertical

out vec4 o_color;

// w_0 .. w_3 for sigma = 1.5; w_0 + 2 (w_1 + w_2 + w_3) = 1.
const float c_weights[4] = float[4](0.270682149, 0.216745321, 0.111280758, 0.036632845);

// The weight of the tap k texels from the centre, k = -3..3: the kernel is symmetric.
float tapWeight(int k) {
    return c_weights[abs(k)];
}

// One texel of the input along direction, in texture coordinates.
vec2 tapStep(vec2 direction) {
    return direction / vec2(textureSize(u_image, 0));
}

void main() {
    vec2 offset = tapStep(u_direction);
    vec3 sum = tapWeight(0) * texture(u_image, v_uv).rgb;
    for (int k = 1; k <= 3; ++k) {
        sum += tapWeight(k) * texture(u_image, v_uv + float(k) * offset).rgb;
        sum += tapWeight(-k) * texture(u_image, v_uv - float(k) * offset).rgb;
    }
    o_color = vec4(sum, 1.0);
}
