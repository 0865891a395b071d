#version 330 core
// 04-render-to-texture, passes "uv_check" and "mesh": colour the mesh from a texture, then light it.
// u_texture is the pattern target in the "mesh" pass, and a UV test grid (uv_grid.png) in the
// "uv_check" pass: the same code must put both on the mesh the same way. The lab sets up the
// sampler (trilinear filtering with mipmaps, wrap mode repeat); your job is the coordinate and the
// lookup.

in vec3 v_world_position;
in vec3 v_world_normal;
in vec2 v_texcoord;

uniform sampler2D u_texture;
uniform vec2 u_tiling;       // how often the texture repeats across the mesh's 0..1 range
uniform float u_ambient;
uniform int u_light_count;
uniform vec4 u_light_position[SL_MAX_LIGHTS];  // w = 1: point light; w = 0: direction toward it
uniform vec3 u_light_color[SL_MAX_LIGHTS];

out vec4 o_color;

// Each function below is one idea of the lab and is graded on its own: keep their names and
// parameters (README, "How it is graded").

// The coordinate to read the texture at: the mesh's texture coordinate, repeated u_tiling times
// across the mesh's 0..1 range.
vec2 tiledCoord(vec2 texcoord) {
    return texcoord;  // the mesh's own coordinate
}

// The surface colour at the texture coordinate uv.
vec3 surfaceColor(vec2 uv) {
    return texture(u_texture, uv).rgb;
}

void main() {
    vec3 albedo = surfaceColor(tiledCoord(v_texcoord));

    // Given: ambient + Lambert diffuse, so the shape reads.
    vec3 n = normalize(v_world_normal);
    vec3 light = vec3(u_ambient);
    for (int i = 0; i < u_light_count; ++i) {
        vec3 l = normalize(u_light_position[i].xyz - v_world_position * u_light_position[i].w);
        light += (1.0 - u_ambient) * max(dot(n, l), 0.0) * u_light_color[i];
    }
    o_color = vec4(albedo * light, 1.0);
}
