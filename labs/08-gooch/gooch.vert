#version 330 core
// 08-gooch, pass 1 (vertex stage): world-space position and normal for per-fragment shading.
// Nothing here is new: it is the vertex stage of lab 01. It is done, but it is one of your files:
// it is graded with your submission, and you may change it (to shade in eye space, say).

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;

uniform mat4 u_model;
uniform mat4 u_view;
uniform mat4 u_projection;
uniform mat3 u_normal_matrix;  // transpose(inverse(mat3(u_model))): keeps normals perpendicular

out vec3 v_world_position;
out vec3 v_world_normal;

void main() {
    vec4 world = u_model * vec4(a_position, 1.0);
    v_world_position = world.xyz;
    v_world_normal = u_normal_matrix * a_normal;
    gl_Position = u_projection * u_view * world;
}
