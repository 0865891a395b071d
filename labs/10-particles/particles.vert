#version 330 core
// Lab 10 (particles), pass "draw" (vertex stage): one vertex per particle, no mesh. lab.json
// draws {"primitive": "points", "count": 1024}: this shader runs once per particle, and
// gl_VertexID (0..1023) says which. The state textures are 64x16 texels, one per particle, filled
// row by row: particle id sits in column id % 64 of row id / 64.
// This file is one goal of the lab, graded on its own with the reference's particles.frag (README,
// "How it is graded"): keep the output v_color as it is.
// (lab.json's scenes also set u_spawn_min, u_spawn_max, u_velocity_mean, u_velocity_spread,
// u_gravity, u_attraction, u_restitution for the init and step passes; they are named here only
// because the framework warns about a scene uniform that a pass's shaders never mention.)

uniform sampler2D u_positions;
uniform sampler2D u_velocities;
uniform mat4 u_view_projection;  // the scene's camera (lab.json, scenes[].camera)
uniform float u_point_size;      // pixels
uniform vec3 u_slow_color;
uniform vec3 u_fast_color;
uniform float u_max_speed;       // speeds at and above this get u_fast_color

out vec3 v_color;

void main() {
    // TODO(student): particle gl_VertexID's texel, and its position and velocity from
    // u_positions and u_velocities (texelFetch reads one texel by its integer coordinates, and
    // ignores the wrap mode: an index outside the texture reads garbage, so make sure (x, y) =
    // (column, row) lies in it).
    vec3 position = vec3(0.5);
    vec3 velocity = vec3(0.0);

    gl_Position = u_view_projection * vec4(position, 1.0);
    // TODO(student): the point's size: without it a point is 1 pixel.
    v_color = mix(u_slow_color, u_fast_color, clamp(length(velocity) / u_max_speed, 0.0, 1.0));
}
