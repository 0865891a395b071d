#version 330 core
// Environment mapping computed in eye space: the eye is at the origin, so the incident ray is
// just the fragment's position.

in vec3 v_view_position;
in vec3 v_view_normal;

uniform vec4 u_base_color;

uniform samplerCube u_sky;
uniform samplerCube u_irradiance;

uniform float u_diffuse;
uniform float u_reflection;
uniform float u_refraction;
uniform float u_ior;

out vec4 o_color;

vec3 reflectedSky(vec3 incident, vec3 n) {
    vec3 r = reflect(normalize(incident), n);
    return texture(u_sky, r).rgb;
}

vec3 refractedSky(vec3 incident, vec3 n) {
    vec3 t = refract(normalize(incident), n, 1.0 / u_ior);
    return texture(u_sky, t).rgb;
}

vec3 diffuseLight(vec3 n, vec3 albedo) { return albedo * texture(u_irradiance, n).rgb; }

void main() {
    vec3 n = normalize(v_view_normal);
    vec3 incident = v_view_position;  // from the eye (origin) to the fragment
    vec3 color = u_diffuse * diffuseLight(n, u_base_color.rgb) + u_reflection * reflectedSky(incident, n) +
                 u_refraction * refractedSky(incident, n);
    o_color = vec4(color, 1.0);
}
