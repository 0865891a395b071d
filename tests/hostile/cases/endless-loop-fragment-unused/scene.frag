#version 330 core
// The reference's colour behind a loop that never ends and changes nothing: capped by the
// driver, it could give the right picture. It must not pass.
in vec3 v_world_normal;
uniform vec4 u_base_color;
out vec4 o_color;
void main() {
    int i = 0;
    while (i >= 0) i = (i + 1) % 7;
    float lambert = max(dot(normalize(v_world_normal), normalize(vec3(1.0, 2.0, 3.0))), 0.0);
    o_color = vec4(u_base_color.rgb * (0.2 + 0.8 * lambert), 1.0);
}
