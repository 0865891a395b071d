#version 330 core
// 01-phong, fragment stage: Phong lighting from the light source.

in vec3 v_world_position;
in vec3 v_world_normal;

uniform vec3 u_camera_position;
uniform vec4 u_light_position;  // the light: w = 1 point, w = 0 directional
uniform vec3 u_light_color;
uniform vec4 u_base_color;

uniform float u_ambient;
uniform float u_diffuse;
uniform float u_specular;
uniform float u_shininess;

out vec4 o_color;

void main() {
    vec3 n = normalize(v_world_normal);
    vec3 v = normalize(u_camera_position - v_world_position);
    vec3 l = normalize(u_light_position.xyz - v_world_position * u_light_position.w);

    vec3 ambient = u_ambient * u_base_color.rgb;
    vec3 diffuse = vec3(0.0);
    vec3 specular = vec3(0.0);

    float n_dot_l = dot(n, l);
    if (n_dot_l > 0.0) {
        diffuse = u_diffuse * n_dot_l * u_base_color.rgb * u_light_color;
        vec3 r = reflect(-l, n);
        specular = u_specular * pow(max(dot(r, v), 0.0), u_shininess) * u_light_color;
    }

    o_color = vec4(ambient + diffuse + specular, 1.0);
}
