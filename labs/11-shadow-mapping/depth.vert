#version 330 core
// Lab 11 (shadow mapping), pass "shadow": the scene seen from the first light. The framework gives
// this pass the light's camera ("camera": {"light": 0} in lab.json), so u_model_view_projection
// already takes a vertex to the light's clip space. This file is the course's, not a student file.

layout(location = 0) in vec3 a_position;

uniform mat4 u_model_view_projection;

void main() {
    gl_Position = u_model_view_projection * vec4(a_position, 1.0);
}
