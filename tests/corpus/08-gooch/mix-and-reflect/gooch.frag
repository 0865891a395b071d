#version 330 core
// 08-gooch, pass 1: Gooch tone + white highlight, colour and normal to two attachments.
// Written with GLSL's built-ins: mix() for the cool-to-warm blend, reflect() for the highlight.

in vec3 v_world_position;
in vec3 v_world_normal;

uniform vec3 u_camera_position;
uniform vec4 u_light_position;  // declared as one vec4: the framework gives it the first light
uniform vec4 u_base_color;

uniform vec3 u_k_blue;
uniform vec3 u_k_yellow;
uniform float u_alpha;
uniform float u_beta;
uniform float u_specular;
uniform float u_shininess;

layout(location = 0) out vec4 o_color;
layout(location = 1) out vec4 o_normal;

void main() {
    vec3 n = normalize(v_world_normal);
    vec3 l = u_light_position.w == 0.0 ? normalize(u_light_position.xyz)
                                       : normalize(u_light_position.xyz - v_world_position);
    vec3 v = normalize(u_camera_position - v_world_position);

    vec3 k_cool = u_k_blue + u_alpha * u_base_color.rgb;
    vec3 k_warm = u_k_yellow + u_beta * u_base_color.rgb;
    // mix(a, b, t) = a (1 - t) + b t: t = 0 gives cool (facing away), t = 1 warm (facing the light)
    vec3 tone = mix(k_cool, k_warm, 0.5 + 0.5 * dot(n, l));

    // reflect() wants the incoming direction, which travels from the light to the surface: -l
    float highlight = dot(n, l) > 0.0 ? pow(max(dot(reflect(-l, n), v), 0.0), u_shininess) : 0.0;

    o_color = vec4(tone + u_specular * highlight, 1.0);
    o_normal = vec4(0.5 + 0.5 * n, 1.0);
}
