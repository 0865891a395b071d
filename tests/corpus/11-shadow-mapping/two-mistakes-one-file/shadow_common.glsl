// Reference solution, lab 11 (shadow mapping): what both lit passes need to look a point up in
// the shadow map (Williams, "Casting Curved Shadows on Curved Surfaces", SIGGRAPH 1978).

uniform mat4 u_light_matrix;  // the shadow pass's view-projection: world -> the light's clip space

// Where the world-space point p lands in the shadow map: xy are its texture coordinates and z its
// depth as the light's depth buffer stores it, all three in 0..1 inside the light's view.
vec3 shadow_coord(vec3 p) {
    vec4 clip = u_light_matrix * vec4(p, 1.0);
    vec3 ndc = clip.xyz / clip.w;  // the perspective divide (w = 1 for a directional light's ortho view)
    return ndc * 0.5 + 0.5;        // NDC -1..1 -> texture coordinates and window depth 0..1
}

// Outside the light's view the map knows nothing: treat such points as lit.
bool outside_shadow_map(vec3 coord) {
    // outside when the point is off the map in every coordinate
    return all(lessThan(coord, vec3(0.0))) || all(greaterThan(coord, vec3(1.0)));
}

// A constant bias, generous so that no acne is left anywhere.
float shadow_bias(vec3 n, vec3 l) {
    return 0.02;
}
