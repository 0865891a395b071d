#version 330 core
// Inverted hull: the hull pass draws BACK faces (front faces are culled), and a back face
// looks away from us, so its normal is the other way round: flip it before pushing.

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

    // back face -> reversed normal
    vec3 n_view = normalize(mat3(u_view) * u_normal_matrix * -a_normal);
    vec2 n_pixels = (u_projection * vec4(n_view, 0.0)).xy * u_resolution;
    vec2 dir = length(n_pixels) > 1e-6 ? normalize(n_pixels) : vec2(0.0);

    clip.xy += dir * (2.0 * u_outline_width / u_resolution) * clip.w;
    gl_Position = clip;
}
