#version 330 core
// 01-phong, vertex stage. Lighting in view space: position and normal handed on in view space.

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;

uniform mat4 u_model_view;
uniform mat4 u_projection;

out vec3 v_view_position;
out vec3 v_view_normal;

// The normal in view space: the inverse transpose of the model-view matrix's upper 3x3.
vec3 worldNormal(vec3 normal) {
    return transpose(inverse(mat3(u_model_view))) * normal;
}

void main() {
    vec4 eye = u_model_view * vec4(a_position, 1.0);
    v_view_position = eye.xyz;
    v_view_normal = worldNormal(a_normal);
    gl_Position = u_projection * eye;
}
