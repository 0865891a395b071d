#version 330 core
// Composite: scene plus the three glare levels, then Reinhard tone mapping. The widest level gets
// the first weight, the sharpest the last.

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
    vec3 glare = u_level_weights.x * texture(u_bloom2, v_uv).rgb + u_level_weights.y * texture(u_bloom1, v_uv).rgb +
                 u_level_weights.z * texture(u_bloom0, v_uv).rgb;
    vec3 x = u_exposure * (scene + glare);
    o_color = vec4(x / (1.0 + x), 1.0);
}
