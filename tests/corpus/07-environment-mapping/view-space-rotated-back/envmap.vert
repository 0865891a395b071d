#version 330 core
// Eye-space position and normal: the eye is at the origin there.

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;

uniform mat4 u_model_view;
uniform mat4 u_projection;
uniform mat4 u_view;
uniform mat3 u_normal_matrix;  // object to world, for normals

out vec3 v_view_position;
out vec3 v_view_normal;

vec3 worldNormal(vec3 normal) { return u_normal_matrix * normal; }

void main() {
    vec4 eye = u_model_view * vec4(a_position, 1.0);
    v_view_position = eye.xyz;
    // To world with the normal matrix, then into eye space with the view's rotation (the view is
    // a rigid motion, so its rotation part transforms normals too).
    v_view_normal = mat3(u_view) * worldNormal(a_normal);
    gl_Position = u_projection * eye;
}
