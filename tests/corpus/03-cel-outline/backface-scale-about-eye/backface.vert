#version 330 core
// Back-face lines: scale the view-space position about the eye (the origin) so that the vertex
// comes u_depth_offset closer. Scaling about the eye keeps it on its view ray.

layout(location = 0) in vec3 a_position;

uniform mat4 u_model_view;
uniform mat4 u_projection;
uniform float u_depth_offset;

void main() {
    vec4 p_view = u_model_view * vec4(a_position, 1.0);
    float distance_to_eye = length(p_view.xyz);
    p_view.xyz *= (distance_to_eye - u_depth_offset) / distance_to_eye;
    gl_Position = u_projection * p_view;
}
