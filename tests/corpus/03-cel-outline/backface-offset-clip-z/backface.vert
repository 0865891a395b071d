#version 330 core
// Back-face lines: pull them toward the viewer a little. In clip space "toward the viewer" is
// a smaller z, and moving only z leaves the line on the same pixel.

layout(location = 0) in vec3 a_position;

uniform mat4 u_model_view;
uniform mat4 u_projection;
uniform float u_depth_offset;

void main() {
    gl_Position = u_projection * u_model_view * vec4(a_position, 1.0);
    gl_Position.z -= u_depth_offset;
}
