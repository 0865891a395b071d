#version 330 core
// The sky through each pixel: the pixel's far-plane point in world space, minus the eye.

in vec2 v_ndc;

uniform mat4 u_inverse_view_projection;
uniform vec3 u_camera_position;
uniform samplerCube u_sky;

out vec4 o_color;

void main() {
    // clip space back to world space
    vec3 far_point = (u_inverse_view_projection * vec4(v_ndc, 1.0, 1.0)).xyz;
    vec3 direction = far_point - u_camera_position;
    o_color = vec4(texture(u_sky, direction).rgb, 1.0);
}
