#version 330 core
// Inverted hull in clip space, with the normal matrix of the model-view transform computed here
// (the inverse transpose of its upper 3x3) and the projection applied separately.

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;

uniform mat4 u_model_view;
uniform mat4 u_projection;
uniform vec2 u_resolution;
uniform float u_outline_width;

void main() {
    vec4 p_view = u_model_view * vec4(a_position, 1.0);
    vec4 clip = u_projection * p_view;

    mat3 normal_to_view = transpose(inverse(mat3(u_model_view)));
    vec3 n_view = normal_to_view * a_normal;

    // Screen-space direction, in pixels, of the normal.
    vec4 n_clip = u_projection * vec4(n_view, 0.0);
    vec2 n_pixels = n_clip.xy * 0.5 * u_resolution;
    float len = length(n_pixels);
    if (len > 1e-6) {
        vec2 offset_pixels = n_pixels / len * u_outline_width;
        vec2 offset_ndc = offset_pixels / (0.5 * u_resolution);
        clip.xy += offset_ndc * clip.w;
    }
    gl_Position = clip;
}
