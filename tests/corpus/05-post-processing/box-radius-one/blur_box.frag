#version 330 core
// Lab 05: box blur.

in vec2 v_uv;

uniform sampler2D u_scene;
uniform int u_box_radius;  // r, in texels

out vec4 o_color;

void main() {
    // One texel in uv units: uv runs 0..1 over the whole texture, so a texel is 1 / its size.
    vec2 texel = 1.0 / vec2(textureSize(u_scene, 0));
    vec3 sum = vec3(0.0);
    // The 3x3 neighbourhood.
    for (int y = -1; y <= 1; ++y) {
        for (int x = -1; x <= 1; ++x) {
            sum += texture(u_scene, v_uv + vec2(x, y) * texel).rgb;
        }
    }
    o_color = vec4(sum / 9.0, 1.0);
}
