#version 330 core
// Environment mapping with the reflection and refraction formulas written out instead of
// reflect() and refract().

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

vec3 reflectedSky(vec3 incident, vec3 n) {
    vec3 d = normalize(incident);  // eye -> surface
    float cos_i = -dot(n, d);      // cosine of the angle of incidence
    // Mirror: flip the component of d along n.
    return texture(u_sky, d + 2.0 * cos_i * n).rgb;
}

vec3 refractedSky(vec3 incident, vec3 n) {
    vec3 d = normalize(incident);
    float cos_i = -dot(n, d);
    // Snell: sin_t = eta sin_i with eta = 1 / ior; the refracted ray keeps d's tangential
    // component scaled by eta and gets a normal component of length cos_t.
    float eta = 1.0 / u_ior;
    float sin2_t = eta * eta * (1.0 - cos_i * cos_i);
    vec3 t = vec3(0.0);
    if (sin2_t <= 1.0) {
        float cos_t = sqrt(1.0 - sin2_t);
        t = eta * d + (eta * cos_i - cos_t) * n;
    }
    return texture(u_sky, t).rgb;
}

vec3 diffuseLight(vec3 n, vec3 albedo) { return albedo * texture(u_irradiance, n).rgb; }

void main() {
    vec3 n = normalize(v_world_normal);
    vec3 incident = v_world_position - u_camera_position;
    vec3 color = u_diffuse * diffuseLight(n, u_base_color.rgb) + u_reflection * reflectedSky(incident, n) +
                 u_refraction * refractedSky(incident, n);
    o_color = vec4(color, 1.0);
}
