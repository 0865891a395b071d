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

void main() {
    vec3 n = normalize(v_view_normal);
    vec3 incident = normalize(v_view_position);  // from the eye (origin) to the fragment

    vec3 r = reflect(incident, n);
    vec3 t = refract(incident, n, 1.0 / u_ior);

    vec3 diffuse = u_base_color.rgb * texture(u_irradiance, n).rgb;
    vec3 color = u_diffuse * diffuse + u_reflection * texture(u_sky, r).rgb + u_refraction * texture(u_sky, t).rgb;
    o_color = vec4(color, 1.0);
}
