#version 330 core
// Lab 06 (bloom), passes "blur<level>_h" and "blur<level>_v": one direction of a separable 7-tap
// Gaussian blur. lab.json runs this shader six times: a horizontal pass (u_direction = (1, 0))
// then a vertical one (u_direction = (0, 1)) at each of three levels (1/2, 1/4 and 1/8 of the
// screen). The first pass of each level reads an image twice the size of its target.
//
// The taps sit at offsets -3, -2, ..., 3 TEXELS OF THE INPUT along u_direction, with Gaussian
// weights for sigma = 1.5 texels normalised so that the seven of them sum to 1:
//     w_k = exp(-k^2 / (2 sigma^2)) / sum_{j=-3..3} exp(-j^2 / (2 sigma^2))
// Texture coordinates run 0..1 across the image, so one texel is 1 / (the input's size).

in vec2 v_uv;

uniform sampler2D u_image;
uniform vec2 u_direction;  // (1, 0): horizontal; (0, 1): vertical

out vec4 o_color;

// Each function below is one idea of the lab and is graded on its own: keep their names and
// parameters (README, "How it is graded").

// The weight w_|k| of the tap k texels from the centre, k = -3..3.
float tapWeight(int k) {
    const float w[4] = float[4](0.270682149, 0.216745321, 0.111280758, 0.036632845);
    return w[abs(k)];
}

// One texel of the input along direction, in texture coordinates.
vec2 tapStep(vec2 direction) {
    return direction / vec2(textureSize(u_image, 0));
}

void main() {
    // The linear-sampling trick: one bilinear fetch between the taps at 1 and 2 texels reads
    // both at once, weighted w1 : w2, so 5 reads do the work of 7.
    vec2 texel = tapStep(u_direction);
    float w12 = tapWeight(1) + tapWeight(2);
    vec2 o12 = texel * (tapWeight(1) + 2.0 * tapWeight(2)) / w12;
    vec3 sum = tapWeight(0) * texture(u_image, v_uv).rgb;
    sum += w12 * (texture(u_image, v_uv + o12).rgb + texture(u_image, v_uv - o12).rgb);
    sum += tapWeight(3) * (texture(u_image, v_uv + 3.0 * texel).rgb + texture(u_image, v_uv - 3.0 * texel).rgb);
    o_color = vec4(sum, 1.0);
}
