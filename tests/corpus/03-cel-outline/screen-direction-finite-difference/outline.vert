#version 330 core
// Inverted hull with the screen direction found numerically: project the vertex and a point a
// tiny step along its normal, and see which way the second one landed on the screen. That is
// the exact direction of the normal on the screen (perspective included), then pushed out by
// u_outline_width pixels, times w.

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;

uniform mat4 u_model;
uniform mat4 u_view_projection;
uniform mat3 u_normal_matrix;
uniform vec2 u_resolution;
uniform float u_outline_width;

void main() {
    vec4 world = u_model * vec4(a_position, 1.0);
    vec3 n_world = normalize(u_normal_matrix * a_normal);

    vec4 clip = u_view_projection * world;
    vec4 clip_step = u_view_projection * vec4(world.xyz + 1e-3 * n_world, 1.0);

    vec2 screen = clip.xy / clip.w * 0.5 * u_resolution;
    vec2 screen_step = clip_step.xy / clip_step.w * 0.5 * u_resolution;
    vec2 d = screen_step - screen;

    if (length(d) > 1e-5) {
        clip.xy += normalize(d) * u_outline_width / (0.5 * u_resolution) * clip.w;
    }
    gl_Position = clip;
}
