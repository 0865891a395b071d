#version 330 core
// The debug view's vertex stage (framework/render/src/debug_view.cpp): each vertex's normal,
// tangent and bitangent in world space, its handedness and its texture coordinates, passed on
// for the fragment stage to show as colours. Written by the framework, never by a student.
in vec3 a_position;
in vec3 a_normal;
in vec2 a_texcoord;
in vec4 a_tangent;

uniform mat4 u_model;
uniform mat3 u_normal_matrix;  // transpose(inverse(mat3(u_model)))
uniform mat4 u_view_projection;

out vec3 v_normal;
out vec3 v_tangent;
out vec3 v_bitangent;
out float v_handedness;
out vec2 v_texcoord;

void main() {
    v_normal = u_normal_matrix * a_normal;
    // Tangent and bitangent lie along the surface, so they move with it (the model matrix); the
    // bitangent is made in the mesh's own space, as glTF 2.0 defines it (3.7.2.1), then moved.
    v_tangent = mat3(u_model) * a_tangent.xyz;
    v_bitangent = mat3(u_model) * (cross(a_normal, a_tangent.xyz) * a_tangent.w);
    v_handedness = a_tangent.w;
    v_texcoord = a_texcoord;
    gl_Position = u_view_projection * (u_model * vec4(a_position, 1.0));
}
