#version 330 core
// Lab 11 (shadow mapping), pass "shadow": what the light sees is its depth buffer (shadow.depth),
// which the lit passes sample. The colour written here is only a picture of that depth for you to
// look at (render with --all-passes); nothing reads it. This file is the course's, not a student
// file.
//
// Some scenes push the stored depth back as glPolygonOffset does (OpenGL 4.5 core specification,
// section 14.6, "Depth Offset"): offset = factor * m + units, with m the depth slope of the
// triangle, max(|dz/dx|, |dz/dy|) in the map's pixels. With the map itself biased, those scenes
// show no acne even without your bias, so they grade the projection and the filtering alone;
// the bias scenes set both numbers to 0, and there your bias alone decides.

uniform float u_offset_factor;  // times the depth slope
uniform float u_offset_units;   // in depth units (0..1)

out vec4 o_color;

void main() {
    float z = gl_FragCoord.z;
    float slope = max(abs(dFdx(z)), abs(dFdy(z)));
    gl_FragDepth = z + u_offset_factor * slope + u_offset_units;
    o_color = vec4(vec3(z), 1.0);
}
