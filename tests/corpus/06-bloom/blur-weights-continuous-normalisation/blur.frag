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
    const float SIGMA = 1.5;
    const float PI = 3.14159265;
    float x = float(k);
    return exp(-(x * x) / (2.0 * SIGMA * SIGMA)) / (SIGMA * sqrt(2.0 * PI));
}

// One texel of the input along direction, in texture coordinates.
vec2 tapStep(vec2 direction) {
    return direction / vec2(textureSize(u_image, 0));
}

void main() {
    vec2 offset = tapStep(u_direction);
    vec3 sum = vec3(0.0);
    for (int k = -3; k <= 3; ++k) {
        sum += tapWeight(k) * texture(u_image, v_uv + float(k) * offset).rgb;
    }
    o_color = vec4(sum, 1.0);
}
