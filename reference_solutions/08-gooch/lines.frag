#version 330 core
// Reference solution, 08-gooch, pass 2: dark lines from the G-buffer of pass 1.
//   silhouette: the view distance jumps between neighbouring pixels by more than a fraction of
//               the nearer distance (a depth discontinuity);
//   crease:     the normals of two neighbouring covered pixels meet at a sharp angle
//               (dot(n_a, n_b) below a threshold: a normal discontinuity).
// T. Saito, T. Takahashi, "Comprehensible Rendering of 3-D Shapes", SIGGRAPH 1990 (G-buffers,
// edges from depth and normal discontinuities); A. Gooch et al., SIGGRAPH 1998 (lines in black).
// (u_k_blue, u_k_yellow, u_alpha, u_beta and u_specular in lab.json belong to pass 1, gooch.frag.)

in vec2 v_uv;

uniform sampler2D u_color;   // gooch.color
uniform sampler2D u_normal;  // gooch.normal: world-space normal encoded as n * 0.5 + 0.5
uniform sampler2D u_depth;   // gooch.depth: the raw depth buffer value, 0..1 (1 = background)

uniform mat4 u_projection;  // the camera that drew pass 1 (this pass has no camera of its own)
uniform vec2 u_resolution;  // this target's size in pixels, the same as pass 1's

uniform float u_depth_threshold;   // a jump larger than this fraction of the distance is a silhouette
uniform float u_crease_threshold;  // normals whose dot product is below this meet at a crease
uniform vec3 u_line_color;
uniform bool u_silhouettes;  // the lab switches each kind of line on or off per scene
uniform bool u_creases;

out vec4 o_color;

const vec2 NEIGHBOURS[4] = vec2[4](vec2(1.0, 0.0), vec2(-1.0, 0.0), vec2(0.0, 1.0), vec2(0.0, -1.0));

bool covered(vec2 uv) {
    return texture(u_depth, uv).r < 1.0;
}

// Undo the perspective divide: the depth buffer holds z_ndc * 0.5 + 0.5, and for a perspective
// projection z_ndc = -P[2][2] - P[3][2] / z_eye, so the distance along the view axis is
// -z_eye = P[3][2] / (z_ndc + P[2][2]).
float view_distance(vec2 uv) {
    float z_ndc = texture(u_depth, uv).r * 2.0 - 1.0;
    return u_projection[3][2] / (z_ndc + u_projection[2][2]);
}

vec3 normal_at(vec2 uv) {
    return normalize(texture(u_normal, uv).xyz * 2.0 - 1.0);
}

bool is_silhouette(vec2 uv, vec2 texel) {
    float here = view_distance(uv);
    for (int i = 0; i < 4; ++i) {
        float there = view_distance(uv + NEIGHBOURS[i] * texel);
        if (abs(there - here) > u_depth_threshold * min(here, there)) return true;
    }
    return false;
}

bool is_crease(vec2 uv, vec2 texel) {
    if (!covered(uv)) return false;
    vec3 here = normal_at(uv);
    for (int i = 0; i < 4; ++i) {
        vec2 q = uv + NEIGHBOURS[i] * texel;
        if (!covered(q)) continue;  // object against background: the silhouette test's business
        if (dot(here, normal_at(q)) < u_crease_threshold) return true;
    }
    return false;
}

void main() {
    vec2 texel = 1.0 / u_resolution;
    bool line = (u_silhouettes && is_silhouette(v_uv, texel)) || (u_creases && is_crease(v_uv, texel));
    vec3 color = texture(u_color, v_uv).rgb;
    o_color = vec4(line ? u_line_color : color, 1.0);
}
