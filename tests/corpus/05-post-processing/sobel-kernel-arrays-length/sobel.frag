#version 330 core
// Lab 05: Sobel edges. The two kernels as arrays, applied in one loop over the 3x3
// neighbourhood. I wrote them as in the textbook's convolution (flipped, y down), so my "gx"
// is really the vertical derivative with its sign flipped, and "gy" the horizontal one: the
// gradient's length is the same either way.

in vec2 v_uv;

uniform sampler2D u_scene;

out vec4 o_color;

// Row by row, (-1,-1) first: the offsets are vec2(i % 3 - 1, i / 3 - 1).
const float kKernelX[9] = float[9](1.0, 2.0, 1.0, 0.0, 0.0, 0.0, -1.0, -2.0, -1.0);
const float kKernelY[9] = float[9](1.0, 0.0, -1.0, 2.0, 0.0, -2.0, 1.0, 0.0, -1.0);

void main() {
    vec2 texel = vec2(1.0) / vec2(textureSize(u_scene, 0));
    vec2 g = vec2(0.0);
    for (int i = 0; i < 9; ++i) {
        vec2 offset = vec2(i % 3 - 1, i / 3 - 1);
        vec3 c = texture(u_scene, v_uv + offset * texel).rgb;
        float y = 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
        g += y * vec2(kKernelX[i], kKernelY[i]);
    }
    o_color = vec4(vec3(length(g)), 1.0);
}
