#version 330 core
// Lab 05, step 2: grayscale. Replace each colour by its luma, the single brightness a viewer
// perceives, written to all three channels.

in vec2 v_uv;  // (0, 0) bottom-left .. (1, 1) top-right: the centre of this fragment's texel
// (Reading texelFetch(u_scene, ivec2(gl_FragCoord.xy), 0) instead? Then delete this line and what
// reads it: the grader warns about an input a shader never uses.)

uniform sampler2D u_scene;

out vec4 o_color;

// luma is graded on its own, together with the luma of sobel.frag: keep its name and parameters
// (README, "How it is graded").

// The luma of a colour, with the ITU-R BT.709 weights (see the README: why not simply
// (r + g + b) / 3?). sobel.frag needs the same function.
float luma(vec3 color) {
    // TODO(student)
    return 0.0;
}

void main() {
    vec3 color = texture(u_scene, v_uv).rgb;
    o_color = vec4(vec3(luma(color)), 1.0);  // the luma as a grey (luma, luma, luma)
}
