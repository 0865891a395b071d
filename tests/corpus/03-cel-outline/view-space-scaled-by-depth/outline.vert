#version 330 core
// Inverted hull, extruded in VIEW space but by an amount that grows with the distance, so it
// comes out as the same number of pixels everywhere. With a symmetric perspective projection,
// x_ndc = P[0][0] x_view / (-z_view): moving x_view by dx moves the point by
// P[0][0] dx / (-z_view) NDC units, i.e. that times width/2 pixels. Solve for dx.

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;

uniform mat4 u_model_view;
uniform mat4 u_projection;
uniform mat4 u_view;
uniform mat3 u_normal_matrix;
uniform vec2 u_resolution;
uniform float u_outline_width;

void main() {
    vec4 p_view = u_model_view * vec4(a_position, 1.0);
    vec3 n_view = mat3(u_view) * u_normal_matrix * a_normal;

    // The normal's direction on the screen, in pixels.
    vec2 scale = vec2(u_projection[0][0], u_projection[1][1]) * 0.5 * u_resolution;
    vec2 n_pixels = n_view.xy * scale;
    if (dot(n_pixels, n_pixels) > 1e-12) {
        vec2 dir = normalize(n_pixels);
        // u_outline_width pixels back to view-space units at this vertex's depth. Only x and y
        // move, so the depth stays that of the surface.
        p_view.xy += dir * u_outline_width * (-p_view.z) / scale;
    }
    gl_Position = u_projection * p_view;
}
