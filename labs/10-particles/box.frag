#version 330 core
// Lab 10 (particles), pass "box" (given, not graded): the box's edges in one flat colour.
// (lab.json's scenes set u_spawn_min, u_spawn_max, u_velocity_mean, u_velocity_spread, u_gravity,
// u_attraction, u_restitution, u_point_size, u_intensity, u_slow_color, u_fast_color and
// u_max_speed for the other passes; they are named here only because the framework warns about a
// scene uniform that a pass's shaders never mention.)

uniform vec3 u_box_color;

out vec4 o_color;

void main() { o_color = vec4(u_box_color, 1.0); }
