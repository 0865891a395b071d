#version 330 core
// 01-phong, vertex stage. Pass the world-space position and normal on to the fragment stage,
// where the lighting happens (that is what makes it Phong shading rather than Gouraud).

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;

uniform mat4 u_model;
uniform mat4 u_view;
uniform mat4 u_projection;
uniform mat3 u_normal_matrix;  // transpose(inverse(mat3(u_model))), provided by the framework

out vec3 v_world_position;
out vec3 v_world_normal;

// The normal in world space.
vec3 worldNormal(vec3 normal) {
    // TODO(student): think about which matrix keeps a normal perpendicular to the surface when
    // the model is scaled more along one axis than another (the "nonuniform_scale" scene).
    return normal;
}

void main() {
    vec4 world = u_model * vec4(a_position, 1.0);
    v_world_position = world.xyz;
    v_world_normal = worldNormal(a_normal);
    gl_Position = u_projection * u_view * world;
}
