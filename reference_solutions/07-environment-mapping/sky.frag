#version 330 core
// Reference solution, 07-environment-mapping: the sky seen through each pixel. The pixel's point
// on the far plane, taken back to world space by the inverse view-projection (with the
// perspective divide), minus the eye position is the direction of the view ray.

in vec2 v_ndc;

uniform mat4 u_inverse_view_projection;
uniform vec3 u_camera_position;
uniform samplerCube u_sky;

out vec4 o_color;

void main() {
    vec4 far_point = u_inverse_view_projection * vec4(v_ndc, 1.0, 1.0);
    vec3 direction = far_point.xyz / far_point.w - u_camera_position;
    o_color = vec4(texture(u_sky, direction).rgb, 1.0);
}
