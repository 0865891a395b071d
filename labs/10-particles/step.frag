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

// The acceleration per unit mass of a particle at x.
vec3 acceleration(vec3 x) {
    // TODO(student): a(x) = g + k (c - x), from u_gravity, u_attraction and u_attractor.
    return vec3(0.0);
}

// One time step of u_dt seconds for the particle at x with velocity v (both updated in place).
void eulerStep(inout vec3 x, inout vec3 v) {
    // TODO(student): one step of semi-implicit Euler:
    //     v' = v + dt a(x),   x' = x + dt v'   (the position moves with the NEW velocity)
}

// The walls of the box [0, 1]^3, for the particle at x with velocity v (both updated in place).
void walls(inout vec3 x, inout vec3 v) {
    // TODO(student): for each coordinate that left [0, 1]: put it back on the wall, and reflect
    // that component of the velocity, scaled by the restitution u_restitution.
}

void main() {
    // TODO(student): read this particle's position and velocity. This fragment's pixel IS the
    // particle's texel: gl_FragCoord.xy is the pixel's centre, (i + 0.5, j + 0.5), so
    // ivec2(gl_FragCoord.xy) is always a texel of the state (texelFetch needs no clamp here).
    vec3 x = vec3(0.5);
    vec3 v = vec3(0.0);

    // TODO(student): one step (eulerStep), and the walls (walls). In which order? The walls
    // must test the NEW position (README, "The walls").

    o_position = vec4(x, 1.0);
    o_velocity = vec4(v, 1.0);
}
