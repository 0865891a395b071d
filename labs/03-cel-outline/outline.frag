#version 330 core
// 03-cel-outline: the colour of the outline, for both tasks (the hull of task 1 and the
// back-face lines of task 2).

out vec4 o_color;

void main() {
    // TODO(student): the outline is ink: what colour, and does it need any lighting?
    o_color = vec4(1.0, 0.0, 1.0, 1.0);
}
