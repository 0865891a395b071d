#version 330 core
// Inverted hull, pushed out in clip space by u_outline_width pixels (times w so the divide
// does not shrink it). The normal goes to view space with the model-view matrix, like the
// position does.

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;

uniform mat4 u_model_view;
uniform mat4 u_projection;
uniform vec2 u_resolution;
uniform float u_outline_width;

void main() {
    vec4 p_view = u_model_view * vec4(a_position, 1.0);
    vec4 clip = u_projection * p_view;

    vec3 n_view = normalize(mat3(u_model_view) * a_normal);
    vec2 n_pixels = (u_projection * vec4(n_view, 0.0)).xy * u_resolution;
    vec2 dir = length(n_pixels) > 1e-6 ? normalize(n_pixels) : vec2(0.0);

    clip.xy += dir * (2.0 * u_outline_width / u_resolution) * clip.w;
    gl_Position = clip;
}
