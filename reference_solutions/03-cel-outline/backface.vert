#version 330 core
// Reference solution, 03-cel-outline, task 2: back faces drawn as wide lines (polygon mode
// "line", front faces culled, depth test LEQUAL). Where a back face meets a front face, at the
// silhouette, its edge is as near as the front face and the line shows; everywhere else the
// front surface hides the back faces. Each vertex is moved toward the eye along its own view ray
// by u_depth_offset world units, so the half of every wide line that lies over the object is not
// lost to the depth test, and the line keeps its place on the screen (a point moved along the
// ray through the eye projects to the same pixel). (Raskar, Cohen, "Image Precision Silhouette
// Edges", I3D 1999, translate back faces toward the viewer the same way; Gooch, Sloan, Gooch,
// Shirley, Riesenfeld, "Interactive Technical Illustration", I3D 1999, draw them as wide lines.)

layout(location = 0) in vec3 a_position;

uniform mat4 u_model_view;
uniform mat4 u_projection;

uniform float u_depth_offset;  // world (= view) units toward the eye

void main() {
    vec4 p_view = u_model_view * vec4(a_position, 1.0);
    // The eye is at the origin of view space: -p_view.xyz points from the vertex to the eye.
    p_view.xyz += normalize(-p_view.xyz) * u_depth_offset;
    gl_Position = u_projection * p_view;
}
