#version 330 core
// Reflection and refraction computed in eye space, where the incident ray is the position
// itself; the cube maps hold WORLD directions, so every direction is rotated back to world space
// before the lookup. The inverse of the view's rotation is its transpose.

in vec3 v_view_position;
in vec3 v_view_normal;

uniform mat4 u_view;
uniform vec4 u_base_color;

uniform samplerCube u_sky;
uniform samplerCube u_irradiance;

uniform float u_diffuse;
uniform float u_reflection;
uniform float u_refraction;
uniform float u_ior;

out vec4 o_color;

void main() {
    mat3 eye_to_world = transpose(mat3(u_view));
    vec3 n = normalize(v_view_normal);
    vec3 incident = normalize(v_view_position);

    vec3 r = eye_to_world * reflect(incident, n);
    vec3 t = eye_to_world * refract(incident, n, 1.0 / u_ior);
    vec3 n_world = eye_to_world * n;

    vec3 color = u_diffuse * u_base_color.rgb * texture(u_irradiance, n_world).rgb +
                 u_reflection * texture(u_sky, r).rgb + u_refraction * texture(u_sky, t).rgb;
    o_color = vec4(color, 1.0);
}
