#version 330 core
// 01-phong, vertex stage. Known mistake: normals by the model matrix.

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;

uniform mat4 u_model;
uniform mat4 u_view;
uniform mat4 u_projection;
uniform mat3 u_normal_matrix;  // transpose(inverse(mat3(u_model)))

out vec3 v_world_position;
out vec3 v_world_normal;

vec3 worldNormal(vec3 normal) {
    // Normals transform with the inverse transpose so they stay perpendicular to the surface
    // under non-uniform scale.
    return mat3(u_model) * normal;
}

void main() {
    vec4 world = u_model * vec4(a_position, 1.0);
    v_world_position = world.xyz;
    v_world_normal = worldNormal(a_normal);
    gl_Position = u_projection * u_view * world;
}
