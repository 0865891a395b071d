#version 330 core
// 03-cel-outline, provided (not a student file): cel ("toon") shading. The Lambert term of every
// light is cut into a few flat bands, so the object reads as a cartoon: a lit tone, a mid tone
// and a shadow tone with hard borders between them. (Lake, Marshall, Harris, Blackstein,
// "Stylized Rendering Techniques for Scalable Real-Time 3D Animation", NPAR 2000, look the
// band up in a 1D texture; three steps written as code do the same here.) Lab 02 treats cel
// shading properly; this lab is about the outline drawn around it.

in vec3 v_world_position;
in vec3 v_world_normal;

uniform int u_light_count;
uniform vec4 u_light_position[SL_MAX_LIGHTS];  // w = 1: point light at xyz; w = 0: toward the light
uniform vec3 u_light_color[SL_MAX_LIGHTS];
uniform vec4 u_base_color;

out vec4 o_color;

// Three bands of the Lambert term: shadow, mid tone, lit.
float band(float lambert) {
    if (lambert > 0.6) return 1.0;
    if (lambert > 0.2) return 0.65;
    return 0.35;
}

void main() {
    vec3 n = normalize(v_world_normal);
    vec3 light = vec3(0.0);
    for (int i = 0; i < u_light_count; ++i) {
        vec3 l = normalize(u_light_position[i].xyz - v_world_position * u_light_position[i].w);
        light += band(max(dot(n, l), 0.0)) * u_light_color[i];
    }
    o_color = vec4(u_base_color.rgb * light, 1.0);
}
