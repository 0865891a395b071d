// Lab 11 (shadow mapping): the lighting both lit passes share. It is the course's, not a student
// file, and not the lesson: ambient light plus Lambert's diffuse term from every light, where the
// first light's share is scaled by its visibility (1 lit, 0 in shadow, in between at a soft edge).
// Only the first light has a shadow map; any other light shines everywhere.

uniform int u_light_count;
uniform vec4 u_light_position[SL_MAX_LIGHTS];  // w = 1: point light; w = 0: direction toward the light
uniform vec3 u_light_color[SL_MAX_LIGHTS];
uniform vec4 u_base_color;
uniform float u_ambient;
uniform float u_diffuse;

// Unit vector from the surface point p toward light i (point or directional).
vec3 to_light(int i, vec3 p) {
    vec4 light = u_light_position[i];
    return normalize(light.xyz - p * light.w);
}

vec3 shade(vec3 p, vec3 n, float first_light_visibility) {
    vec3 color = u_ambient * u_base_color.rgb;
    for (int i = 0; i < u_light_count; ++i) {
        float lambert = max(dot(n, to_light(i, p)), 0.0);
        float visibility = i == 0 ? first_light_visibility : 1.0;
        color += visibility * u_diffuse * lambert * u_light_color[i] * u_base_color.rgb;
    }
    return color;
}
