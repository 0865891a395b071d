#version 330 core
// Outline: make the object a little bigger and draw its back faces in black behind it.
// "Bigger" = push every vertex away from the centre of the object.

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;

uniform mat4 u_model_view_projection;
uniform vec2 u_resolution;
uniform float u_outline_width;

void main() {
    vec4 clip = u_model_view_projection * vec4(a_position, 1.0);

    // Direction away from the object's centre, on the screen: where the vertex is, minus where
    // the centre is.
    vec4 centre = u_model_view_projection * vec4(0.0, 0.0, 0.0, 1.0);
    vec2 away = clip.xy / clip.w - centre.xy / centre.w;
    vec2 dir = length(away) > 0.0 ? normalize(away * u_resolution) : vec2(0.0);

    clip.xy += dir * (2.0 * u_outline_width / u_resolution) * clip.w;
    gl_Position = clip;
}
