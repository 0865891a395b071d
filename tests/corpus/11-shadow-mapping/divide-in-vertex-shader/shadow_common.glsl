// Reference solution, lab 11 (shadow mapping): what both lit passes need to look a point up in
// the shadow map (Williams, "Casting Curved Shadows on Curved Surfaces", SIGGRAPH 1978).

uniform mat4 u_light_matrix;  // the shadow pass's view-projection: world -> the light's clip space

in vec3 v_light_ndc;  // from lit.vert: the point in the light's NDC

// Where the world-space point p lands in the shadow map: xy are its texture coordinates and z its
// depth as the light's depth buffer stores it, all three in 0..1 inside the light's view.
// lit.vert already took the point to the light's NDC (v_light_ndc), divided by w once per vertex
// instead of once per fragment: only the remap to 0..1 is left, and p is not needed.
vec3 shadow_coord(vec3 p) {
    return v_light_ndc * 0.5 + 0.5;
}

// Outside the light's view the map knows nothing: treat such points as lit.
bool outside_shadow_map(vec3 coord) {
    return any(lessThan(coord, vec3(0.0))) || any(greaterThan(coord, vec3(1.0)));
}

// Slope-scaled depth bias (the slope term of glPolygonOffset; OpenGL 4.5 core specification,
// section 14.6, "Depth Offset"): a surface at an angle theta to the light changes depth by
// tan(theta) times a texel's width across one texel of the map, about 0.00067 tan(theta) in depth
// units here. PCF compares against texels up to 1.5 texels away, so 0.002 tan(theta) (three
// texels' worth), clamped so that a grazing angle does not get an enormous bias.
float shadow_bias(vec3 n, vec3 l) {
    float cos_theta = clamp(dot(n, l), 0.05, 1.0);
    float tan_theta = sqrt(1.0 - cos_theta * cos_theta) / cos_theta;
    return clamp(0.002 * tan_theta, 0.0002, 0.01);
}
