#version 330 core
// 7-tap Gaussian (sigma 1.5), written out tap by tap.
// Weights: exp(-k^2/4.5) / 3.69437 for k = 0, 1, 2, 3.

in vec2 v_uv;

uniform sampler2D u_image;
uniform vec2 u_direction;

out vec4 o_color;

void main() {
    ivec2 size = textureSize(u_image, 0);
    vec2 d = vec2(u_direction.x / float(size.x), u_direction.y / float(size.y));
    vec3 c = 0.2707 * texture(u_image, v_uv).rgb
           + 0.2167 * (texture(u_image, v_uv + d).rgb + texture(u_image, v_uv - d).rgb)
           + 0.1113 * (texture(u_image, v_uv + 2.0 * d).rgb + texture(u_image, v_uv - 2.0 * d).rgb)
           + 0.0366 * (texture(u_image, v_uv + 3.0 * d).rgb + texture(u_image, v_uv - 3.0 * d).rgb);
    o_color = vec4(c, 1.0);
}
