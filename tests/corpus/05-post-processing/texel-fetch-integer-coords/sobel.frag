#version 330 core
// Lab 05: Sobel on luma with texelFetch and clamped integer indices.

uniform sampler2D u_scene;

out vec4 o_color;

float luma_at(ivec2 p) {
    p = clamp(p, ivec2(0), textureSize(u_scene, 0) - 1);
    return dot(texelFetch(u_scene, p, 0).rgb, vec3(0.2126, 0.7152, 0.0722));
}

void main() {
    ivec2 c = ivec2(gl_FragCoord.xy);
    float a = luma_at(c + ivec2(-1, 1)), b = luma_at(c + ivec2(0, 1)), d = luma_at(c + ivec2(1, 1));
    float e = luma_at(c + ivec2(-1, 0)), f = luma_at(c + ivec2(1, 0));
    float g = luma_at(c + ivec2(-1, -1)), h = luma_at(c + ivec2(0, -1)), k = luma_at(c + ivec2(1, -1));
    float gx = (d + 2.0 * f + k) - (a + 2.0 * e + g);
    float gy = (a + 2.0 * b + d) - (g + 2.0 * h + k);
    o_color = vec4(vec3(sqrt(gx * gx + gy * gy)), 1.0);
}
