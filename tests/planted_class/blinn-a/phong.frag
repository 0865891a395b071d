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
    // one expression for both kinds of light
    return normalize(light_position.xyz - p * light_position.w);
}

// Lambert's diffuse term k_d * max(n.l, 0) * C, before the light's colour.
vec3 diffuse(vec3 n, vec3 l, vec3 base_color) {
    return u_diffuse * max(dot(n, l), 0.0) * base_color;
}

// Phong's highlight k_s * max(r.v, 0)^s, before the light's colour, with r = l_in - 2(n.l_in)n.
// Careful: in that formula l_in points FROM the light TOWARD the surface.
float phongHighlight(vec3 n, vec3 l, vec3 v) {
    vec3 h = normalize(l + v);
    return u_specular * pow(max(dot(n, h), 0.0), u_shininess);
}

// What one light of colour light_color adds: its diffuse light and its highlight, tinted by its
// colour, and nothing at all when the light is behind the surface.
vec3 shadeLight(vec3 n, vec3 l, vec3 v, vec3 light_color, vec3 base_color) {
    if (dot(n, l) <= 0.0) {
        return vec3(0.0);  // behind the surface
    }
    return (diffuse(n, l, base_color) + phongHighlight(n, l, v)) * light_color;
}

void main() {
    // the interpolated normal is shorter than 1
    vec3 n = normalize(v_world_normal);
    vec3 v = normalize(u_camera_position - v_world_position);

    vec3 color = u_ambient * u_base_color.rgb;

    for (int i = 0; i < u_light_count; ++i) {
        vec3 l = toLight(u_light_position[i], v_world_position);
        color += shadeLight(n, l, v, u_light_color[i], u_base_color.rgb);
    }

    o_color = vec4(color, 1.0);
}
