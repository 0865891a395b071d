#version 330 core
// Lab 10 (particles), pass "step": advances every particle by one time step. The state lives in
// the two attachments of target "state" (64x16 texels, one texel per particle): position in
// "position", velocity in "velocity". lab.json runs this pass `repeat` times; the framework keeps
// two copies of "state" and swaps them after every run (ping-pong), so this pass reads the
// previous step while it writes the next.
//
// Forces (per unit mass):   a(x) = g + k (c - x)        (gravity plus a spring to the attractor c)
// Walls: the box [0, 1]^3 (see README.md for the exact rule).
// Each function below is one idea of the lab and is graded on its own: keep their names and
// parameters (README, "How it is graded").
// (lab.json's scenes also set u_spawn_min, u_spawn_max, u_velocity_mean, u_velocity_spread for
// init.frag and u_point_size, u_intensity, u_slow_color, u_fast_color, u_max_speed for the draw
// pass; they are named here only because the framework warns about a scene uniform that a pass's
// shaders never mention.)

// No `in vec2 v_uv;` here: texelFetch at ivec2(gl_FragCoord.xy) needs no texture coordinate, and
// the grader warns about an input a shader never reads. If you would rather sample with
// texture(u, v_uv) (shared/fullscreen.vert hands v_uv on, at this texel's centre), declare it.

uniform sampler2D u_state_position;  // xyz: position, w: 1 (unused)
uniform sampler2D u_state_velocity;  // xyz: velocity, w: 1 (unused)

uniform float u_dt;           // seconds per step
uniform vec3 u_gravity;       // m/s^2
uniform float u_attraction;   // k, 1/s^2 (0: no attractor)
uniform vec3 u_attractor;     // c
uniform float u_restitution;  // e

out vec4 o_position;
out vec4 o_velocity;

// How much the velocity changes over one step.
vec3 acceleration(vec3 x) {
    vec3 a = u_gravity + u_attraction * (u_attractor - x);
    return a * u_dt;
}

// Semi-implicit Euler: velocity first, then the position with the new velocity.
void eulerStep(inout vec3 x, inout vec3 v) {
    v = v + acceleration(x) * u_dt;
    x = x + v * u_dt;
}

// The walls of the box [0, 1]^3: each coordinate that left it is put back on its wall, and that
// component of the velocity (the one across the wall) is reflected and damped; the others slide on.
void walls(inout vec3 x, inout vec3 v) {
    for (int i = 0; i < 3; ++i) {
        if (x[i] < 0.0) {
            x[i] = 0.0;
            v[i] = -u_restitution * v[i];
        } else if (x[i] > 1.0) {
            x[i] = 1.0;
            v[i] = -u_restitution * v[i];
        }
    }
}

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy);  // pixel centre (i + 0.5, j + 0.5) -> texel (i, j)
    vec3 x = texelFetch(u_state_position, texel, 0).xyz;
    vec3 v = texelFetch(u_state_velocity, texel, 0).xyz;

    eulerStep(x, v);
    // The walls test where the step took the particle, so that no particle is stored outside.
    walls(x, v);

    // Both attachments: an output left unwritten would keep its old state.
    o_position = vec4(x, 1.0);
    o_velocity = vec4(v, 1.0);
}
