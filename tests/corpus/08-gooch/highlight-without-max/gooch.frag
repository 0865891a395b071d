#version 330 core
// 08-gooch, pass 1, fragment stage: Gooch tone shading with a white highlight, written to TWO
// attachments of the target "gooch" at once (multiple render targets, MRT):
//   o_color  -> gooch.color   the illustration's colour
//   o_normal -> gooch.normal  the surface normal, which pass 2 (lines.frag) reads to find creases
// Read labs/08-gooch/README.md first: it derives every formula below. Each function is one idea
// of the lab and is graded on its own: keep their names and parameters (README, "How it is graded").
// (u_silhouettes, u_creases, u_depth_threshold, u_crease_threshold and u_line_color in lab.json
// belong to pass 2, lines.frag.)

in vec3 v_world_position;
in vec3 v_world_normal;

uniform vec3 u_camera_position;                // eye position, world space
uniform vec4 u_light_position[SL_MAX_LIGHTS];  // w = 1: point light at xyz; w = 0: xyz points toward the light
uniform vec4 u_base_color;                     // k_d, the object's own colour

uniform vec3 u_k_blue;      // k_blue = (0, 0, b): the cool undertone
uniform vec3 u_k_yellow;    // k_yellow = (y, y, 0): the warm undertone
uniform float u_alpha;      // how much of k_d the cool end keeps
uniform float u_beta;       // how much of k_d the warm end keeps
uniform float u_specular;   // k_s, strength of the white highlight
uniform float u_shininess;  // the Phong exponent

out vec4 o_color;   // attachment "color"
out vec4 o_normal;  // attachment "normal"

// The Gooch tone at a point with unit normal n, l the unit vector toward the light and k_d the
// object's own colour: the cool colour where the surface faces away from the light, the warm one
// where it faces it.
vec3 goochTone(vec3 n, vec3 l, vec3 k_d) {
    // Both ends carry some of the object's colour.
    vec3 k_cool = u_k_blue + u_alpha * k_d;
    vec3 k_warm = u_k_yellow + u_beta * k_d;
    float t = (1.0 + dot(n, l)) / 2.0;  // -1..1 -> 0..1, 1 = facing the light
    return t * k_warm + (1.0 - t) * k_cool;
}

// The white Phong highlight k_s * max(r.v, 0)^shininess, as a colour, with r the direction toward
// the light mirrored about n and v the unit vector toward the eye; black where the light is behind
// the surface (n.l <= 0).
vec3 whiteHighlight(vec3 n, vec3 l, vec3 v) {
    // white Phong highlight, none where the light is behind the surface
    float n_dot_l = dot(n, l);
    if (n_dot_l <= 0.0) return vec3(0.0);
    vec3 r = 2.0 * n_dot_l * n - l;
    return vec3(u_specular * pow(dot(r, v), u_shininess));
}

// The unit normal n as o_normal stores it, for pass 2 (lines.frag decodes it in normal_at).
vec4 encodeNormal(vec3 n) {
    // -1..1 -> 0..1 so the rgba8 target keeps the negative components
    return vec4(n * 0.5 + 0.5, 1.0);
}

void main() {
    vec3 n = normalize(v_world_normal);
    // Gooch shading uses ONE light: the first. Its colour and any other light are ignored.
    vec4 light = u_light_position[0];
    vec3 l = normalize(light.xyz - v_world_position * light.w);
    vec3 v = normalize(u_camera_position - v_world_position);

    vec3 color = goochTone(n, l, u_base_color.rgb);
    color += whiteHighlight(n, l, v);  // white

    o_color = vec4(color, 1.0);
    o_normal = encodeNormal(n);
}
