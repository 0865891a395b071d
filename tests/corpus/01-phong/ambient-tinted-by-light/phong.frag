#version 330 core
// 01-phong, fragment stage.

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

void main() {
    // Interpolation shortens normals: renormalise per fragment.
    vec3 n = normalize(v_world_normal);
    vec3 v = normalize(u_camera_position - v_world_position);
    // Ambient light is the light of the room: take the light's colour.
    vec3 color = u_ambient * u_base_color.rgb * u_light_color[0];
    for (int i = 0; i < u_light_count; ++i) {
        vec4 light = u_light_position[i];
        // Works for both kinds: for w = 0 the position term vanishes.
        vec3 to_light = normalize(light.xyz - v_world_position * light.w);
        float n_dot_l = dot(n, to_light);
        if (n_dot_l <= 0.0) {
            continue;  // the light is behind the surface: no diffuse, no highlight
        }
        // r = l - 2(n.l)n needs l pointing from the light toward the surface.
        vec3 incident = -to_light;
        vec3 r = incident - 2.0 * dot(n, incident) * n;
        float highlight = pow(max(dot(r, v), 0.0), u_shininess);
        color += u_light_color[i] * (u_diffuse * n_dot_l * u_base_color.rgb + u_specular * highlight);
    }
    o_color = vec4(color, 1.0);
}
