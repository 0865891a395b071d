#version 330 core
// Inverted hull: push every vertex out along its normal, on the screen, by u_outline_width
// pixels. Pixels -> NDC: 2 / resolution per pixel.

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
    vec2 n_screen = (u_projection * vec4(n_view, 0.0)).xy * u_resolution;
    vec2 dir = length(n_screen) > 1e-6 ? normalize(n_screen) : vec2(0.0);

    // width in NDC units
    clip.xy += dir * 2.0 * u_outline_width / u_resolution;
    gl_Position = clip;
}
