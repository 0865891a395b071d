#version 330 core
// 01-phong, vertex stage. The normal matrix is computed here rather than taken from
// u_normal_matrix: the inverse transpose of the model matrix's linear part.

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;

uniform mat4 u_model;
uniform mat4 u_view_projection;

out vec3 v_world_position;
out vec3 v_world_normal;

void main() {
    vec4 world = u_model * vec4(a_position, 1.0);
    v_world_position = world.xyz;
    mat3 normal_matrix = transpose(inverse(mat3(u_model)));
    v_world_normal = normal_matrix * a_normal;
    gl_Position = u_view_projection * world;
}
