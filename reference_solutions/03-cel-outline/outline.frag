#version 330 core
// Reference solution, 03-cel-outline: the outline's colour. The hull is ink, not a lit surface:
// one flat black, no lighting, so it reads as a line and not as a second, larger object.

out vec4 o_color;

void main() {
    o_color = vec4(0.0, 0.0, 0.0, 1.0);
}
