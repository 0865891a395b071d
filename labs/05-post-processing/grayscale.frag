#version 330 core
// Lab 05, step 2: grayscale. Replace each colour by its luma, the single brightness a viewer
// perceives, written to all three channels.

in vec2 v_uv;  // (0, 0) bottom-left .. (1, 1) top-right: the centre of this fragment's texel
// (Reading texelFetch(u_scene, ivec2(gl_FragCoord.xy), 0) instead? Then delete this line and what
// reads it: the grader warns about an input a shader never uses.)

uniform sampler2D u_scene;

out vec4 o_color;

void main() {
    vec3 color = texture(u_scene, v_uv).rgb;
    // TODO(student): compute the luma of color with the ITU-R BT.709 weights (see the README:
    // why not simply (r + g + b) / 3?) and write it as a grey (luma, luma, luma).
    o_color = vec4(color, 1.0);
}
