#version 330 core
// 07-environment-mapping, the object's vertex stage: hand the fragment stage what it needs to
// look up the cube maps, which are indexed by WORLD-space directions.
// Each function below is one idea of the lab and is graded on its own: keep their names and
// parameters (README, "How it is graded").

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;

uniform mat4 u_model;
uniform mat4 u_view_projection;
uniform mat3 u_normal_matrix;  // transpose(inverse(mat3(u_model)))

out vec3 v_world_position;
out vec3 v_world_normal;

// The normal in world space.
vec3 worldNormal(vec3 normal) {
    // TODO(student): which matrix keeps a normal perpendicular to the surface when the model is
    // scaled differently along its axes (the squashed ellipsoid of "ellipsoid_mirror")?
    return normal;
}

void main() {
    vec4 world = u_model * vec4(a_position, 1.0);
    v_world_position = world.xyz;
    v_world_normal = worldNormal(a_normal);
    gl_Position = u_view_projection * world;
}
