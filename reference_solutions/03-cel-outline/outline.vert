#version 330 core
// Reference solution, 03-cel-outline, task 1: the inverted hull. Every vertex is pushed out
// along its normal by u_outline_width PIXELS, measured on the screen: the offset is computed in
// clip space and multiplied by w, so that after the perspective divide it is the same number of
// pixels near and far. The shell is drawn with front faces culled, so only its back faces
// remain, and they show as a rim around the silhouette. (Silhouettes from back faces: Gooch,
// Sloan, Gooch, Shirley, Riesenfeld, "Interactive Technical Illustration", I3D 1999; Raskar,
// Cohen, "Image Precision Silhouette Edges", I3D 1999.)

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;

uniform mat4 u_model_view_projection;
uniform mat4 u_view;
uniform mat4 u_projection;
uniform mat3 u_normal_matrix;  // transpose(inverse(mat3(u_model))): object normals to world space
uniform vec2 u_resolution;     // target size in pixels

uniform float u_outline_width;  // pixels

// The normal in view space: the inverse transpose keeps it perpendicular to the surface under
// non-uniform scale; the view matrix is a rotation (and a translation, which mat3() drops), and
// normals follow a rotation like any direction.
vec3 viewNormal(vec3 normal) {
    return normalize(mat3(u_view) * (u_normal_matrix * normal));
}

// The normal's direction on the screen, a unit vector in pixels.
vec2 screenDirection(vec3 n_view) {
    // The projection applied to a direction (w = 0), x and y kept, then measured in pixels (NDC
    // spans 2 units over u_resolution pixels), so that a non-square target still gets round
    // offsets.
    vec2 n_pixels = (u_projection * vec4(n_view, 0.0)).xy * (0.5 * u_resolution);
    float len = length(n_pixels);
    vec2 dir = len > 1e-6 ? n_pixels / len : vec2(0.0);

    // A vertex whose normal points (nearly) straight at or away from the eye is far from the
    // silhouette: its direction on the screen is ill-defined and flips between neighbours, and a
    // full push would fold its triangles over (specks of ink on the surface). Fade the push out
    // over the last 15 degrees or so; silhouette normals are nearly perpendicular to the view
    // axis and get the full width.
    float fade = clamp(length(n_view.xy) / 0.25, 0.0, 1.0);
    return dir * fade;
}

void main() {
    vec4 clip = u_model_view_projection * vec4(a_position, 1.0);
    vec2 dir = screenDirection(viewNormal(a_normal));

    // u_outline_width pixels are 2 * width / resolution NDC units; times w because the
    // rasteriser will divide clip.xy by w.
    clip.xy += dir * (2.0 * u_outline_width / u_resolution) * clip.w;
    gl_Position = clip;
}
