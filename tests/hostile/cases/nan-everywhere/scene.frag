#version 330 core
// Every pixel NaN.
in vec3 v_world_normal;
uniform vec4 u_base_color;
out vec4 o_color;
void main() {
    float zero = u_base_color.a - u_base_color.a;
    o_color = vec4(zero / zero);
}
