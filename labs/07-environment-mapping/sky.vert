#version 330 core
// 07-environment-mapping, the sky's vertex stage. The pass draws one triangle covering the
// screen (a_position is already in clip space, with z = 0) AFTER the objects, with the depth
// test "lequal": a fragment survives only where its depth is <= the depth already stored.

layout(location = 0) in vec3 a_position;

out vec2 v_ndc;

void main() {
    v_ndc = a_position.xy;
    // TODO(student): z = 0 puts the sky at depth 0.5, in front of almost everything. Where
    // must it be so that it shows only where no object was drawn?
    gl_Position = vec4(a_position, 1.0);
}
