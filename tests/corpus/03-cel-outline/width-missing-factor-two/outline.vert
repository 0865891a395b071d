#version 330 core
// Inverted hull in clip space: u_outline_width pixels, one pixel = 1 / resolution of the
// screen, times w because of the perspective divide.

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

    vec3 n_view = mat3(u_view) * u_normal_matrix * a_normal;
    vec2 n_pixels = (u_projection * vec4(n_view, 0.0)).xy * u_resolution;
    vec2 dir = length(n_pixels) > 1e-6 ? normalize(n_pixels) : vec2(0.0);

    clip.xy += dir * (u_outline_width / u_resolution) * clip.w;
    gl_Position = clip;
}
