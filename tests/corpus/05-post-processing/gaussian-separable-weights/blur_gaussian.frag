#version 330 core
// Lab 05, step 4: Gaussian blur. Like the box blur, but the tap at offset (x, y) texels weighs
// w(x, y) = exp(-(x^2 + y^2) / (2 sigma^2)), so near texels count more than far ones.

in vec2 v_uv;  // (0, 0) bottom-left .. (1, 1) top-right: the centre of this fragment's texel
// (Reading by texelFetch instead? The texel under uv is ivec2(uv / texel); clamp every index to the
// texture, as the README says.)

uniform sampler2D u_scene;
uniform int u_gauss_radius;   // r, in texels: taps from -r to r on each axis
uniform float u_gauss_sigma;  // sigma, the standard deviation, in texels

out vec4 o_color;

const int kMaxRadius = 16;

// Each function below is one idea of the lab and is graded on its own: keep their names and
// parameters (README, "How it is graded").

// One texel in uv units, as in blur_box.frag.
vec2 texelSize() {
    return 1.0 / vec2(textureSize(u_scene, 0));
}

// The Gaussian blur at uv: the (2r+1) x (2r+1) taps one texel apart, r = radius, each weighed by
// w(x, y), divided by the sum of the weights used (the README says why not 1 / (2 pi sigma^2)).
vec3 gaussianBlur(vec2 uv, vec2 texel, int radius, float sigma) {
    // The 2D Gaussian is separable: normalised 1D weights, and the 2D weight wx * wy.
    float w[2 * kMaxRadius + 1];
    float total = 0.0;
    for (int i = -radius; i <= radius; ++i) {
        w[i + kMaxRadius] = exp(-float(i * i) / (2.0 * sigma * sigma));
        total += w[i + kMaxRadius];
    }
    for (int i = -radius; i <= radius; ++i) {
        w[i + kMaxRadius] /= total;
    }
    vec3 result = vec3(0.0);
    for (int y = -radius; y <= radius; ++y) {
        vec3 row = vec3(0.0);
        for (int x = -radius; x <= radius; ++x) {
            row += w[x + kMaxRadius] * texture(u_scene, uv + vec2(x, y) * texel).rgb;
        }
        result += w[y + kMaxRadius] * row;
    }
    return result;
}

void main() {
    o_color = vec4(gaussianBlur(v_uv, texelSize(), u_gauss_radius, u_gauss_sigma), 1.0);
}
