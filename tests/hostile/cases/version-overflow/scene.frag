#version 99999999999
in vec3 v_world_normal;
out vec4 o_color;
void main() { o_color = vec4(1.0); }
