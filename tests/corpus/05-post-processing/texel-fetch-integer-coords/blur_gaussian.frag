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

// Each function below is one idea of the lab and is graded on its own: keep their names and
// parameters (README, "How it is graded").

// One texel in uv units, as in blur_box.frag.
vec2 texelSize() {
    return 1.0 / vec2(textureSize(u_scene, 0));
}

// The Gaussian blur at uv: the (2r+1) x (2r+1) taps one texel apart, r = radius, each weighed by
// w(x, y), divided by the sum of the weights used (the README says why not 1 / (2 pi sigma^2)).
vec3 gaussianBlur(vec2 uv, vec2 texel, int radius, float sigma) {
    // texelFetch with a clamped integer index (see blur_box.frag).
    ivec2 size = textureSize(u_scene, 0);
    ivec2 here = ivec2(uv / texel);
    vec3 sum = vec3(0.0);
    float total = 0.0;
    for (int dy = -radius; dy <= radius; ++dy) {
        for (int dx = -radius; dx <= radius; ++dx) {
            float w = exp(-float(dx * dx + dy * dy) / (2.0 * sigma * sigma));
            sum += w * texelFetch(u_scene, clamp(here + ivec2(dx, dy), ivec2(0), size - 1), 0).rgb;
            total += w;
        }
    }
    return sum / total;
}

void main() {
    o_color = vec4(gaussianBlur(v_uv, texelSize(), u_gauss_radius, u_gauss_sigma), 1.0);
}
