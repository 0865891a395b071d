#version 330 core
// 12-normal-mapping, vertex stage: a file you hand in (with normal_map.frag).
//
// Task 2 starts here: give the fragment stage the surface's normal and tangent in world space.
// The glTF file stores them in object space, per vertex: a_normal, and a_tangent, whose xyz points
// along +u (the direction the texture's x runs on the surface) and whose w is +1 or -1 (the
// handedness: -1 where the texture is mirrored). Read README.md, "The frame", first.
// world_normal and world_tangent are graded on their own: keep their names and parameters.
//
// Look for TODO(student). Position, texture coordinates and main() are provided.

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_texcoord;
in vec4 a_tangent;  // xyz: unit tangent along +u, object space; w: +1 or -1

uniform mat4 u_model;          // object to world
uniform mat4 u_view;           // world to eye
uniform mat4 u_projection;     // eye to clip
uniform mat3 u_normal_matrix;  // transpose(inverse(mat3(u_model))), provided by the framework

out vec3 v_world_position;
out vec3 v_world_normal;   // unit normal, world space
out vec4 v_world_tangent;  // xyz: unit tangent, world space; w: the handedness, passed on as it is
out vec2 v_texcoord;

// The unit normal in world space. A normal stays perpendicular to the surface with the inverse
// transpose of the model matrix.
vec3 world_normal(vec3 normal) {
    return normalize(u_normal_matrix * normal);
}

// The unit tangent in world space. A tangent lies in the surface, like an edge of a triangle, and
// moves with the model matrix itself.
vec3 world_tangent(vec3 tangent) {
    return normalize(mat3(u_model) * tangent);
}

void main() {
    vec4 world = u_model * vec4(a_position, 1.0);
    v_world_position = world.xyz;
    v_texcoord = a_texcoord;
    v_world_normal = world_normal(a_normal);
    v_world_tangent = vec4(world_tangent(a_tangent.xyz), a_tangent.w);  // w passed on as it is
    gl_Position = u_projection * u_view * world;
}
