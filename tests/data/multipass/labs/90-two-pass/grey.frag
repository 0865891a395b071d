#version 330 core
// Rec. 709 luma weights.
in vec2 v_texcoord;
uniform sampler2D u_scene;
out vec4 o_color;
void main() {
    vec3 c = texture(u_scene, v_texcoord).rgb;
    float y = dot(c, vec3(0.2126, 0.7152, 0.0722));
    o_color = vec4(vec3(y), 1.0);
}
