// Lab 11 (shadow mapping): what both lit passes need to look a point up in the shadow map.
// shadow_basic.frag and shadow_pcf.frag both #include this file, so you write it once.
// Read labs/11-shadow-mapping/README.md first. Each function below is one idea of the lab and is
// graded on its own: keep their names and parameters (README, "How it is graded").

uniform mat4 u_light_matrix;  // the shadow pass's view-projection: world -> the light's clip space

// Where the world-space point p lands in the shadow map: xy are its texture coordinates and z its
// depth as the light's depth buffer stores it, all three in 0..1 inside the light's view.
vec3 shadow_coord(vec3 p) {
    // TODO(student): take p to the light's clip space with u_light_matrix (p is a point: w = 1).
    // TODO(student): divide by w (a point light's perspective view needs it; for a directional
    // light's orthographic view w is 1 and the divide changes nothing).
    // TODO(student): map normalised device coordinates (-1..1) to texture coordinates and depth
    // (0..1).
    // If you move part of this into lit.vert (a varying), read the varying here and keep the
    // function's name and parameter: the shadow passes call shadow_coord(p).
    return vec3(0.0);
}

// Outside the light's view the map knows nothing: treat such points as lit.
bool outside_shadow_map(vec3 coord) {
    // TODO(student): true when any of x, y, z is outside 0..1 (beside the light's view, behind the
    // light, beyond its far plane).
    return false;
}

// The bias subtracted from a point's depth before the comparison, so that a lit surface does not
// shadow itself (shadow acne). n: unit normal, l: unit vector toward the light.
float shadow_bias(vec3 n, vec3 l) {
    // TODO(student): big enough that no surface shadows itself, in both passes (PCF looks one texel
    // further away), small enough that shadows stay attached to what casts them. The README
    // works out the size of one texel in depth units; a slope-scaled bias grows with tan(theta).
    return 0.0;
}
