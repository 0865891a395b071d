#version 330 core
// Reference solution, 07-environment-mapping: world-space position and normal, because the cube
// maps are indexed by world-space directions.

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;

uniform mat4 u_model;
uniform mat4 u_view_projection;

out vec3 v_world_position;
out vec3 v_world_normal;

// normals go to world space with the model matrix, like the positions (no translation)
vec3 worldNormal(vec3 normal) { return mat3(u_model) * normal; }

void main() {
    vec4 world = u_model * vec4(a_position, 1.0);
    v_world_position = world.xyz;
    v_world_normal = worldNormal(a_normal);
    gl_Position = u_view_projection * world;
}
