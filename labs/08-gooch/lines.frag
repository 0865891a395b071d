#version 330 core
// 08-gooch, pass 2: draw dark lines over the Gooch image where the G-buffer of pass 1 is
// discontinuous. A fullscreen pass: this runs once for every pixel of the picture, and v_uv is
// where that pixel is in the textures of pass 1 (0..1 across the screen).
//   silhouettes: the distance to the surface jumps between neighbouring pixels (u_depth)
//   creases:     the surface normal turns sharply between neighbouring pixels (u_normal)
// Read labs/08-gooch/README.md first. The functions are graded on their own: keep their names and
// parameters (README, "How it is graded").
// (Reading texels with texelFetch at ivec2(gl_FragCoord.xy) + offset instead of uv offsets? Then
// clamp every address to 0..textureSize(u_depth, 0) - 1: texelFetch outside the texture returns
// undefined values. If v_uv then ends up unused, delete its declaration.)
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
    // TODO(student): this is the raw depth-buffer value, not a distance: the projection squeezed
    // it (most of 0..1 is spent close to the near plane). Undo the projection with u_projection.
    return texture(u_depth, uv).r;
}

// The unit normal pass 1 wrote at uv.
vec3 normal_at(vec2 uv) {
    // TODO(student): decode what gooch.frag encoded into o_normal.
    return texture(u_normal, uv).xyz;
}

// True when the view distance jumps between uv and one of its four neighbours (left, right,
// up, down; one texel away) by more than u_depth_threshold times the nearer of the two distances.
bool is_silhouette(vec2 uv, vec2 texel) {
    // TODO(student)
    return false;
}

// True when uv is covered and the normal of one of its four covered neighbours makes a dot
// product below u_crease_threshold with the normal at uv. Skip neighbours that are background:
// an object against the background is the silhouette test's business.
bool is_crease(vec2 uv, vec2 texel) {
    // TODO(student)
    return false;
}

void main() {
    // TODO(student): the size of one texel in uv units, so that uv + vec2(texel.x, 0.0) is the
    // centre of the next pixel to the right.
    vec2 texel = vec2(0.0);

    bool line = (u_silhouettes && is_silhouette(v_uv, texel)) || (u_creases && is_crease(v_uv, texel));
    vec3 color = texture(u_color, v_uv).rgb;
    o_color = vec4(line ? u_line_color : color, 1.0);
}
