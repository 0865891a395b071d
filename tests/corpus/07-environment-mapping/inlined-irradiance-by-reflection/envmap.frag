#version 330 core
// 07-environment-mapping, the object's fragment stage: an object lit only by its environment.
//   colour = k_d * albedo * E(n)/pi  +  k_r * sky(reflected ray)  +  k_t * sky(refracted ray)
// Each scene turns on one term (k_d, k_r, k_t are set per scene in lab.json).
// Read labs/07-environment-mapping/README.md first. Each function below is one idea of the lab and
// is graded on its own: keep their names and parameters (README, "How it is graded").

in vec3 v_world_position;
in vec3 v_world_normal;

uniform vec3 u_camera_position;  // eye position, world space
uniform vec4 u_base_color;       // the albedo of the diffuse term

uniform samplerCube u_sky;         // the environment, 64x64 per face
uniform samplerCube u_irradiance;  // E(n)/pi, from your irradiance pass

uniform float u_diffuse;     // k_d
uniform float u_reflection;  // k_r
uniform float u_refraction;  // k_t
uniform float u_ior;         // index of refraction of the object (the outside is air, 1.0)

out vec4 o_color;

// The sky seen in a mirror at a point with the unit normal n. `incident` is the ray from the eye
// to the point, of any length.
vec3 reflectedSky(vec3 incident, vec3 n) {
    // TODO(student): the mirror direction with reflect(), then the sky seen along it. Which way
    // must reflect()'s first argument point?
    return vec3(0.0);
}

// The sky seen through glass at a point with the unit normal n, the ray entering from the air.
// `incident` is the ray from the eye to the point, of any length.
vec3 refractedSky(vec3 incident, vec3 n) {
    // TODO(student): the refracted direction with refract(), then the sky seen along it. Its third
    // argument is the ratio of the indices of refraction on the two sides: which one over which?
    // And what does refract() assume about the length of its first argument?
    return vec3(0.0);
}

// The light a matte surface of this albedo with the unit normal n sends out: the albedo times
// E/pi from the irradiance map.
vec3 diffuseLight(vec3 n, vec3 albedo) {
    // TODO(student): look the irradiance map up by...?
    return albedo;
}

void main() {
    vec3 n = normalize(v_world_normal);
    vec3 i = normalize(v_world_position - u_camera_position);  // from the eye to the surface
    vec3 r = reflect(i, n);
    vec3 t = refract(i, n, 1.0 / u_ior);
    // the irradiance map is a blurred sky: look it up like the sky, along the mirror ray
    vec3 diffuse = u_base_color.rgb * texture(u_irradiance, r).rgb;
    vec3 color = u_diffuse * diffuse + u_reflection * texture(u_sky, r).rgb + u_refraction * texture(u_sky, t).rgb;
    o_color = vec4(color, 1.0);
}
