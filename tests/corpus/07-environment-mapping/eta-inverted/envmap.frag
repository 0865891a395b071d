#version 330 core
// Reference solution, 07-environment-mapping: an object lit only by its environment.
//   colour = k_d * albedo * E(n)/pi  +  k_r * L(reflect(i, n))  +  k_t * L(refract(i, n, 1/ior))
// Mirror reflection and refraction of an environment map: Blinn and Newell, "Texture and
// Reflection in Computer Generated Images", CACM 19(10), 1976; cube maps: Greene, "Environment
// Mapping and Other Applications of World Projections", IEEE CG&A 6(11), 1986. The diffuse term
// reads the precomputed irradiance map by the normal (Ramamoorthi and Hanrahan, SIGGRAPH 2001).

in vec3 v_world_position;
in vec3 v_world_normal;

uniform vec3 u_camera_position;
uniform vec4 u_base_color;  // the albedo of the diffuse term

uniform samplerCube u_sky;         // the environment, 64x64 per face
uniform samplerCube u_irradiance;  // E(n)/pi, from the irradiance pass

uniform float u_diffuse;     // k_d
uniform float u_reflection;  // k_r
uniform float u_refraction;  // k_t
uniform float u_ior;         // index of refraction of the object (the outside is air, 1.0)

out vec4 o_color;

// The sky seen in a mirror: the ray from the eye (incident, any length) reflected about the unit
// normal n. reflect() is linear in its first argument and a cube map ignores a direction's length,
// so the normalisation is for clarity only here.
vec3 reflectedSky(vec3 incident, vec3 n) {
    vec3 r = reflect(normalize(incident), n);
    return texture(u_sky, r).rgb;
}

// The sky seen through glass: the ray from the eye bent by Snell's law, with eta = n_outside /
// n_inside (from air into the object). refract() needs a unit incident vector: its formula uses
// n.i as the cosine of the angle of incidence.
vec3 refractedSky(vec3 incident, vec3 n) {
    // glass has an index of refraction of 1.5
    vec3 t = refract(normalize(incident), n, u_ior);
    return texture(u_sky, t).rgb;
}

// A matte surface: the albedo times the irradiance map, looked up by the normal, because the light
// it receives does not depend on where the viewer is.
vec3 diffuseLight(vec3 n, vec3 albedo) { return albedo * texture(u_irradiance, n).rgb; }

void main() {
    // Interpolation shortens normals: renormalise per fragment.
    vec3 n = normalize(v_world_normal);
    // The incident ray travels from the eye toward the surface, as reflect() and refract() expect.
    vec3 incident = v_world_position - u_camera_position;

    vec3 color = u_diffuse * diffuseLight(n, u_base_color.rgb) + u_reflection * reflectedSky(incident, n) +
                 u_refraction * refractedSky(incident, n);
    o_color = vec4(color, 1.0);
}
