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
        vec3 l = normalize(u_light_position[i].xyz - v_world_position * u_light_position[i].w);

        // Lambert: brightness follows the cosine of the angle between n and l.
        float lambert = dot(n, l);
        vec3 diffuse = u_diffuse * lambert * u_base_color.rgb;

        // No highlight when the light is behind the surface.
        vec3 specular = vec3(0.0);
        if (lambert > 0.0) {
            vec3 r = reflect(-l, n);
            specular = vec3(u_specular * pow(max(dot(r, v), 0.0), u_shininess));
        }

        color += u_light_color[i] * (diffuse + specular);
    }

    o_color = vec4(color, 1.0);
}
