#version 330 core
// Lab 05: Gaussian blur. texelFetch reads exact texels by index, no uv arithmetic needed.

uniform sampler2D u_scene;
uniform int u_gauss_radius;
uniform float u_gauss_sigma;

out vec4 o_color;

void main() {
    ivec2 here = ivec2(gl_FragCoord.xy);
    vec3 sum = vec3(0.0);
    float total = 0.0;
    for (int dy = -u_gauss_radius; dy <= u_gauss_radius; ++dy) {
        for (int dx = -u_gauss_radius; dx <= u_gauss_radius; ++dx) {
            float w = exp(-float(dx * dx + dy * dy) / (2.0 * u_gauss_sigma * u_gauss_sigma));
            sum += w * texelFetch(u_scene, here + ivec2(dx, dy), 0).rgb;
            total += w;
        }
    }
    o_color = vec4(sum / total, 1.0);
}
