#version 330 core
// 01-phong, fragment stage. Evaluate the Phong reflection model for every fragment:
//   colour = ambient + sum over lights of (diffuse + specular)
// Read labs/01-phong/README.md first: it derives each term. Each function below is one idea of the
// lab and is graded on its own: keep their names and parameters (README, "How it is graded").

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
uniform float u_shininess;  // the exponent s

out vec4 o_color;

// The unit vector from the surface point p toward the light.
vec3 toLight(vec4 light_position, vec3 p) {
    // TODO(student): one expression can serve point lights (w = 1) and directional lights (w = 0).
    return vec3(0.0, 1.0, 0.0);
}

// Lambert's diffuse term k_d * max(n.l, 0) * C, before the light's colour.
vec3 diffuse(vec3 n, vec3 l, vec3 base_color) {
    // TODO(student)
    return vec3(0.0);
}

// Phong's highlight k_s * max(r.v, 0)^s, before the light's colour, with r = l_in - 2(n.l_in)n.
// Careful: in that formula l_in points FROM the light TOWARD the surface.
float phongHighlight(vec3 n, vec3 l, vec3 v) {
    // TODO(student)
    return 0.0;
}

// What one light of colour light_color adds: its diffuse light and its highlight, tinted by its
// colour, and nothing at all when the light is behind the surface.
vec3 shadeLight(vec3 n, vec3 l, vec3 v, vec3 light_color, vec3 base_color) {
    // TODO(student)
    return vec3(0.0);
}

void main() {
    // TODO(student): the interpolated normal is no longer unit length. Fix that.
    vec3 n = v_world_normal;
    // TODO(student): v, the unit vector from the fragment toward the eye.
    vec3 v = vec3(0.0, 0.0, 1.0);

    vec3 color = u_ambient * u_base_color.rgb;

    // TODO(student): add what every light adds (toLight, then shadeLight).

    o_color = vec4(color, 1.0);
}
