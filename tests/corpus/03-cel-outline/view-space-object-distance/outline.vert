#version 330 core
// Inverted hull in view space: push the vertex along its view-space normal. u_outline_width is
// in pixels, so convert it to view-space units: at distance d one pixel is
// 2 d tan(fov/2) / height = 2 d / (P[1][1] * height). d is the object's distance from the eye.

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;

uniform mat4 u_model_view;
uniform mat4 u_projection;
uniform mat4 u_view;
uniform mat3 u_normal_matrix;
uniform vec2 u_resolution;
uniform float u_outline_width;

void main() {
    vec3 n_view = normalize(mat3(u_view) * u_normal_matrix * a_normal);

    // how far the object is from the camera (its origin, in view space)
    float d = -u_model_view[3].z;
    float pixel_size = 2.0 * d / (u_projection[1][1] * u_resolution.y);

    vec4 p_view = u_model_view * vec4(a_position, 1.0);
    p_view.xyz += n_view * u_outline_width * pixel_size;
    gl_Position = u_projection * p_view;
}
