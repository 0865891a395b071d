#version 330 core
// 01-phong, fragment stage: Phong reflection model per fragment, with GLSL's reflect().

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
    vec3 N = normalize(v_world_normal);
    vec3 V = normalize(u_camera_position - v_world_position);

    vec3 diffuse_sum = vec3(0.0);
    vec3 specular_sum = vec3(0.0);
    for (int i = 0; i < u_light_count; ++i) {
        vec3 L = normalize(u_light_position[i].xyz - u_light_position[i].w * v_world_position);
        float lambert = max(dot(N, L), 0.0);
        // reflect(I, N) wants the incident direction, travelling toward the surface: -L.
        vec3 R = reflect(-L, N);
        float phong = lambert > 0.0 ? pow(max(dot(R, V), 0.0), u_shininess) : 0.0;
        diffuse_sum += lambert * u_light_color[i];
        specular_sum += phong * u_light_color[i];
    }

    vec3 color = u_base_color.rgb * (u_ambient + u_diffuse * diffuse_sum) + u_specular * specular_sum;
    o_color = vec4(color, 1.0);
}
