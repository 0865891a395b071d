#version 330 core
// 03-cel-outline, task 2, vertex stage of the back-face lines.
//
// The "backlines" pass draws the object's BACK faces (front faces culled) as wide lines
// (polygon mode "line", 5 pixels) over the cel-shaded image, with the depth test LEQUAL
// (lab.json). The front surface hides every back face except where the two meet: at the
// silhouette. See the README, task 2.

layout(location = 0) in vec3 a_position;

uniform mat4 u_model_view;
uniform mat4 u_projection;

uniform float u_depth_offset;  // how far to move each vertex toward the eye, in world units (0.1)

void main() {
    vec4 p_view = u_model_view * vec4(a_position, 1.0);

    // TODO(student): half of every wide line lies over the object, where the front surface is
    // nearer than the line and hides it. Move the vertex u_depth_offset world units toward the
    // eye, along the line through the eye and the vertex, so that it still lands on the same
    // pixel. (In view space the eye is at the origin.)

    gl_Position = u_projection * p_view;
}
