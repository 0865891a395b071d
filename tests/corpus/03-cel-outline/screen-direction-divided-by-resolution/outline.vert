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
uniform mat4 u_view;
uniform mat4 u_projection;
uniform mat3 u_normal_matrix;  // transpose(inverse(mat3(u_model))): object normals to world space
uniform vec2 u_resolution;     // target size in pixels

uniform float u_outline_width;  // the outline's width in PIXELS (4 in most scenes; some set others)

// The normal in view space.
vec3 viewNormal(vec3 normal) {
    // The inverse transpose for the object's scale, then the view's rotation.
    return normalize(mat3(u_view) * u_normal_matrix * normal);
}

// The normal's direction on the screen: a unit vector measured in pixels, or (0, 0) where the
// normal points straight at (or away from) the eye.
vec2 screenDirection(vec3 n_view) {
    // The normal projected as a direction (w = 0), converted to pixels like the offset in main,
    // then normalised.
    vec2 n_pixels = (u_projection * vec4(n_view, 0.0)).xy / (0.5 * u_resolution);
    return dot(n_pixels, n_pixels) > 1e-12 ? normalize(n_pixels) : vec2(0.0);
}

void main() {
    vec4 clip = u_model_view_projection * vec4(a_position, 1.0);
    vec2 dir = screenDirection(viewNormal(a_normal));

    // One pixel is 2 / u_resolution in NDC, and clip.xy is divided by w afterwards.
    clip.xy += dir * u_outline_width * (2.0 / u_resolution) * clip.w;

    gl_Position = clip;
}
