#version 330 core
// Inverted hull in view space: push the vertex sideways (x and y only, so its depth stays that
// of the surface) along the normal's direction on the screen. u_outline_width is a small
// number, so take it in hundredths of a world unit: 4 gives 0.04, about 4 pixels at the usual
// distance.

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;

uniform mat4 u_model_view;
uniform mat4 u_view;
uniform mat4 u_projection;
uniform mat3 u_normal_matrix;
uniform float u_outline_width;

void main() {
    vec4 p_view = u_model_view * vec4(a_position, 1.0);
    vec3 n_view = normalize(mat3(u_view) * u_normal_matrix * a_normal);

    vec2 dir = length(n_view.xy) > 1e-6 ? normalize(n_view.xy) : vec2(0.0);
    p_view.xy += dir * u_outline_width * 0.01;
    gl_Position = u_projection * p_view;
}
