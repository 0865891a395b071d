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
    // the interpolated normal is shorter than 1
    vec3 n = normalize(v_world_normal);
    vec3 v = normalize(u_camera_position - v_world_position);

    vec3 color = u_ambient * u_base_color.rgb;

    for (int i = 0; i < u_light_count; ++i) {
        // one expression for both kinds of light
        vec3 l = normalize(u_light_position[i].xyz - v_world_position * u_light_position[i].w);
        float ndotl = dot(n, l);
        if (ndotl <= 0.0) {
            continue;  // behind the surface
        }
        vec3 diffuse = u_diffuse * ndotl * u_base_color.rgb * u_light_color[i];
        vec3 h = normalize(l + v);
        vec3 specular = u_specular * pow(max(dot(n, h), 0.0), u_shininess) * u_light_color[i];
        color += diffuse + specular;
    }

    o_color = vec4(color, 1.0);
}
