#version 330 core
#line 2147483646
in vec3 v_world_normal;
out vec4 o_color;
void main() {
    o_color = vec4(undeclared_name);
}
