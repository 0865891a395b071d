#version 330 core
// 08-gooch, pass 1, vertex stage, in EYE space: the camera sits at the origin looking down -z,
// so the direction toward it is simply -position.

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;

uniform mat4 u_model_view;
uniform mat4 u_projection;
uniform mat4 u_view;
uniform mat3 u_normal_matrix;  // object to world, for normals

out vec3 v_eye_position;
out vec3 v_eye_normal;

void main() {
    vec4 eye = u_model_view * vec4(a_position, 1.0);
    v_eye_position = eye.xyz;
    // world-space normal, then rotated by the view (a rigid motion: no inverse transpose needed)
    v_eye_normal = mat3(u_view) * (u_normal_matrix * a_normal);
    gl_Position = u_projection * eye;
}
