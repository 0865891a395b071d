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
// Each function below is one idea of the lab and is graded on its own: keep their names and
// parameters (README, "How it is graded").

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

// Stripes of period 1: 0 on the first half of every period, 1 on the second half
// (0 for 0 <= fract(x) < 0.5, 1 for 0.5 <= fract(x) < 1).
float stripes(float x) {
    // TODO(student): one line with fract() and step(). Mind the order of step()'s arguments:
    // step(edge, x) is 0 below the edge and 1 from it on.
    return 0.0;
}

// The checker: 1 where exactly one of stripes(p.x) and stripes(p.y) is 1 (exclusive or).
float checker(vec2 p) {
    // TODO(student): combine stripes(p.x) and stripes(p.y) into their XOR with arithmetic on 0/1
    // values (no bool, no if). Their product is AND, not XOR.
    return 0.0;
}

// ---- Task 2: the same patterns, averaged over the pixel's footprint -----------------------------

// The integral of stripes() from 0 to x.
float stripes_integral(float x) {
    // TODO(student): every whole period contributes 1/2; inside the current period the stripe has
    // been 1 for as long as fract(x) has been above 0.5. See "Integrate, then subtract" in the
    // README.
    return 0.0;
}

// The average of stripes() over [x - w/2, x + w/2]: a box filter of width w (in periods).
float filtered_stripes(float x, float w) {
    // TODO(student): the integral over the box, divided by the box's width. Guard against w = 0.
    // Until then this returns the point-sampled stripes, so the task-2 scenes show the aliasing
    // you are about to remove.
    return stripes(x);
}

// The average of checker() over a box of w.x by w.y around p.
float filtered_checker(vec2 p, vec2 w) {
    // TODO(student): filter each direction with its own width, then combine the two averages the
    // way checker() combines the two stripe patterns (the README says why that is exact).
    return checker(p);
}

void main() {
    vec2 p = v_texcoord * u_frequency;
    vec2 w = max(fwidth(p), vec2(1e-6));  // the footprint, before any branch

    // Point-sampled stripes along each axis, and their running integrals at the box's two ends.
    vec2 a = step(0.5, fract(p));
    vec2 lo = p - 0.5 * w, hi = p + 0.5 * w;
    vec2 filtered = (0.5 * floor(hi) + max(fract(hi) - 0.5, 0.0) - 0.5 * floor(lo) - max(fract(lo) - 0.5, 0.0)) / w;

    vec2 v = u_filtered ? filtered : a;
    float s = (u_pattern == 0) ? v.x : v.x + v.y - 2.0 * v.x * v.y;
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
