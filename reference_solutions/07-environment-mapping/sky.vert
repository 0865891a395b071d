#version 330 core
// Reference solution, 07-environment-mapping: the sky behind everything. The fullscreen triangle
// is put on the far plane (z = w, so depth 1 after the perspective divide): with the depth test
// "lequal" it survives only where the scene left the cleared depth 1, i.e. behind the objects.

layout(location = 0) in vec3 a_position;  // already in clip space, z = 0

out vec2 v_ndc;

void main() {
    v_ndc = a_position.xy;
    gl_Position = vec4(a_position.xy, 1.0, 1.0);
}
