#version 330 core
// 08-gooch, pass 1. The tone in the form of the SIGGRAPH 1999 course notes (Advanced Graphics
// Programming Techniques Using OpenGL, "Non-photorealistic lighting models"): two opposed lights
// l and -l with diffuse colours (k_warm - k_cool)/2 and (k_cool - k_warm)/2 over an ambient
// (k_cool + k_warm)/2. Without the clamp of OpenGL's lighting this is exactly
//   (k_cool + k_warm)/2 + (k_warm - k_cool)/2 * n.l  =  t k_warm + (1 - t) k_cool,  t = (1 + n.l)/2

in vec3 v_world_position;
in vec3 v_world_normal;

uniform vec3 u_camera_position;
uniform vec4 u_light_position[SL_MAX_LIGHTS];
uniform vec4 u_base_color;

uniform vec3 u_k_blue;
uniform vec3 u_k_yellow;
uniform float u_alpha;
uniform float u_beta;
uniform float u_specular;
uniform float u_shininess;

out vec4 o_color;
out vec4 o_normal;

vec3 to_light(vec4 light, vec3 p) {
    if (light.w == 0.0) return normalize(light.xyz);
    return normalize(light.xyz - p);
}

void main() {
    vec3 n = normalize(v_world_normal);
    vec3 l = to_light(u_light_position[0], v_world_position);
    float n_dot_l = dot(n, l);

    vec3 k_cool = u_k_blue + u_alpha * u_base_color.rgb;
    vec3 k_warm = u_k_yellow + u_beta * u_base_color.rgb;
    vec3 ambient = 0.5 * (k_cool + k_warm);
    vec3 swing = 0.5 * (k_warm - k_cool);
    vec3 color = ambient + swing * n_dot_l;

    // Phong highlight in white
    vec3 v = normalize(u_camera_position - v_world_position);
    vec3 r = normalize(2.0 * n_dot_l * n - l);
    float s = n_dot_l > 0.0 ? pow(max(dot(r, v), 0.0), u_shininess) : 0.0;
    color += vec3(u_specular * s);

    o_color = vec4(color, 1.0);
    o_normal = vec4((n + 1.0) / 2.0, 1.0);
}
