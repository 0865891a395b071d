#version 330 core
// Reference solution, 04-render-to-texture, passes "uv_check" and "mesh": the vertex stage hands
// the mesh's own texture coordinates (glTF TEXCOORD_0) to the fragment stage unchanged, with the
// world-space position and normal for the lighting.

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_texcoord;

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
    // The texture coordinate belongs to the vertex, like its position: the rasteriser
    // interpolates it (perspective-correctly) across each triangle.
    v_texcoord = a_texcoord;
    gl_Position = u_view_projection * world;
}
