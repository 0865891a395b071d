#version 330 core
// Composite: tone-map the scene into 0..1 first, then put the glare on top.

in vec2 v_uv;

uniform sampler2D u_scene;
uniform sampler2D u_bloom0;
uniform sampler2D u_bloom1;
uniform sampler2D u_bloom2;
uniform vec3 u_level_weights;
uniform float u_exposure;

out vec4 o_color;

void main() {
    vec3 x = u_exposure * texture(u_scene, v_uv).rgb;
    vec3 scene = x / (1.0 + x);  // Reinhard
    vec3 glare = u_level_weights.x * texture(u_bloom0, v_uv).rgb + u_level_weights.y * texture(u_bloom1, v_uv).rgb +
                 u_level_weights.z * texture(u_bloom2, v_uv).rgb;
    o_color = vec4(scene + glare, 1.0);
}
