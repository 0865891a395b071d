#version 330 core
// The sky is a fullscreen triangle: the same vertex shader as every fullscreen pass.

layout(location = 0) in vec3 a_position;

out vec2 v_ndc;

void main() {
    v_ndc = a_position.xy;
    gl_Position = vec4(a_position, 1.0);
}
