#version 330 core
// 04-render-to-texture, passes "uv_check" and "mesh": the vertex stage of the textured mesh.
// It places the vertex on screen and hands the fragment stage what it needs: the world-space
// position and normal (for the lighting, already done) and the vertex's texture coordinate.
// Its main is graded with tiledCoord in mesh.frag, as the texture-coordinate goal's work.

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_texcoord;  // glTF TEXCOORD_0: where this vertex sits on the texture

uniform mat4 u_model;
uniform mat4 u_view_projection;
uniform mat3 u_normal_matrix;

out vec3 v_world_position;
out vec3 v_world_normal;
out vec2 v_texcoord;

void main() {
    vec4 world = u_model * vec4(a_position, 1.0);
    v_world_position = world.xyz;
    v_world_normal = u_normal_matrix * a_normal;

    // TODO(student): the texture coordinate of this vertex. The mesh was modelled with one: use
    // it. (Not the position, and not anything on the screen.)
    v_texcoord = vec2(0.0);

    gl_Position = u_view_projection * world;
}
