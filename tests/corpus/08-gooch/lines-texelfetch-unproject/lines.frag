#version 330 core
// 08-gooch, pass 2, with integer texel addresses: texelFetch() reads exactly one texel, so there
// is no texel size to get wrong, and the view distance comes from unprojecting the pixel with
// inverse(u_projection) rather than from the closed form.

uniform sampler2D u_color;
uniform sampler2D u_normal;
uniform sampler2D u_depth;

uniform mat4 u_projection;

uniform float u_depth_threshold;
uniform float u_crease_threshold;
uniform vec3 u_line_color;
uniform bool u_silhouettes;
uniform bool u_creases;

out vec4 o_color;

const ivec2 OFFSETS[4] = ivec2[4](ivec2(1, 0), ivec2(-1, 0), ivec2(0, 1), ivec2(0, -1));

ivec2 clamp_to_image(ivec2 p) {
    return clamp(p, ivec2(0), textureSize(u_depth, 0) - 1);
}

float depth_at(ivec2 p) {
    return texelFetch(u_depth, clamp_to_image(p), 0).r;
}

// Back from the depth buffer to the eye: only z matters, and x, y of the clip point do not
// change the z of the unprojected point, so unproject (0, 0, z_ndc).
float eye_distance(ivec2 p) {
    vec4 eye = inverse(u_projection) * vec4(0.0, 0.0, depth_at(p) * 2.0 - 1.0, 1.0);
    return -eye.z / eye.w;
}

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    bool line = false;

    if (u_silhouettes) {
        float here = eye_distance(p);
        for (int i = 0; i < 4; ++i) {
            float there = eye_distance(p + OFFSETS[i]);
            line = line || abs(there - here) > u_depth_threshold * min(here, there);
        }
    }

    if (u_creases && depth_at(p) < 1.0) {
        vec3 here = normalize(texelFetch(u_normal, p, 0).xyz * 2.0 - 1.0);
        for (int i = 0; i < 4; ++i) {
            ivec2 q = clamp_to_image(p + OFFSETS[i]);
            if (depth_at(q) == 1.0) continue;
            vec3 there = normalize(texelFetch(u_normal, q, 0).xyz * 2.0 - 1.0);
            line = line || dot(here, there) < u_crease_threshold;
        }
    }

    o_color = line ? vec4(u_line_color, 1.0) : vec4(texelFetch(u_color, p, 0).rgb, 1.0);
}
