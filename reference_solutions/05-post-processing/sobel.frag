#version 330 core
// Reference solution, 05-post-processing: Sobel edge detection on luma. Two 3x3 kernels estimate
// the horizontal and vertical derivatives of the image, each smoothing across the other axis
// with weights 1 2 1:
//        | -1 0 +1 |          | +1 +2 +1 |
//   Gx = | -2 0 +2 |     Gy = |  0  0  0 |
//        | -1 0 +1 |          | -1 -2 -1 |      (top row is +y, up)
// and the edge strength is the length of the gradient, sqrt(Gx^2 + Gy^2). (I. Sobel and
// G. Feldman, "An Isotropic 3x3 Image Gradient Operator", talk at the Stanford Artificial
// Intelligence Project, 1968; in print in R. Duda and P. Hart, "Pattern Classification and Scene
// Analysis", Wiley, 1973.) It runs on luma, BT.709 weights as in grayscale.frag, so an edge
// between two colours counts by how different they look, whatever channel differs.

in vec2 v_uv;

uniform sampler2D u_scene;

out vec4 o_color;

const vec3 kLumaWeights = vec3(0.2126, 0.7152, 0.0722);

float luma(vec3 color) {
    return dot(color, kLumaWeights);
}

// One texel in uv units (see blur_box.frag).
vec2 texelSize() {
    return 1.0 / vec2(textureSize(u_scene, 0));
}

// The length of the Sobel gradient of luma at uv, the taps one texel apart.
float sobelMagnitude(vec2 uv, vec2 texel) {
    float top_left = luma(texture(u_scene, uv + vec2(-1, 1) * texel).rgb);
    float top = luma(texture(u_scene, uv + vec2(0, 1) * texel).rgb);
    float top_right = luma(texture(u_scene, uv + vec2(1, 1) * texel).rgb);
    float left = luma(texture(u_scene, uv + vec2(-1, 0) * texel).rgb);
    float right = luma(texture(u_scene, uv + vec2(1, 0) * texel).rgb);
    float bottom_left = luma(texture(u_scene, uv + vec2(-1, -1) * texel).rgb);
    float bottom = luma(texture(u_scene, uv + vec2(0, -1) * texel).rgb);
    float bottom_right = luma(texture(u_scene, uv + vec2(1, -1) * texel).rgb);

    float gx = (top_right + 2.0 * right + bottom_right) - (top_left + 2.0 * left + bottom_left);
    float gy = (top_left + 2.0 * top + top_right) - (bottom_left + 2.0 * bottom + bottom_right);
    return sqrt(gx * gx + gy * gy);
}

void main() {
    o_color = vec4(vec3(sobelMagnitude(v_uv, texelSize())), 1.0);
}
