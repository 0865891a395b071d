#version 330 core
// 01-phong, fragment stage. Lighting in view space: the eye sits at the origin, and the lights are
// brought over with u_view (w keeps a point light's position apart from a sun's direction).

in vec3 v_view_position;
in vec3 v_view_normal;

uniform mat4 u_view;
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
    vec3 unnormalised = light_position.xyz - light_position.w * p;
    return unnormalised / length(unnormalised);
}

vec3 diffuse(vec3 n, vec3 l, vec3 base_color) {
    return base_color * u_diffuse * clamp(dot(l, n), 0.0, 1.0);
}

float phongHighlight(vec3 n, vec3 l, vec3 v) {
    vec3 r = reflect(-l, n);
    return u_specular * pow(clamp(dot(v, r), 0.0, 1.0), u_shininess);
}

vec3 shadeLight(vec3 n, vec3 l, vec3 v, vec3 light_color, vec3 base_color) {
    return dot(l, n) <= 0.0 ? vec3(0.0) : (diffuse(n, l, base_color) + vec3(phongHighlight(n, l, v))) * light_color;
}

void main() {
    vec3 n = normalize(v_view_normal);
    vec3 v = -normalize(v_view_position);
    vec3 rgb = u_base_color.rgb * u_ambient;
    for (int k = 0; k < u_light_count; k++) {
        vec4 light = u_view * u_light_position[k];
        rgb += shadeLight(n, toLight(light, v_view_position), v, u_light_color[k], u_base_color.rgb);
    }
    o_color = vec4(rgb, 1.0);
}
