#version 330 core
// 01-phong, vertex stage: world-space position and normal for per-fragment lighting.

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;

uniform mat4 u_model;
uniform mat4 u_view;
uniform mat4 u_projection;

out vec3 v_world_position;
out vec3 v_world_normal;

void main() {
    vec4 world = u_model * vec4(a_position, 1.0);
    v_world_position = world.xyz;
    // The normal as the mesh gives it.
    v_world_normal = a_normal;
    gl_Position = u_projection * u_view * world;
}
