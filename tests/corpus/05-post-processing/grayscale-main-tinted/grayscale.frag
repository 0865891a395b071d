#version 330 core
// Reference solution, 05-post-processing: grayscale by luma.
//   Y' = 0.2126 R' + 0.7152 G' + 0.0722 B'
// (ITU-R Recommendation BT.709-6, "Parameter values for the HDTV standards for production and
// international programme exchange", 2015, section 3, "Derivation of luminance signal".)
// The weights say how bright each primary looks to the eye: green most, blue least. A plain
// mean (R + G + B) / 3 would make a pure blue look as bright as a pure green.

in vec2 v_uv;

uniform sampler2D u_scene;

out vec4 o_color;

const vec3 kLumaWeights = vec3(0.2126, 0.7152, 0.0722);  // BT.709; they sum to 1, so white stays white

float luma(vec3 color) {
    return dot(color, kLumaWeights);
}

void main() {
    vec3 color = texture(u_scene, v_uv).rgb;
    o_color = vec4(color * luma(color), 1.0);  // the colour, darkened where it is dark
}
