#version 330 core
// Lab 10 (particles), pass "init" (given, not graded): writes the initial state of every particle
// into target "state". Each texel is one particle. Its position is a uniformly random point of the
// spawn box, its velocity the mean plus a uniformly random offset in [-spread, +spread] per axis.
// The random numbers come from two noise textures the framework generates (lab.json,
// "generate": {"pattern": "noise", ...}): independent values in [0, 1) from the splitmix64 hash
// of (seed, texel), the same on every machine, so the initial state is reproducible.

uniform sampler2D u_noise_position;  // seed 1
uniform sampler2D u_noise_velocity;  // seed 2

uniform vec3 u_spawn_min;
uniform vec3 u_spawn_max;
uniform vec3 u_velocity_mean;
uniform vec3 u_velocity_spread;

out vec4 o_position;
out vec4 o_velocity;

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy);
    vec3 r = texelFetch(u_noise_position, texel, 0).xyz;
    vec3 s = texelFetch(u_noise_velocity, texel, 0).xyz;
    o_position = vec4(u_spawn_min + r * (u_spawn_max - u_spawn_min), 1.0);
    // w = 1 is unused; it keeps the state PNGs of `render --all-passes` opaque.
    o_velocity = vec4(u_velocity_mean + (2.0 * s - 1.0) * u_velocity_spread, 1.0);
}
