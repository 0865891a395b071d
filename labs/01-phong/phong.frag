#version 330 core
// 01-phong, fragment stage. Evaluate the Phong reflection model for every fragment:
//   colour = ambient + sum over lights of (diffuse + specular)
// Read labs/01-phong/README.md first: it derives each term.

in vec3 v_world_position;
in vec3 v_world_normal;

uniform vec3 u_camera_position;                // eye position, world space
uniform int u_light_count;                     // how many entries below are in use
uniform vec4 u_light_position[SL_MAX_LIGHTS];  // w = 1: point light at xyz; w = 0: xyz points toward the light
uniform vec3 u_light_color[SL_MAX_LIGHTS];     // colour times intensity
uniform vec4 u_base_color;                     // the material's colour

uniform float u_ambient;    // k_a
uniform float u_diffuse;    // k_d
uniform float u_specular;   // k_s
uniform float u_shininess;  // the exponent n

out vec4 o_color;

void main() {
    // TODO(student): the interpolated normal is no longer unit length. Fix that.
    vec3 n = v_world_normal;

    vec3 color = u_ambient * u_base_color.rgb;

    for (int i = 0; i < u_light_count; ++i) {
        // TODO(student): the unit vector from the fragment toward light i. One expression can
        // serve point lights (w = 1) and directional lights (w = 0).

        // TODO(student): the diffuse term k_d * max(n.l, 0) * base colour * light colour.

        // TODO(student): the specular term k_s * max(r.v, 0)^shininess * light colour, with
        // r = l - 2(n.l)n. Careful: in this formula l points FROM the light TOWARD the surface.
        // Skip the highlight when the light is behind the surface.
    }

    o_color = vec4(color, 1.0);
}
