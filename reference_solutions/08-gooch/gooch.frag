#version 330 core
// Reference solution, 08-gooch, pass 1: Gooch tone shading with a white Phong highlight, written
// to two attachments at once (multiple render targets): the colour, and the normal for pass 2.
//
//   t      = (1 + n.l) / 2                       0 facing away from the light, 1 facing it
//   k_cool = k_blue   + alpha k_d
//   k_warm = k_yellow + beta  k_d
//   I      = t k_warm + (1 - t) k_cool  +  k_s max(r.v, 0)^shininess   (white; only where n.l > 0)
//
// A. Gooch, B. Gooch, P. Shirley, E. Cohen, "A Non-Photorealistic Lighting Model for Automatic
// Technical Illustration", SIGGRAPH 1998, Section 4 (Equations 2 and 3). Warm faces the light, as
// the paper's text and figures have it (its Equation 2, read literally with l pointing toward the
// light, swaps the two weights; Real-Time Rendering, 4th ed., Section 5.1, writes it as here).
// Only the first light's direction is used; its colour and any other light are ignored.
// (u_silhouettes, u_creases, u_depth_threshold, u_crease_threshold and u_line_color in lab.json
// belong to pass 2, lines.frag.)

in vec3 v_world_position;
in vec3 v_world_normal;

uniform vec3 u_camera_position;
uniform vec4 u_light_position[SL_MAX_LIGHTS];  // w = 1: point light; w = 0: direction toward the light
uniform vec4 u_base_color;                     // k_d

uniform vec3 u_k_blue;      // (0, 0, b)
uniform vec3 u_k_yellow;    // (y, y, 0)
uniform float u_alpha;      // how much of k_d the cool end keeps
uniform float u_beta;       // how much of k_d the warm end keeps
uniform float u_specular;   // k_s of the white highlight
uniform float u_shininess;  // Phong exponent

out vec4 o_color;   // attachment "color"
out vec4 o_normal;  // attachment "normal": world-space unit normal, encoded into 0..1

vec3 goochTone(vec3 n, vec3 l, vec3 k_d) {
    float t = (1.0 + dot(n, l)) * 0.5;
    vec3 k_cool = u_k_blue + u_alpha * k_d;
    vec3 k_warm = u_k_yellow + u_beta * k_d;
    return t * k_warm + (1.0 - t) * k_cool;
}

vec3 whiteHighlight(vec3 n, vec3 l, vec3 v) {
    float n_dot_l = dot(n, l);
    if (n_dot_l <= 0.0) {
        return vec3(0.0);  // the light is behind the surface: r may still point at the viewer
    }
    vec3 r = 2.0 * n_dot_l * n - l;  // l mirrored about n
    return vec3(u_specular * pow(max(dot(r, v), 0.0), u_shininess));  // white, not k_d
}

vec4 encodeNormal(vec3 n) {
    // The target is rgba8: it stores 0..1 only, so a component of -0.7 would come back as 0.
    return vec4(n * 0.5 + 0.5, 1.0);
}

void main() {
    vec3 n = normalize(v_world_normal);
    vec4 light = u_light_position[0];
    vec3 l = normalize(light.xyz - v_world_position * light.w);
    vec3 v = normalize(u_camera_position - v_world_position);

    vec3 color = goochTone(n, l, u_base_color.rgb) + whiteHighlight(n, l, v);

    o_color = vec4(color, 1.0);
    o_normal = encodeNormal(n);
}
