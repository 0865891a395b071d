#version 330 core
// Nothing drawn.
in vec3 v_world_normal;
uniform vec4 u_base_color;
out vec4 o_color;
void main() {
    discard;
}
