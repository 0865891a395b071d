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

// Eye-space directions back to world space, for the lookups.
vec3 toWorld(vec3 d) { return transpose(mat3(u_view)) * d; }

vec3 reflectedSky(vec3 incident, vec3 n) {
    return texture(u_sky, toWorld(reflect(normalize(incident), n))).rgb;
}

vec3 refractedSky(vec3 incident, vec3 n) {
    return texture(u_sky, toWorld(refract(normalize(incident), n, 1.0 / u_ior))).rgb;
}

vec3 diffuseLight(vec3 n, vec3 albedo) { return albedo * texture(u_irradiance, toWorld(n)).rgb; }

void main() {
    vec3 n = normalize(v_view_normal);
    vec3 incident = v_view_position;  // from the eye (origin) to the fragment
    vec3 color = u_diffuse * diffuseLight(n, u_base_color.rgb) + u_reflection * reflectedSky(incident, n) +
                 u_refraction * refractedSky(incident, n);
    o_color = vec4(color, 1.0);
}
