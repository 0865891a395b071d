#version 330 core
// 02-toon, task 2 (pass "ramp"): toon shading through 1D ramp textures, as games do it.
// The ramps are tiny images (8x1 texels) the lab binds with nearest filtering and
// clamp-to-edge wrapping; your job is to compute where to look them up:
//   diffuse:   base colour * light colour * ramp(s),   s = n.l remapped from [-1, 1] to [0, 1]
//   highlight: light colour * specular_ramp(t),        t = max(n.h, 0)^shininess,
//              h = the Blinn half vector between l and v; only where n.l > 0
//   edges:     the sum of both, times edge_ramp(max(n.v, 0))  (dark where the surface turns away)
// Read labs/02-toon/README.md first. Each function below is one idea of the lab and is graded on
// its own: keep their names and parameters (README, "How it is graded").

in vec3 v_world_position;
in vec3 v_world_normal;

uniform vec3 u_camera_position;                // eye position, world space
uniform int u_light_count;                     // how many entries below are in use
uniform vec4 u_light_position[SL_MAX_LIGHTS];  // w = 1: point light at xyz; w = 0: xyz points toward the light
uniform vec3 u_light_color[SL_MAX_LIGHTS];     // colour times intensity
uniform vec4 u_base_color;                     // the material's colour

uniform sampler1D u_ramp;           // ramp.png: diffuse ramp, RGB
uniform sampler1D u_specular_ramp;  // specular_ramp.png: highlight ramp, grey (use .r)
uniform sampler1D u_edge_ramp;      // edge_ramp.png: silhouette ramp, grey (use .r)

uniform float u_diffuse;    // weight of the diffuse term (0 to show the highlight alone; 100 in the
                            // silhouette scenes, which drives the colour past white to show the edges alone)
uniform float u_specular;   // weight of the highlight (0 in scenes about diffuse light or edges)
uniform float u_shininess;  // the Blinn exponent
uniform float u_edge;       // 1: darken silhouettes; 0: don't (mix(1.0, edge, u_edge))

out vec4 o_color;

// One light's diffuse term before the light's colour: the base colour times the diffuse ramp,
// looked up at s, n.l remapped from [-1, 1] to [0, 1].
vec3 rampDiffuse(vec3 n, vec3 l, vec3 base_color) {
    float s = 0.5 * dot(n, l) + 0.5;  // n.l from [-1, 1] onto the ramp's [0, 1]
    return base_color * texture(u_ramp, s).rgb;
}

// One light's hard highlight before the light's colour: the specular ramp (.r) at
// t = max(n.h, 0)^u_shininess, h the Blinn half vector between l and v; 0 where n.l <= 0.
float toonHighlight(vec3 n, vec3 l, vec3 v) {
    if (dot(n, l) <= 0.0) {
        return 0.0;  // the light does not reach this point
    }
    vec3 h = normalize(l + v);
    float t = pow(max(dot(n, h), 0.0), u_shininess);
    return texture(u_specular_ramp, t).r;
}

// The silhouette factor the colour is multiplied by: the edge ramp (.r) at max(n.v, 0).
float silhouette(vec3 n, vec3 v) {
    return texture(u_edge_ramp, max(dot(n, v), 0.0)).r;
}

void main() {
    // The vertex stage already gives a unit normal (u_normal_matrix * a_normal).
    vec3 n = v_world_normal;
    vec3 v = normalize(u_camera_position - v_world_position);

    vec3 color = vec3(0.0);
    for (int i = 0; i < u_light_count; ++i) {
        vec4 lp = u_light_position[i];
        vec3 l = normalize(lp.xyz - v_world_position * lp.w);

        color += u_light_color[i] * u_diffuse * rampDiffuse(n, l, u_base_color.rgb);
        color += u_light_color[i] * u_specular * toonHighlight(n, l, v);
    }

    color *= mix(1.0, silhouette(n, v), u_edge);

    o_color = vec4(color, 1.0);
}
