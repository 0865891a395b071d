#version 330 core
// 01-phong, fragment stage.

in vec3 v_world_position;
in vec3 v_world_normal;

uniform vec3 u_camera_position;
uniform int u_light_count;
uniform vec4 u_light_position[SL_MAX_LIGHTS];
uniform vec3 u_light_color[SL_MAX_LIGHTS];
uniform vec4 u_base_color;

uniform float u_ambient;
uniform float u_diffuse;
uniform float u_specular;
uniform float u_shininess;

out vec4 o_color;

void main() {
    vec3 n = normalize(v_world_normal);
    vec3 v = normalize(u_camera_position - v_world_position);

    vec3 color = u_ambient * u_base_color.rgb;

    for (int i = 0; i < u_light_count; ++i) {
        // The light direction: from the light to the point it lights.
        vec3 l = normalize(v_world_position * u_light_position[i].w - u_light_position[i].xyz);
        float n_dot_l = dot(n, l);
        if (n_dot_l <= 0.0) {
            continue;
        }
        vec3 r = reflect(-l, n);
        float spec = pow(max(dot(r, v), 0.0), u_shininess);
        color += u_light_color[i] * (u_diffuse * n_dot_l * u_base_color.rgb + u_specular * spec);
    }

    o_color = vec4(color, 1.0);
}
