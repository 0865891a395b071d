#version 330 core
// 01-phong, vertex stage: position and normal in VIEW (eye) space, where the camera sits at
// the origin looking down -z.

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;

uniform mat4 u_model_view;
uniform mat4 u_projection;

out vec3 v_view_position;
out vec3 v_view_normal;

void main() {
    vec4 eye = u_model_view * vec4(a_position, 1.0);
    v_view_position = eye.xyz;
    // Normals need the inverse transpose of the model-view matrix's upper 3x3.
    v_view_normal = transpose(inverse(mat3(u_model_view))) * a_normal;
    gl_Position = u_projection * eye;
}
