#version 330 core
// Lab 05: box blur.

in vec2 v_uv;

uniform sampler2D u_scene;
uniform int u_box_radius;

out vec4 o_color;

void main() {
    vec3 sum = vec3(0.0);
    int count = 0;
    // Walk over the neighbouring pixels, r pixels in every direction.
    for (int y = -u_box_radius; y <= u_box_radius; ++y) {
        for (int x = -u_box_radius; x <= u_box_radius; ++x) {
            sum += texture(u_scene, v_uv + vec2(x, y)).rgb;
            count++;
        }
    }
    o_color = vec4(sum / float(count), 1.0);
}
