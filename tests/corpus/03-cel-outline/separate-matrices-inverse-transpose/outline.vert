#version 330 core
// 03-cel-outline, task 1, vertex stage of the inverted hull.
//
// The "hull" pass draws the object a second time, into the image the "cel" pass just drew, with
// FRONT faces culled (lab.json). If every vertex is pushed out along its normal, the back faces
// of this slightly larger shell peek out around the object: that rim is the outline. Read
// labs/03-cel-outline/README.md first: it explains why the push is done in clip space and why
// it is multiplied by w. The two functions and main are graded each on its own: keep the
// functions' names and parameters (README, "How it is graded").

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;

uniform mat4 u_model_view_projection;
uniform mat4 u_model_view;
uniform mat4 u_view;
uniform mat4 u_projection;
uniform mat3 u_normal_matrix;  // transpose(inverse(mat3(u_model))): object normals to world space
uniform vec2 u_resolution;     // target size in pixels

uniform float u_outline_width;  // the outline's width in PIXELS (4 in most scenes; some set others)

// The normal in view space.
vec3 viewNormal(vec3 normal) {
    // The inverse transpose of the whole object-to-view matrix, computed here.
    mat3 normal_to_view = transpose(inverse(mat3(u_model_view)));
    return normal_to_view * normal;
}

// The normal's direction on the screen: a unit vector measured in pixels, or (0, 0) where the
// normal points straight at (or away from) the eye.
vec2 screenDirection(vec3 n_view) {
    // Screen-space direction, in pixels, of the normal.
    vec4 n_clip = u_projection * vec4(n_view, 0.0);
    vec2 n_pixels = n_clip.xy * 0.5 * u_resolution;
    float len = length(n_pixels);
    if (len > 1e-6) {
        return n_pixels / len;
    }
    return vec2(0.0);
}

void main() {
    vec4 p_view = u_model_view * vec4(a_position, 1.0);
    vec4 clip = u_projection * p_view;

    vec2 offset_pixels = screenDirection(viewNormal(a_normal)) * u_outline_width;
    vec2 offset_ndc = offset_pixels / (0.5 * u_resolution);
    clip.xy += offset_ndc * clip.w;

    gl_Position = clip;
}
