#version 330 core
// 02-toon, vertex stage of both passes (given; not part of your submission): world-space position
// and normal for per-fragment lighting, exactly as in 01-phong.

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;

uniform mat4 u_model;
uniform mat4 u_view;
uniform mat4 u_projection;
uniform mat3 u_normal_matrix;  // transpose(inverse(mat3(u_model))): keeps normals perpendicular

out vec3 v_world_position;
out vec3 v_world_normal;  // interpolated, so no longer unit length in the fragment stage

void main() {
    vec4 world = u_model * vec4(a_position, 1.0);
    v_world_position = world.xyz;
    v_world_normal = u_normal_matrix * a_normal;
    gl_Position = u_projection * u_view * world;
}
