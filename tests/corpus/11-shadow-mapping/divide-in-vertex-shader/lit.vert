#version 330 core
// Reference solution, lab 11 (shadow mapping), passes "basic" and "pcf": the scene from the
// camera, with the world-space position and normal the lighting and the shadow lookup need.

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;

uniform mat4 u_model;
uniform mat4 u_view_projection;
uniform mat3 u_normal_matrix;  // transpose(inverse(mat3(u_model)))
uniform mat4 u_light_matrix;   // world -> the light's clip space

out vec3 v_world_position;
out vec3 v_world_normal;
out vec3 v_light_ndc;  // the vertex in the light's NDC, divided here: cheaper than per fragment

void main() {
    vec4 world = u_model * vec4(a_position, 1.0);
    v_world_position = world.xyz;
    v_world_normal = u_normal_matrix * a_normal;
    vec4 lc = u_light_matrix * world;
    v_light_ndc = lc.xyz / lc.w;
    gl_Position = u_view_projection * world;
}
