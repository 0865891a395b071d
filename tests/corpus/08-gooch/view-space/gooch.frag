#version 330 core
// 08-gooch, pass 1, in eye space. The G-buffer gets the EYE-space normal: lines.frag only
// compares normals with each other (dot products), and a rotation changes no dot product, so
// eye-space normals find the same creases as world-space ones.

in vec3 v_eye_position;
in vec3 v_eye_normal;

uniform mat4 u_view;
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

void main() {
    vec3 n = normalize(v_eye_normal);
    // the light into eye space: a point moves with the whole matrix, a direction (w = 0) only rotates
    vec4 light = u_view * u_light_position[0];
    vec3 l = normalize(light.xyz - v_eye_position * light.w);
    vec3 v = normalize(-v_eye_position);

    float n_dot_l = dot(n, l);
    float t = (1.0 + n_dot_l) * 0.5;
    vec3 k_cool = u_k_blue + u_alpha * u_base_color.rgb;
    vec3 k_warm = u_k_yellow + u_beta * u_base_color.rgb;
    vec3 color = t * k_warm + (1.0 - t) * k_cool;
    if (n_dot_l > 0.0) {
        vec3 r = reflect(-l, n);
        color += u_specular * pow(max(dot(r, v), 0.0), u_shininess);
    }
    o_color = vec4(color, 1.0);
    o_normal = vec4(n * 0.5 + 0.5, 1.0);
}
