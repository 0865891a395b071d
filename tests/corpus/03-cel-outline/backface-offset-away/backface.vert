#version 330 core
// Back-face lines: move each vertex along its view ray by u_depth_offset so the lines
// and the front faces do not fight over the same depth.

layout(location = 0) in vec3 a_position;

uniform mat4 u_model_view;
uniform mat4 u_projection;
uniform float u_depth_offset;

void main() {
    vec4 p_view = u_model_view * vec4(a_position, 1.0);
    // along the view ray
    p_view.xyz += normalize(p_view.xyz) * u_depth_offset;
    gl_Position = u_projection * p_view;
}
