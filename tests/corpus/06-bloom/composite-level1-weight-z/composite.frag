#version 330 core
// Lab 06 (bloom), pass "composite": add the glare to the scene, then tone-map.
//
// Inputs: u_scene (the HDR scene) and the three blurred levels u_bloom0 (1/2 size), u_bloom1
// (1/4) and u_bloom2 (1/8). The texture unit scales them to this pass's full size for you.
//     hdr   = scene + u_level_weights.x * L0 + u_level_weights.y * L1 + u_level_weights.z * L2
//     x     = u_exposure * hdr
//     color = x / (1 + x)        (Reinhard's operator, per colour component)
// Add in HDR first; tone mapping is the very last step.

in vec2 v_uv;

uniform sampler2D u_scene;
uniform sampler2D u_bloom0;  // level 0: half size
uniform sampler2D u_bloom1;  // level 1: quarter size
uniform sampler2D u_bloom2;  // level 2: eighth size
uniform vec3 u_level_weights;
uniform float u_exposure;

out vec4 o_color;

// Each function below is one idea of the lab and is graded on its own: keep their names and
// parameters (README, "How it is graded").

// The glare at uv: the three levels, weighted by u_level_weights.
vec3 glare(vec2 uv) {
    vec3 level0 = texture(u_bloom0, uv).rgb;
    vec3 level1 = texture(u_bloom1, uv).rgb;
    vec3 level2 = texture(u_bloom2, uv).rgb;
    return u_level_weights.x * level0 + u_level_weights.z * level1 + u_level_weights.z * level2;
}

// Tone mapping: the HDR colour times u_exposure, through x / (1 + x) (Reinhard's operator, per
// colour component).
vec3 toneMap(vec3 hdr) {
    vec3 x = u_exposure * hdr;
    return x / (1.0 + x);
}

void main() {
    vec3 scene = texture(u_scene, v_uv).rgb;
    o_color = vec4(toneMap(scene + glare(v_uv)), 1.0);
}
