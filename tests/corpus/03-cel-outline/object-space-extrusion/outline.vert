#version 330 core
// Inverted hull, the classic way: push the vertex along its normal in object space, before
// any transformation. The width is in pixels; one pixel at the object's distance d is
// 2 d / (P[1][1] * height) world units.

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;

uniform mat4 u_model_view_projection;
uniform mat4 u_model_view;
uniform mat4 u_projection;
uniform vec2 u_resolution;
uniform float u_outline_width;

void main() {
    float d = -u_model_view[3].z;
    float pixel_size = 2.0 * d / (u_projection[1][1] * u_resolution.y);

    vec3 p = a_position + normalize(a_normal) * u_outline_width * pixel_size;
    gl_Position = u_model_view_projection * vec4(p, 1.0);
}
