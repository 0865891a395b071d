#version 330 core
// Environment mapping: diffuse from the irradiance map, mirror reflection and refraction.

in vec3 v_world_position;
in vec3 v_world_normal;

uniform vec3 u_camera_position;
uniform vec4 u_base_color;

uniform samplerCube u_sky;
uniform samplerCube u_irradiance;

uniform float u_diffuse;
uniform float u_reflection;
uniform float u_refraction;
uniform float u_ior;

out vec4 o_color;

void main() {
    vec3 n = normalize(v_world_normal);
    // view vector, from the surface to the eye (as in the Phong lab)
    vec3 v = normalize(u_camera_position - v_world_position);

    // mirror the view vector about the normal
    vec3 r = reflect(v, n);
    // the ray going into the glass continues away from the eye
    vec3 t = refract(-v, n, 1.0 / u_ior);

    vec3 diffuse = u_base_color.rgb * texture(u_irradiance, n).rgb;
    vec3 color = u_diffuse * diffuse + u_reflection * texture(u_sky, r).rgb + u_refraction * texture(u_sky, t).rgb;
    o_color = vec4(color, 1.0);
}
