#version 330 core
// Lab 11 (shadow mapping), passes "basic" and "pcf": the scene from the camera, with the
// world-space position and normal the lighting and the shadow lookup need. This file is done;
// it is yours to change if you would rather do part of the light-space projection here (for
// example pass u_light_matrix * world on as a vec4 varying, which shadow_coord then reads). It is
// graded with shadow_coord, as part of the projection.

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;

uniform mat4 u_model;
uniform mat4 u_view_projection;
uniform mat3 u_normal_matrix;  // transpose(inverse(mat3(u_model)))

out vec3 v_world_position;
out vec3 v_world_normal;

void main() {
    vec4 world = u_model * vec4(a_position, 1.0);
    v_world_position = world.xyz;
    v_world_normal = u_normal_matrix * a_normal;
    gl_Position = u_view_projection * world;
}
