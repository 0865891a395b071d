#version 330 core
// 01-phong, fragment stage. Known mistake: the light's colour never used.

in vec3 v_world_position;
in vec3 v_world_normal;

uniform vec3 u_camera_position;
uniform int u_light_count;
uniform vec4 u_light_position[SL_MAX_LIGHTS];  // w = 1: point light; w = 0: direction toward the light
uniform vec3 u_light_color[SL_MAX_LIGHTS];
uniform vec4 u_base_color;

uniform float u_ambient;
uniform float u_diffuse;
uniform float u_specular;
uniform float u_shininess;

out vec4 o_color;

vec3 toLight(vec4 light_position, vec3 p) {
    // Works for both kinds: for w = 0 the position term vanishes.
    return normalize(light_position.xyz - p * light_position.w);
}

vec3 diffuse(vec3 n, vec3 l, vec3 base_color) {
    return u_diffuse * max(dot(n, l), 0.0) * base_color;
}

float phongHighlight(vec3 n, vec3 l, vec3 v) {
    // r = l_in - 2(n.l_in)n needs l_in pointing from the light toward the surface.
    vec3 incident = -l;
    vec3 r = incident - 2.0 * dot(n, incident) * n;
    return u_specular * pow(max(dot(r, v), 0.0), u_shininess);
}

vec3 shadeLight(vec3 n, vec3 l, vec3 v, vec3 light_color, vec3 base_color) {
    if (dot(n, l) <= 0.0) {
        return vec3(0.0);  // the light is behind the surface: no diffuse, no highlight
    }
    return diffuse(n, l, base_color) + phongHighlight(n, l, v);
}

void main() {
    // Interpolation shortens normals: renormalise per fragment.
    vec3 n = normalize(v_world_normal);
    vec3 v = normalize(u_camera_position - v_world_position);
    vec3 color = u_ambient * u_base_color.rgb;
    for (int i = 0; i < u_light_count; ++i) {
        vec3 l = toLight(u_light_position[i], v_world_position);
        color += shadeLight(n, l, v, u_light_color[i], u_base_color.rgb);
    }
    o_color = vec4(color, 1.0);
}
