#version 330 core
// Known mistake: Gouraud shading. The model is evaluated per vertex and colours are
// interpolated, so highlights inside a triangle are lost or smeared.

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;

uniform mat4 u_model;
uniform mat4 u_view;
uniform mat4 u_projection;
uniform mat3 u_normal_matrix;
uniform vec3 u_camera_position;
uniform int u_light_count;
uniform vec4 u_light_position[SL_MAX_LIGHTS];
uniform vec3 u_light_color[SL_MAX_LIGHTS];
uniform vec4 u_base_color;
uniform float u_ambient;
uniform float u_diffuse;
uniform float u_specular;
uniform float u_shininess;

out vec3 v_world_position;
out vec3 v_world_normal;
out vec3 v_color;

void main() {
    vec4 world = u_model * vec4(a_position, 1.0);
    vec3 n = normalize(u_normal_matrix * a_normal);
    vec3 v = normalize(u_camera_position - world.xyz);
    vec3 color = u_ambient * u_base_color.rgb;
    for (int i = 0; i < u_light_count; ++i) {
        vec3 to_light = normalize(u_light_position[i].xyz - world.xyz * u_light_position[i].w);
        float n_dot_l = dot(n, to_light);
        if (n_dot_l <= 0.0) {
            continue;
        }
        vec3 r = reflect(-to_light, n);
        color += u_light_color[i] * (u_diffuse * n_dot_l * u_base_color.rgb +
                                     u_specular * pow(max(dot(r, v), 0.0), u_shininess));
    }
    v_color = color;
    v_world_position = world.xyz;
    v_world_normal = n;
    gl_Position = u_projection * u_view * world;
}
