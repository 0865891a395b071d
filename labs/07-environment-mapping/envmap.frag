#version 330 core
// 07-environment-mapping, the object's fragment stage: an object lit only by its environment.
//   colour = k_d * albedo * E(n)/pi  +  k_r * sky(reflected ray)  +  k_t * sky(refracted ray)
// Each scene turns on one term (k_d, k_r, k_t are set per scene in lab.json).
// Read labs/07-environment-mapping/README.md first.

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

void main() {
    // TODO(student): the interpolated normal is no longer unit length. Fix that.
    vec3 n = v_world_normal;

    // TODO(student): the incident direction, world space. Which way must it point for
    // reflect() and refract()?

    // TODO(student): the mirror direction with reflect(), then the sky seen along it.
    vec3 reflected = vec3(0.0);

    // TODO(student): the refracted direction with refract(). Its third argument is the ratio
    // of the indices of refraction on the two sides: which one over which?
    vec3 refracted = vec3(0.0);

    // TODO(student): the diffuse term: the albedo times the irradiance map, looked up by...?
    vec3 diffuse = u_base_color.rgb;

    vec3 color = u_diffuse * diffuse + u_reflection * reflected + u_refraction * refracted;
    o_color = vec4(color, 1.0);
}
