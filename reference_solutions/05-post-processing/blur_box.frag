#version 330 core
// Reference solution, 05-post-processing: box blur. The mean of the (2r+1) x (2r+1) texels
// around this one: every tap weighs 1 / (2r+1)^2, so the weights sum to one and a flat area
// keeps its brightness.

in vec2 v_uv;

uniform sampler2D u_scene;
uniform int u_box_radius;  // r, in texels

out vec4 o_color;

// One texel in uv units: uv runs 0..1 over the whole texture, so a texel is 1 / its size, which
// is not the same across (1/320) as up (1/240).
vec2 texelSize() {
    return 1.0 / vec2(textureSize(u_scene, 0));
}

vec3 boxBlur(vec2 uv, vec2 texel, int radius) {
    vec3 sum = vec3(0.0);
    for (int y = -radius; y <= radius; ++y) {
        for (int x = -radius; x <= radius; ++x) {
            sum += texture(u_scene, uv + vec2(x, y) * texel).rgb;
        }
    }
    float side = float(2 * radius + 1);
    return sum / (side * side);
}

void main() {
    o_color = vec4(boxBlur(v_uv, texelSize(), u_box_radius), 1.0);
}
