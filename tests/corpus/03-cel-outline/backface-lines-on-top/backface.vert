#version 330 core
// Back-face lines: the lines must not be hidden by the object, so put them at the very front
// of the depth range (NDC z = -1 after the divide by w).

layout(location = 0) in vec3 a_position;

uniform mat4 u_model_view;
uniform mat4 u_projection;
uniform float u_depth_offset;

void main() {
    gl_Position = u_projection * u_model_view * vec4(a_position, 1.0);
    gl_Position.z = -gl_Position.w;
}
