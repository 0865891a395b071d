#version 330 core
// Rec. 709 luma weights.
in vec2 v_texcoord;
uniform sampler2D u_scene;
out vec4 o_color;
void main() {
    vec3 c = texture(u_scene, v_texcoord).rgb;
    float y = c.g;  // mistake: green channel instead of luma
    o_color = vec4(vec3(y), 1.0);
}
