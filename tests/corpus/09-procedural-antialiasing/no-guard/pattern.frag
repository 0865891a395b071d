#version 330 core
// 09-procedural-antialiasing, fragment stage: the file you hand in.
//
// Task 1: stripes and a checker, computed at the pixel centre only. Up close they are crisp; far
// away, where one pixel covers many stripes, they alias into moire.
// Task 2: the same patterns averaged over the part of the pattern that the pixel covers (a box
// filter), with the filter width taken from the screen-space derivatives of the pattern
// coordinate. Read README.md first: it derives every formula you need and pins down which one the
// grader expects.
//
// Look for TODO(student). Everything else (the uniforms, the lighting at the end) is provided.

in vec3 v_world_position;
in vec3 v_world_normal;
in vec2 v_texcoord;

uniform int u_light_count;
uniform vec4 u_light_position[SL_MAX_LIGHTS];
uniform vec3 u_light_color[SL_MAX_LIGHTS];

uniform vec2 u_frequency;  // pattern periods across the texture, along u and v
uniform int u_pattern;     // 0: stripes across u, 1: checker
uniform bool u_filtered;   // false: task 1 (point-sampled), true: task 2 (box-filtered)
uniform vec3 u_color_a;    // where the pattern is 0
uniform vec3 u_color_b;    // where the pattern is 1
uniform float u_ambient;

out vec4 o_color;

// ---- Task 1: the patterns, sampled at the pixel centre only -------------------------------------

// 0 on the first half of every period, 1 on the second half.
float stripes(float x) {
    return step(0.5, fract(x));
}

// 1 where exactly one of the two stripe patterns is 1 (exclusive or), written with arithmetic.
float checker(vec2 p) {
    float a = stripes(p.x);
    float b = stripes(p.y);
    return a + b - 2.0 * a * b;
}

// ---- Task 2: the same patterns, averaged over the pixel's footprint -----------------------------

// The integral of stripes() from 0 to x: each whole period contributes 1/2, and inside the
// current period the pattern has been 1 for max(fract(x) - 0.5, 0).
float stripes_integral(float x) {
    return 0.5 * floor(x) + max(fract(x) - 0.5, 0.0);
}

// The average of stripes() over [x - w/2, x + w/2]: a box filter of width w.
float filtered_stripes(float x, float w) {
    return (stripes_integral(x + 0.5 * w) - stripes_integral(x - 0.5 * w)) / w;
}

// A box over a rectangle is separable; in +-1 form the checker is a product (1 - 2c) =
// (1 - 2a)(1 - 2b), and the average of a product of functions of x and of y alone is the product
// of their averages. So the filtered checker is the XOR formula applied to filtered stripes.
float filtered_checker(vec2 p, vec2 w) {
    float a = filtered_stripes(p.x, w.x);
    float b = filtered_stripes(p.y, w.y);
    return a + b - 2.0 * a * b;
}

void main() {
    vec2 p = v_texcoord * u_frequency;

    // The pixel's extent in pattern space: how far p moves to the next pixel across plus to the
    // next pixel down. Taken here, outside any branch, where every pixel of a 2x2 quad runs.
    vec2 w = fwidth(p);

    float s;
    if (u_filtered) {
        s = (u_pattern == 0) ? filtered_stripes(p.x, w.x) : filtered_checker(p, w);
    } else {
        s = (u_pattern == 0) ? stripes(p.x) : checker(p);
    }
    vec3 albedo = mix(u_color_a, u_color_b, s);

    // Simple diffuse light so that curved objects keep their shape (not part of the lesson).
    vec3 n = normalize(v_world_normal);
    vec3 light = vec3(u_ambient);
    for (int i = 0; i < u_light_count; ++i) {
        vec4 l = u_light_position[i];
        vec3 to_light = normalize(l.xyz - v_world_position * l.w);
        light += (1.0 - u_ambient) * u_light_color[i] * max(dot(n, to_light), 0.0);
    }
    o_color = vec4(albedo * light, 1.0);
}
