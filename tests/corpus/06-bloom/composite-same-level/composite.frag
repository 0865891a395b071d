#version 330 core
// Composite: scene plus the weighted glare levels, then Reinhard tone mapping.

in vec2 v_uv;

uniform sampler2D u_scene;
uniform sampler2D u_bloom0;
uniform sampler2D u_bloom1;
uniform sampler2D u_bloom2;
uniform vec3 u_level_weights;
uniform float u_exposure;

out vec4 o_color;

void main() {
    vec3 scene = texture(u_scene, v_uv).rgb;
    vec3 level0 = texture(u_bloom0, v_uv).rgb;
    vec3 level1 = texture(u_bloom0, v_uv).rgb;
    vec3 level2 = texture(u_bloom0, v_uv).rgb;
    vec3 glare = u_level_weights.x * level0 + u_level_weights.y * level1 + u_level_weights.z * level2;
    vec3 x = u_exposure * (scene + glare);
    o_color = vec4(x / (1.0 + x), 1.0);
}
