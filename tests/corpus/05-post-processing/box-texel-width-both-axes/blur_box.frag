#version 330 core
// Lab 05: box blur.

in vec2 v_uv;

uniform sampler2D u_scene;
uniform int u_box_radius;  // r, in texels

out vec4 o_color;

void main() {
    // One texel in uv units: 1 / the texture's width (texels are square).
    vec2 texel = vec2(1.0 / float(textureSize(u_scene, 0).x));
    vec3 sum = vec3(0.0);
    for (int y = -u_box_radius; y <= u_box_radius; ++y) {
        for (int x = -u_box_radius; x <= u_box_radius; ++x) {
            sum += texture(u_scene, v_uv + vec2(x, y) * texel).rgb;
        }
    }
    float side = float(2 * u_box_radius + 1);
    o_color = vec4(sum / (side * side), 1.0);
}
