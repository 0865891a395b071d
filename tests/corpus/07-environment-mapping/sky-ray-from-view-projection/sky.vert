#version 330 core
// The sky on the far plane, with its view ray built per vertex from the view and projection
// matrices. The eye-space ray through a point (x, y) of the screen is (x / P[0][0], y / P[1][1], -1)
// for a symmetric perspective; it is linear in x and y, so interpolating it across the triangle
// is exact. The transpose of the view's rotation turns it into a world direction.

layout(location = 0) in vec3 a_position;

uniform mat4 u_view;
uniform mat4 u_projection;

out vec3 v_direction;

void main() {
    vec3 eye_ray = vec3(a_position.x / u_projection[0][0], a_position.y / u_projection[1][1], -1.0);
    v_direction = transpose(mat3(u_view)) * eye_ray;
    gl_Position = vec4(a_position.xy, 1.0, 1.0);  // z = w: depth 1, the far plane
}
