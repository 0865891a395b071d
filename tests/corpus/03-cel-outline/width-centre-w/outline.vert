#version 330 core
// Inverted hull in clip space, u_outline_width pixels. The perspective divide shrinks the
// offset by w, so multiply by w first: the w of the object (its origin), computed once, since
// the whole object is at about that distance.

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
    float object_w = (u_model_view_projection * vec4(0.0, 0.0, 0.0, 1.0)).w;

    vec3 n_view = normalize(mat3(u_view) * u_normal_matrix * a_normal);
    vec2 n_pixels = (u_projection * vec4(n_view, 0.0)).xy * (0.5 * u_resolution);
    float len = length(n_pixels);
    vec2 dir = len > 1e-6 ? n_pixels / len : vec2(0.0);

    clip.xy += dir * (2.0 * u_outline_width / u_resolution) * object_w;
    gl_Position = clip;
}
