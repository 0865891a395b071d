#version 330 core
// 01-phong, fragment stage, lighting in view space: the eye is at the origin, so v = -p.

in vec3 v_view_position;
in vec3 v_view_normal;

uniform mat4 u_view;                           // world -> view, to bring the lights over
uniform int u_light_count;
uniform vec4 u_light_position[SL_MAX_LIGHTS];  // world space
uniform vec3 u_light_color[SL_MAX_LIGHTS];
uniform vec4 u_base_color;

uniform float u_ambient;
uniform float u_diffuse;
uniform float u_specular;
uniform float u_shininess;

out vec4 o_color;

void main() {
    vec3 n = normalize(v_view_normal);
    vec3 v = normalize(-v_view_position);

    vec3 color = u_ambient * u_base_color.rgb;
    for (int i = 0; i < u_light_count; ++i) {
        // A homogeneous point (w = 1) picks up the view's translation, a direction (w = 0) only
        // its rotation: one multiplication serves both kinds of light.
        vec4 light = u_view * u_light_position[i];
        vec3 l = normalize(light.xyz - light.w * v_view_position);
        float n_dot_l = dot(n, l);
        if (n_dot_l <= 0.0) continue;
        vec3 r = reflect(-l, n);
        float spec = pow(max(dot(r, v), 0.0), u_shininess);
        color += u_light_color[i] * (u_diffuse * n_dot_l * u_base_color.rgb + u_specular * spec);
    }
    o_color = vec4(color, 1.0);
}
