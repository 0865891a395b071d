#version 330 core
// The sky along the interpolated view ray (a cube map needs no normalised direction).

in vec3 v_direction;

uniform samplerCube u_sky;

out vec4 o_color;

void main() { o_color = vec4(texture(u_sky, v_direction).rgb, 1.0); }
