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
    ivec2 texel = ivec2(gl_FragCoord.xy);
    vec3 x = texelFetch(u_state_position, texel, 0).xyz;
    vec3 v = texelFetch(u_state_velocity, texel, 0).xyz;

    // Semi-implicit Euler: the velocity first, then the position with the new velocity.
    vec3 a = u_gravity + u_attraction * (u_attractor - x);
    v += u_dt * a;
    x += u_dt * v;

    // The walls, on the new position: the components that left the box turn round, damped, and
    // the particle goes back inside.
    bvec3 below = lessThan(x, vec3(0.0));
    bvec3 above = greaterThan(x, vec3(1.0));
    vec3 bounced = -u_restitution * v;
    v = vec3(below.x || above.x ? bounced.x : v.x, below.y || above.y ? bounced.y : v.y,
             below.z || above.z ? bounced.z : v.z);
    x = clamp(x, 0.0, 1.0);

    o_position = vec4(x, 1.0);
    o_velocity = vec4(v, 1.0);
}
