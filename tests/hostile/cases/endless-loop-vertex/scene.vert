#version 330 core
// A vertex stage that never finishes.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
uniform mat4 u_model;
uniform mat4 u_view;
uniform mat4 u_projection;
uniform mat3 u_normal_matrix;
out vec3 v_world_normal;
void main() {
    float s = 1.0;
    for (int i = 0; i != -1; i = (i + 1) % 1000) s = s * 0.5 + 0.5;
    v_world_normal = u_normal_matrix * a_normal * s;
    gl_Position = u_projection * u_view * u_model * vec4(a_position, 1.0);
}
