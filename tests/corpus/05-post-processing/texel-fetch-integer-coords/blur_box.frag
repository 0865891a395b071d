#version 330 core
// Lab 05: box blur with texelFetch. texelFetch reads one texel by its integer index, with no
// filtering and no wrap mode: outside the texture the result is undefined, so the index is
// clamped to the edge by hand (what the sampler's clamp-to-edge does for texture()).

uniform sampler2D u_scene;
uniform int u_box_radius;

out vec4 o_color;

void main() {
    ivec2 size = textureSize(u_scene, 0);
    ivec2 here = ivec2(gl_FragCoord.xy);
    vec3 sum = vec3(0.0);
    for (int dy = -u_box_radius; dy <= u_box_radius; ++dy) {
        for (int dx = -u_box_radius; dx <= u_box_radius; ++dx) {
            ivec2 p = clamp(here + ivec2(dx, dy), ivec2(0), size - 1);
            sum += texelFetch(u_scene, p, 0).rgb;
        }
    }
    int n = 2 * u_box_radius + 1;
    o_color = vec4(sum / float(n * n), 1.0);
}
