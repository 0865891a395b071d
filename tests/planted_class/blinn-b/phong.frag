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
    vec3 normal = normalize(v_world_normal);
    vec3 to_eye = normalize(u_camera_position - v_world_position);

    vec3 color = u_ambient * u_base_color.rgb;

    for (int i = 0; i < u_light_count; ++i) {
        // w = 0 turns the point light into a direction
        vec3 to_light = normalize(u_light_position[i].xyz - v_world_position * u_light_position[i].w);
        float lambert = dot(normal, to_light);
        if (lambert <= 0.0) {
            continue;
        }
        vec3 halfway = normalize(to_light + to_eye);  // Blinn
        vec3 specular = u_specular * pow(max(dot(normal, halfway), 0.0), u_shininess) * u_light_color[i];
        vec3 diffuse = u_diffuse * lambert * u_base_color.rgb * u_light_color[i];
        color += diffuse + specular;
    }

    o_color = vec4(color, 1.0);
}
