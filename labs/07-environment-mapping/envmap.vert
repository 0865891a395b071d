#version 330 core
// 07-environment-mapping, the object's vertex stage: hand the fragment stage what it needs to
// look up the cube maps, which are indexed by WORLD-space directions.

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;

uniform mat4 u_model;
uniform mat4 u_view_projection;
uniform mat3 u_normal_matrix;  // transpose(inverse(mat3(u_model)))

out vec3 v_world_position;
out vec3 v_world_normal;

void main() {
    vec4 world = u_model * vec4(a_position, 1.0);
    v_world_position = world.xyz;
    // TODO(student): the normal in world space. Which matrix keeps it perpendicular to the
    // surface when the model is scaled differently along its axes?
    v_world_normal = a_normal;
    gl_Position = u_view_projection * world;
}
