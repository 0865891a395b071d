#version 330 core
// 09-procedural-antialiasing, vertex stage (provided, not graded). It passes the texture
// coordinates on: the patterns live in texture space, so the fragment stage can ask how fast
// they change from one pixel to the next. World position and normal serve the simple lighting.

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_texcoord;

uniform mat4 u_model;
uniform mat4 u_view;
uniform mat4 u_projection;
uniform mat3 u_normal_matrix;

out vec3 v_world_position;
out vec3 v_world_normal;
out vec2 v_texcoord;

void main() {
    vec4 world = u_model * vec4(a_position, 1.0);
    v_world_position = world.xyz;
    v_world_normal = u_normal_matrix * a_normal;
    v_texcoord = a_texcoord;
    gl_Position = u_projection * u_view * world;
}
