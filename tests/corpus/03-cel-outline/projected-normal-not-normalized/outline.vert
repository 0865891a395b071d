#version 330 core
// Inverted hull in clip space. The normal is a unit vector, so after projecting it I can use it
// as the direction directly.

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;

uniform mat4 u_model_view_projection;
uniform mat4 u_view;
uniform mat4 u_projection;
uniform mat3 u_normal_matrix;
uniform vec2 u_resolution;
uniform float u_outline_width;

void main() {
    vec4 clip = u_model_view_projection * vec4(a_position, 1.0);

    vec3 n_view = normalize(mat3(u_view) * u_normal_matrix * a_normal);
    vec2 dir = (u_projection * vec4(n_view, 0.0)).xy;

    clip.xy += dir * (2.0 * u_outline_width / u_resolution) * clip.w;
    gl_Position = clip;
}
