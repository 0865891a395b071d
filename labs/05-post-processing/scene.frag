#version 330 core
// Lab 05, provided (not a student file): a Phong-lit scene (Phong, CACM 18(6), 1975; lab 01)
// with an optional checkerboard in texture space. The checker gives the filters something to
// work on: hard edges for Sobel, fine detail that a blur visibly softens, colour contrasts
// that a wrong grey conversion gets wrong. Its two colours and cell counts are lab uniforms.

in vec3 v_world_position;
in vec3 v_world_normal;
in vec2 v_texcoord;

uniform vec3 u_camera_position;
uniform int u_light_count;
uniform vec4 u_light_position[SL_MAX_LIGHTS];
uniform vec3 u_light_color[SL_MAX_LIGHTS];
uniform vec4 u_base_color;

uniform vec2 u_checker_cells;  // cells along u and v; (0, 0) turns the checker off
uniform vec3 u_checker_color;  // the colour of every other cell (the others keep u_base_color)
uniform float u_ambient;
uniform float u_specular;
uniform float u_shininess;

out vec4 o_color;

void main() {
    vec3 albedo = u_base_color.rgb;
    if (u_checker_cells.x > 0.0) {
        vec2 cell = floor(v_texcoord * u_checker_cells);
        if (mod(cell.x + cell.y, 2.0) >= 1.0) {
            albedo = u_checker_color;
        }
    }
    vec3 n = normalize(v_world_normal);
    vec3 v = normalize(u_camera_position - v_world_position);
    vec3 color = u_ambient * albedo;
    for (int i = 0; i < u_light_count; ++i) {
        vec4 light = u_light_position[i];
        vec3 l = normalize(light.xyz - v_world_position * light.w);
        float n_dot_l = dot(n, l);
        if (n_dot_l <= 0.0) {
            continue;
        }
        vec3 r = reflect(-l, n);
        float highlight = pow(max(dot(r, v), 0.0), u_shininess);
        color += u_light_color[i] * (n_dot_l * albedo + u_specular * highlight);
    }
    o_color = vec4(color, 1.0);
}
