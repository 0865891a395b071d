#version 330 core
// A loop that never ends and feeds the colour: the driver may stop it after its own cap on
// iterations, giving a wrong picture, or the grader's draw limit stops the whole render.
in vec3 v_world_normal;
uniform vec4 u_base_color;
out vec4 o_color;
void main() {
    float glow = 0.0;
    while (glow >= 0.0) glow += 1e-30;
    o_color = vec4(u_base_color.rgb * glow, 1.0);
}
