#version 330 core
// 08-gooch, pass 2: draw dark lines over the Gooch image where the G-buffer of pass 1 is
// discontinuous. A fullscreen pass: this runs once for every pixel of the picture, and v_uv is
// where that pixel is in the textures of pass 1 (0..1 across the screen).
//   silhouettes: the distance to the surface jumps between neighbouring pixels (u_depth)
//   creases:     the surface normal turns sharply between neighbouring pixels (u_normal)
// Read labs/08-gooch/README.md first. The functions are graded on their own: keep their names and
// parameters (README, "How it is graded").
// (u_k_blue, u_k_yellow, u_alpha, u_beta and u_specular in lab.json belong to pass 1, gooch.frag.)

in vec2 v_uv;

uniform sampler2D u_color;   // gooch.color: the tone image of pass 1
uniform sampler2D u_normal;  // gooch.normal: what gooch.frag wrote to o_normal
uniform sampler2D u_depth;   // gooch.depth: the depth buffer of pass 1, 0..1 in .r (1 = background)

uniform mat4 u_projection;  // the projection that drew pass 1 (this pass uses the same camera)
uniform vec2 u_resolution;  // the size of this target (and of pass 1's) in pixels

uniform float u_depth_threshold;   // a silhouette: the distance jumps by more than this FRACTION of itself
uniform float u_crease_threshold;  // a crease: two normals whose dot product is below this
uniform vec3 u_line_color;
uniform bool u_silhouettes;  // the lab switches each kind of line on or off per scene
uniform bool u_creases;

out vec4 o_color;

// True where pass 1 drew geometry: the background keeps the cleared depth, 1.
bool covered(vec2 uv) {
    return texture(u_depth, uv).r < 1.0;
}

// The distance from the eye along the view axis to the surface seen at uv.
float view_distance(vec2 uv) {
    // depth = z_ndc / 2 + 1/2 and z_ndc = (P22 z + P32) / -z, solved for -z
    float z_ndc = 2.0 * texture(u_depth, uv).r - 1.0;
    return u_projection[3][2] / (z_ndc + u_projection[2][2]);
}

// The unit normal pass 1 wrote at uv.
vec3 normal_at(vec2 uv) {
    return normalize(texture(u_normal, uv).xyz * 2.0 - 1.0);
}

// True when the view distance jumps between uv and one of its four neighbours (left, right,
// up, down; one texel away) by more than u_depth_threshold times the nearer of the two distances.
bool is_silhouette(vec2 uv, vec2 texel) {
    float d = view_distance(uv);
    float right = view_distance(uv + vec2(texel.x, 0.0));
    float left = view_distance(uv - vec2(texel.x, 0.0));
    float up = view_distance(uv + vec2(0.0, texel.y));
    float down = view_distance(uv - vec2(0.0, texel.y));
    // a jump of more than u_depth_threshold times the distance here to any neighbour
    float jump = u_depth_threshold * d;
    return abs(right - d) > jump || abs(left - d) > jump || abs(up - d) > jump || abs(down - d) > jump;
}

bool crease_with(vec3 n, vec2 other) {
    return covered(other) && dot(n, normal_at(other)) < u_crease_threshold;
}

// True when uv is covered and the normal of one of its four covered neighbours makes a dot
// product below u_crease_threshold with the normal at uv. Skip neighbours that are background:
// an object against the background is the silhouette test's business.
bool is_crease(vec2 uv, vec2 texel) {
    if (!covered(uv)) return false;
    vec3 n = normal_at(uv);
    return crease_with(n, uv + vec2(texel.x, 0.0)) || crease_with(n, uv - vec2(texel.x, 0.0)) ||
           crease_with(n, uv + vec2(0.0, texel.y)) || crease_with(n, uv - vec2(0.0, texel.y));
}

void main() {
    vec2 texel = 1.0 / u_resolution;

    bool line = (u_silhouettes && is_silhouette(v_uv, texel)) || (u_creases && is_crease(v_uv, texel));
    vec3 color = texture(u_color, v_uv).rgb;
    o_color = vec4(line ? u_line_color : color, 1.0);
}
