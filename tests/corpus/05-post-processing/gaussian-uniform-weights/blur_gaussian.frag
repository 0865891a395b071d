#version 330 core
// Lab 05: Gaussian blur.

in vec2 v_uv;

uniform sampler2D u_scene;
uniform int u_gauss_radius;   // r, in texels: taps from -r to r on each axis
uniform float u_gauss_sigma;  // standard deviation, in texels

out vec4 o_color;

void main() {
    vec2 texel = 1.0 / vec2(textureSize(u_scene, 0));
    vec3 sum = vec3(0.0);
    float weight_sum = 0.0;
    for (int y = -u_gauss_radius; y <= u_gauss_radius; ++y) {
        for (int x = -u_gauss_radius; x <= u_gauss_radius; ++x) {
            float w = 1.0;  // every tap counts the same
            sum += w * texture(u_scene, v_uv + vec2(x, y) * texel).rgb;
            weight_sum += w;
        }
    }
    o_color = vec4(sum / weight_sum, 1.0);
}
