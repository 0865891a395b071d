#version 330 core
// 12-normal-mapping, fragment stage: a file you hand in (with normal_map.vert).
//
// Task 1: decode the normal map's texel into a tangent-space normal, with a strength.
// Task 2: build the tangent frame (T, B, N) in world space and turn a tangent-space vector with it.
// Task 3: the bitangent's handedness, for the mirrored half of the meshes.
// Task 4: light the surface with the mapped normal.
// Read README.md first: it gives every formula and the conventions of the map and the meshes.
// Each function below is one idea of the lab and is graded on its own: keep their names and
// parameters (README, "How it is graded").
//
// Look for TODO(student). The debug views (u_show) and the lighting function are provided.

in vec3 v_world_position;
in vec3 v_world_normal;   // world space, from your vertex stage
in vec4 v_world_tangent;  // xyz: world space; w: +1 or -1
in vec2 v_texcoord;

uniform sampler2D u_normal_map;   // tangent-space normals stored as n * 0.5 + 0.5; +X right, +Y up the image
uniform float u_normal_strength;  // how steep the bumps are: 1 as the map was made, 0 flat
uniform int u_show;               // 0: lit; 1: the decoded normal; 2: the frame turning u_probe
uniform vec3 u_probe;             // a fixed tangent-space direction, shown by u_show == 2

uniform vec3 u_camera_position;                // eye position, world space
uniform int u_light_count;                     // how many entries below are in use
uniform vec4 u_light_position[SL_MAX_LIGHTS];  // w = 1: point light at xyz; w = 0: xyz points toward the light
uniform vec3 u_light_color[SL_MAX_LIGHTS];     // colour times intensity
uniform vec4 u_base_color;                     // the material's colour
uniform float u_ambient;
uniform float u_specular;
uniform float u_shininess;

out vec4 o_color;

// ---- Task 1: the map's texel to a tangent-space normal ------------------------------------------

// `texel` is what texture() returns for the map, each channel in [0, 1]. Return the unit normal it
// stores, in tangent space: x along the texture's right, y up the texture, z out of the surface.
vec3 decode_normal(vec3 texel) {
    return normalize(texel * 2.0 - 1.0);
}

// The unit tangent-space normal n with its bumps made `strength` times as steep (0: flat, 1: as the
// map was made), as a unit vector.
vec3 scale_bumps(vec3 n, float strength) {
    return normalize(vec3(n.xy * strength, n.z));  // the slope is in x and y
}

// ---- Task 3: the bitangent, with the handedness (to_world, below, calls it) ---------------------

// The unit bitangent B, up the image on the surface, from the unit normal n, the unit tangent t
// perpendicular to it (along the image's right) and the handedness w: -1 where the texture is
// mirrored, +1 elsewhere.
vec3 bitangent(vec3 n, vec3 t, float w) {
    return cross(n, t) * w;  // cross(n, t) alone points down the image where t is mirrored
}

// ---- Task 2: tangent space to world space -------------------------------------------------------

// Turn a tangent-space direction into world space with the frame of this fragment: tangent T,
// bitangent B and normal N, in world space.
vec3 to_world(vec3 n_tangent) {
    vec3 n = normalize(v_world_normal);
    vec3 t = normalize(v_world_tangent.xyz);
    vec3 b = bitangent(n, t, v_world_tangent.w);
    return normalize(mat3(t, b, n) * n_tangent);
}

// ---- Provided: Blinn-Phong in world space (lab 01), from the normal n at world position p ------

vec3 shade(vec3 n, vec3 p) {
    n = normalize(n);
    vec3 v = normalize(u_camera_position - p);
    vec3 color = u_ambient * u_base_color.rgb;
    for (int i = 0; i < u_light_count; ++i) {
        vec4 lp = u_light_position[i];
        vec3 l = normalize(lp.xyz - p * lp.w);
        float diffuse = max(dot(n, l), 0.0);
        float specular = diffuse > 0.0 ? pow(max(dot(n, normalize(l + v)), 0.0), u_shininess) : 0.0;
        color += u_light_color[i] * (diffuse * u_base_color.rgb + u_specular * specular);
    }
    return color;
}

void main() {
    vec3 n_tangent = scale_bumps(decode_normal(texture(u_normal_map, v_texcoord).rgb), u_normal_strength);
    if (u_show == 1) {  // the decoded normal as a colour: the map itself, when decoded right
        o_color = vec4(n_tangent * 0.5 + 0.5, 1.0);
        return;
    }
    if (u_show == 2) {  // the world-space direction of the fixed u_probe, as a colour
        o_color = vec4(to_world(normalize(u_probe)) * 0.5 + 0.5, 1.0);
        return;
    }

    vec3 n = to_world(n_tangent);
    o_color = vec4(shade(n, v_world_position), 1.0);
}
