#version 330 core
// Composite: the three levels as the columns of a matrix times the weight vector, added to the
// scene; then Reinhard written as 1 - 1 / (1 + x), which equals x / (1 + x).

in vec2 v_uv;

uniform sampler2D u_scene;
uniform sampler2D u_bloom0;
uniform sampler2D u_bloom1;
uniform sampler2D u_bloom2;
uniform vec3 u_level_weights;
uniform float u_exposure;

out vec4 o_color;

void main() {
    mat3 levels = mat3(texture(u_bloom0, v_uv).rgb, texture(u_bloom1, v_uv).rgb, texture(u_bloom2, v_uv).rgb);
    vec3 hdr = texture(u_scene, v_uv).rgb + levels * u_level_weights;
    o_color = vec4(vec3(1.0) - vec3(1.0) / (vec3(1.0) + u_exposure * hdr), 1.0);
}
