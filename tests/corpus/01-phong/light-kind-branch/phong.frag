#version 330 core
// 01-phong, fragment stage. An explicit branch on w for the two kinds of light; the textbook
// r = 2(n.l)n - l, with l toward the light.

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

vec3 toLight(vec4 light_position, vec3 p) {
    if (light_position.w == 0.0) {
        // A sun: xyz is already the direction toward it.
        return normalize(light_position.xyz);
    }
    vec3 lamp = light_position.xyz / light_position.w;
    return normalize(lamp - p);
}

vec3 diffuse(vec3 n, vec3 l, vec3 base_color) {
    float cosine = dot(n, l);
    if (cosine < 0.0) cosine = 0.0;
    return cosine * u_diffuse * base_color;
}

float phongHighlight(vec3 n, vec3 l, vec3 v) {
    vec3 mirrored = 2.0 * dot(n, l) * n - l;
    float alignment = max(0.0, dot(mirrored, v));
    return u_specular * pow(alignment, u_shininess);
}

vec3 shadeLight(vec3 n, vec3 l, vec3 v, vec3 light_color, vec3 base_color) {
    bool facing = dot(n, l) > 0.0;
    vec3 result = vec3(0.0);
    if (facing) {
        result = diffuse(n, l, base_color) * light_color;
        result += phongHighlight(n, l, v) * light_color;
    }
    return result;
}

void main() {
    vec3 normal = normalize(v_world_normal);
    vec3 eye_dir = normalize(u_camera_position - v_world_position);
    vec3 sum = vec3(0.0);
    int i = 0;
    while (i < u_light_count) {
        sum += shadeLight(normal, toLight(u_light_position[i], v_world_position), eye_dir, u_light_color[i],
                          u_base_color.rgb);
        i++;
    }
    o_color = vec4(u_ambient * u_base_color.rgb + sum, 1.0);
}
