#version 330 core
// Back-face lines: the camera looks down -z in view space, so toward the camera is +z.

layout(location = 0) in vec3 a_position;

uniform mat4 u_model_view;
uniform mat4 u_projection;
uniform float u_depth_offset;

void main() {
    vec4 p_view = u_model_view * vec4(a_position, 1.0);
    p_view.z += u_depth_offset;
    gl_Position = u_projection * p_view;
}
