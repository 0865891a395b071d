#version 330 core
// Lab 05: box blur.

in vec2 v_uv;

uniform sampler2D u_scene;
uniform int u_box_radius;

out vec4 o_color;

void main() {
    vec2 texel = 1.0 / vec2(textureSize(u_scene, 0));
    vec3 sum = vec3(0.0);
    for (int y = -u_box_radius; y <= u_box_radius; ++y) {
        for (int x = -u_box_radius; x <= u_box_radius; ++x) {
            sum += texture(u_scene, v_uv + vec2(x, y) * texel);
        }
    }
    float taps = float((2 * u_box_radius + 1) * (2 * u_box_radius + 1));
    o_color = vec4(sum / taps, 1.0);
}
