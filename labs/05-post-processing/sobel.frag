#version 330 core
// Lab 05, step 6: Sobel edges. Estimate the gradient of the picture's luma with the two 3x3
// Sobel kernels and write its magnitude as a grey: bright where the picture changes fast.

in vec2 v_uv;  // (0, 0) bottom-left .. (1, 1) top-right: the centre of this fragment's texel
// (Reading by texelFetch from ivec2(gl_FragCoord.xy) instead? Clamp every index to the texture,
// as the README says, and delete this line and what reads it: the grader warns about an input a
// shader never uses.)

uniform sampler2D u_scene;

out vec4 o_color;

void main() {
    vec2 uv = v_uv;  // this fragment's texture coordinate: the centre of the 3x3 neighbourhood
    // TODO(student): read the luma (BT.709 weights, as in grayscale.frag) of the 3x3 texels
    // around this one, apply the horizontal and vertical Sobel kernels to get gx and gy, and
    // write sqrt(gx^2 + gy^2) to all three channels.
    o_color = vec4(0.0, 0.0, 0.0, 1.0);
}
