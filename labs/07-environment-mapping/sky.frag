#version 330 core
// 07-environment-mapping, the sky's fragment stage: the environment seen through each pixel.

in vec2 v_ndc;  // this pixel's x, y in normalised device coordinates (-1..1)
// (Building the ray in sky.vert from u_view and u_projection instead, as the README allows? Then
// pass the ray in place of v_ndc, here and in sky.vert, so that no input is left unused.)

uniform mat4 u_inverse_view_projection;  // clip space back to world space
uniform vec3 u_camera_position;
uniform samplerCube u_sky;

out vec4 o_color;

void main() {
    // TODO(student): the world-space direction of the view ray through this pixel: take a
    // point of the pixel back to world space (do not forget the division by w), and go from
    // the eye toward it. Then look the sky up along it.
    o_color = vec4(0.5, 0.6, 0.8, 1.0);
}
