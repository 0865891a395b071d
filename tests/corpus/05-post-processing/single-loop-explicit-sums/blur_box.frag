#version 330 core
// Lab 05: box blur in a single loop over the (2r+1)^2 taps, counting them as it goes.

in vec2 v_uv;

uniform sampler2D u_scene;
uniform int u_box_radius;

out vec4 o_color;

void main() {
    vec2 texel = 1.0 / vec2(textureSize(u_scene, 0));
    int side = 2 * u_box_radius + 1;
    vec3 sum = vec3(0.0);
    float count = 0.0;
    for (int i = 0; i < side * side; ++i) {
        vec2 offset = vec2(i % side, i / side) - float(u_box_radius);
        sum += texture(u_scene, v_uv + offset * texel).rgb;
        count += 1.0;
    }
    o_color = vec4(sum / count, 1.0);
}
