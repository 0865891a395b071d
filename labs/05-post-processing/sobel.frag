#version 330 core
// Lab 05, step 6: Sobel edges. Estimate the gradient of the picture's luma with the two 3x3
// Sobel kernels and write its magnitude as a grey: bright where the picture changes fast.

in vec2 v_uv;

uniform sampler2D u_scene;

out vec4 o_color;

void main() {
    // TODO(student): read the luma (BT.709 weights, as in grayscale.frag) of the 3x3 texels
    // around this one, apply the horizontal and vertical Sobel kernels to get gx and gy, and
    // write sqrt(gx^2 + gy^2) to all three channels.
    o_color = vec4(0.0, 0.0, 0.0, 1.0);
}
