#version 330 core
// Reference solution, 05-post-processing: box blur. The mean of the (2r+1) x (2r+1) texels
// around this one: every tap weighs 1 / (2r+1)^2, so the weights sum to one and a flat area
// keeps its brightness.

in vec2 v_uv;

uniform sampler2D u_scene;
uniform int u_box_radius;  // r, in texels

out vec4 o_color;

void main() {
    // One texel in uv units: uv runs 0..1 over the whole texture, so a texel is 1 / its size.
    vec2 texel = 1.0 / vec2(textureSize(u_scene, 0));
    vec3 sum = vec3(0.0);
    for (int y = -u_box_radius; y <= u_box_radius; ++y) {
        for (int x = -u_box_radius; x <= u_box_radius; ++x) {
            sum += texture(u_scene, v_uv + vec2(x, y) * texel).rgb;
        }
    }
    float side = float(2 * u_box_radius + 1);
    o_color = vec4(sum / (side * side), 1.0);
}
