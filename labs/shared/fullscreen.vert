#version 330 core
// Shared by the course's post-processing passes ("draw": "fullscreen"): the framework draws one
// triangle whose a_position is already in clip space and whose a_texcoord runs 0..1 across the
// target, so this stage only passes them on.

layout(location = 0) in vec3 a_position;
layout(location = 2) in vec2 a_texcoord;

out vec2 v_uv;

void main() {
    v_uv = a_texcoord;
    gl_Position = vec4(a_position, 1.0);
}
