#version 330 core
// Reference solution, 04-render-to-texture, passes "uv_check" and "mesh": the surface colour is
// read from u_texture (the pattern target, or the UV test grid) at the mesh's texture coordinate
// times u_tiling, then lit with ambient + Lambert diffuse. texture() filters with the sampler the
// lab set up: trilinear with mipmaps, wrapping with repeat (OpenGL 4.5 core specification,
// sections 8.14 "Texture Minification" and 8.14.1 "Scale Factor and Level of Detail").

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

// Coordinates beyond 1 are fine: the target's wrap mode is "repeat", and the derivatives of
// texcoord * u_tiling stay smooth, so the mipmap level is chosen right everywhere.
vec2 tiledCoord(vec2 texcoord) {
    return texcoord * u_tiling;
}

// texture() picks the mipmap level from how fast uv changes between neighbouring pixels.
vec3 surfaceColor(vec2 uv) {
    return texture(u_texture, uv).rgb;
}

void main() {
    vec3 albedo = surfaceColor(tiledCoord(v_texcoord));

    vec3 n = normalize(v_world_normal);
    vec3 light = vec3(u_ambient);
    for (int i = 0; i < u_light_count; ++i) {
        vec3 l = normalize(u_light_position[i].xyz - v_world_position * u_light_position[i].w);
        light += (1.0 - u_ambient) * max(dot(n, l), 0.0) * u_light_color[i];
    }
    o_color = vec4(albedo * light, 1.0);
}
