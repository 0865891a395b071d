#version 330 core
// Inverted hull in clip space. The screen is u_resolution pixels across and NDC runs from -1
// to 1, so from the centre to the edge (1 NDC unit) is half the resolution: one pixel is
// 2 / (u_resolution / 2) NDC units. Times w, because the rasteriser divides by it.

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
    vec2 n_pixels = (u_projection * vec4(n_view, 0.0)).xy * (0.5 * u_resolution);
    float len = length(n_pixels);
    vec2 dir = len > 1e-6 ? n_pixels / len : vec2(0.0);

    vec2 pixel_in_ndc = 2.0 / (0.5 * u_resolution);
    clip.xy += dir * u_outline_width * pixel_in_ndc * clip.w;
    gl_Position = clip;
}
