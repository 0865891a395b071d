#version 330 core
// 01-phong, fragment stage. One function per light; point and directional lights told apart
// by w; the reflection vector from the textbook formula r = 2(n.l)n - l (l toward the light).

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

vec3 directionToLight(vec4 light, vec3 p) {
    if (light.w == 0.0) {
        return normalize(light.xyz);  // directional: xyz already points toward the light
    }
    return normalize(light.xyz / light.w - p);  // point light
}

vec3 shadeOne(vec3 n, vec3 v, vec3 p, int i) {
    vec3 l = directionToLight(u_light_position[i], p);
    float n_dot_l = dot(n, l);
    if (n_dot_l <= 0.0) {
        return vec3(0.0);  // lit from behind: this light contributes nothing here
    }
    vec3 r = 2.0 * n_dot_l * n - l;
    float r_dot_v = max(dot(r, v), 0.0);
    vec3 diffuse = u_diffuse * n_dot_l * u_base_color.rgb;
    vec3 specular = vec3(u_specular * pow(r_dot_v, u_shininess));
    return u_light_color[i] * (diffuse + specular);
}

void main() {
    vec3 n = normalize(v_world_normal);
    vec3 v = normalize(u_camera_position - v_world_position);
    vec3 color = u_ambient * u_base_color.rgb;
    for (int i = 0; i < u_light_count; ++i) {
        color += shadeOne(n, v, v_world_position, i);
    }
    o_color = vec4(color, 1.0);
}
