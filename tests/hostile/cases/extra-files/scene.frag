#version 330 core
in vec3 v_world_normal;
uniform vec4 u_base_color;
out vec4 o_color;
void main() {
    float lambert = max(dot(normalize(v_world_normal), normalize(vec3(1.0, 2.0, 3.0))), 0.0);
    o_color = vec4(u_base_color.rgb * (0.2 + 0.8 * lambert), 1.0);
}
