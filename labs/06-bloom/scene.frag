#version 330 core
// Lab 06 (bloom), pass "scene": Phong shading (Phong, "Illumination for Computer Generated
// Pictures", CACM 18(6), 1975) into a float target, with values ABOVE 1 where the lights are
// strong and the highlights bright: this is the high dynamic range image the bloom works on.
// This file is the course's, not a student file (lab 01 is where Phong shading is taught).
//
// Every material is shaded in its grey (its Rec. 709 luminance): colour comes only from the
// lights. Under white lights every colour component of the image is then equal, so a bright pass
// that thresholds luminance instead of each component goes wrong only in the scenes with
// coloured lights, the ones made to show that mistake.

in vec3 v_world_position;
in vec3 v_world_normal;

uniform vec3 u_camera_position;
uniform int u_light_count;
uniform vec4 u_light_position[SL_MAX_LIGHTS];  // w = 1: point light; w = 0: direction toward the light
uniform vec3 u_light_color[SL_MAX_LIGHTS];     // colour times intensity: may exceed 1
uniform vec4 u_base_color;

uniform float u_ambient;
uniform float u_diffuse;
uniform float u_specular;  // above 1: the highlights exceed 1 even for a light of intensity 1
uniform float u_shininess;

out vec4 o_color;

void main() {
    vec3 albedo = vec3(dot(u_base_color.rgb, vec3(0.2126, 0.7152, 0.0722)));
    vec3 n = normalize(v_world_normal);
    vec3 v = normalize(u_camera_position - v_world_position);
    vec3 color = u_ambient * albedo;
    for (int i = 0; i < u_light_count; ++i) {
        vec4 light = u_light_position[i];
        vec3 l = normalize(light.xyz - v_world_position * light.w);
        float n_dot_l = dot(n, l);
        if (n_dot_l <= 0.0) {
            continue;
        }
        vec3 r = reflect(-l, n);
        float highlight = pow(max(dot(r, v), 0.0), u_shininess);
        color += u_light_color[i] * (u_diffuse * n_dot_l * albedo + u_specular * highlight);
    }
    o_color = vec4(color, 1.0);
}
