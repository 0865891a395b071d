#version 330 core
// Reference solution, 02-toon, task 2: toon shading through 1D ramp textures.
//   diffuse:   C * L_i * ramp(0.5 * n.l + 0.5)
//              (the 1D texture lookup of Lake, Marshall, Harris, Blackstein, "Stylized Rendering
//              Techniques for Scalable Real-Time 3D Animation", NPAR 2000, indexed with the
//              half-Lambert coordinate of Mitchell, Francke, Eng, "Illustrative Rendering in
//              Team Fortress 2", NPAR 2007, so the ramp also shades the side facing away)
//   highlight: L_i * specular_ramp((n.h)^s), h = normalize(l + v)  (Blinn, "Models of Light
//              Reflection for Computer Synthesized Pictures", SIGGRAPH 1977), only where n.l > 0
//   edges:     everything times edge_ramp(n.v): dark where the surface turns away from the eye

in vec3 v_world_position;
in vec3 v_world_normal;

uniform vec3 u_camera_position;
uniform int u_light_count;
uniform vec4 u_light_position[SL_MAX_LIGHTS];
uniform vec3 u_light_color[SL_MAX_LIGHTS];
uniform vec4 u_base_color;

uniform sampler1D u_ramp;           // diffuse ramp, RGB
uniform sampler1D u_specular_ramp;  // highlight ramp, grey
uniform sampler1D u_edge_ramp;      // silhouette ramp, grey

uniform float u_diffuse;    // 1: diffuse ramp on, 0: off
uniform float u_specular;   // strength of the highlight
uniform float u_shininess;  // Blinn exponent s
uniform float u_edge;       // 1: silhouettes darkened, 0: not

out vec4 o_color;

vec3 rampDiffuse(vec3 n, vec3 l, vec3 base_color) {
    // n.l runs over [-1, 1]; the ramp over [0, 1].
    float s = 0.5 * dot(n, l) + 0.5;
    return base_color * texture(u_ramp, s).rgb;
}

float toonHighlight(vec3 n, vec3 l, vec3 v) {
    if (dot(n, l) <= 0.0) {
        return 0.0;  // the light does not reach the point: h may still face the eye
    }
    vec3 h = normalize(l + v);
    float t = pow(max(dot(n, h), 0.0), u_shininess);
    return texture(u_specular_ramp, t).r;
}

float silhouette(vec3 n, vec3 v) {
    return texture(u_edge_ramp, max(dot(n, v), 0.0)).r;
}

void main() {
    vec3 n = normalize(v_world_normal);
    vec3 v = normalize(u_camera_position - v_world_position);
    vec3 color = vec3(0.0);
    for (int i = 0; i < u_light_count; ++i) {
        vec4 lp = u_light_position[i];
        vec3 l = normalize(lp.xyz - v_world_position * lp.w);
        color += u_light_color[i] *
                 (u_diffuse * rampDiffuse(n, l, u_base_color.rgb) + u_specular * toonHighlight(n, l, v));
    }
    color *= mix(1.0, silhouette(n, v), u_edge);
    o_color = vec4(color, 1.0);
}
