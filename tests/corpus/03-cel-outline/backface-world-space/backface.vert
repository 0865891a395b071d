#version 330 core
// Back-face lines, the offset done in world space: step from the vertex toward the camera
// position. The step lies on the ray from the eye through the vertex, so the vertex stays on
// its pixel and only its depth changes.

layout(location = 0) in vec3 a_position;

uniform mat4 u_model;
uniform mat4 u_view_projection;
uniform vec3 u_camera_position;
uniform float u_depth_offset;

void main() {
    vec3 world = (u_model * vec4(a_position, 1.0)).xyz;
    vec3 to_eye = normalize(u_camera_position - world);
    gl_Position = u_view_projection * vec4(world + to_eye * u_depth_offset, 1.0);
}
