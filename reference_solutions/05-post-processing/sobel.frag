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

// Luma of the texel (x, y) texels away from this fragment's.
float luma(vec2 texel, int x, int y) {
    return dot(texture(u_scene, v_uv + vec2(x, y) * texel).rgb, kLumaWeights);
}

void main() {
    vec2 texel = 1.0 / vec2(textureSize(u_scene, 0));
    float top_left = luma(texel, -1, 1), top = luma(texel, 0, 1), top_right = luma(texel, 1, 1);
    float left = luma(texel, -1, 0), right = luma(texel, 1, 0);
    float bottom_left = luma(texel, -1, -1), bottom = luma(texel, 0, -1), bottom_right = luma(texel, 1, -1);

    float gx = (top_right + 2.0 * right + bottom_right) - (top_left + 2.0 * left + bottom_left);
    float gy = (top_left + 2.0 * top + top_right) - (bottom_left + 2.0 * bottom + bottom_right);
    float magnitude = sqrt(gx * gx + gy * gy);
    o_color = vec4(vec3(magnitude), 1.0);
}
