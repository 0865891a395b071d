#version 330 core
// Lab 10 (particles), pass "box" (given, not graded): the twelve edges of the box [0, 1]^3 the
// particles live in, as 24 line vertices computed from gl_VertexID (no mesh).

uniform mat4 u_view_projection;

void main() {
    // Edge e (0..11) runs along axis e / 4; the other two coordinates are the bits of e % 4.
    int edge = gl_VertexID / 2;
    int axis = edge / 4;
    int corner = edge % 4;
    vec3 p = vec3(0.0);
    p[axis] = float(gl_VertexID % 2);
    p[(axis + 1) % 3] = float(corner % 2);
    p[(axis + 2) % 3] = float(corner / 2);
    gl_Position = u_view_projection * vec4(p, 1.0);
}
