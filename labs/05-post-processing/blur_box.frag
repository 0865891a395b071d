#version 330 core
// Lab 05, step 3: box blur. Each output pixel is the plain average of the (2r+1) x (2r+1) scene
// texels centred on it, r = u_box_radius (it changes from scene to scene).

in vec2 v_uv;  // (0, 0) bottom-left .. (1, 1) top-right: the centre of this fragment's texel
// (Reading by texelFetch instead? The texel under uv is ivec2(uv / texel); clamp every index to the
// texture, as the README says.)

uniform sampler2D u_scene;
uniform int u_box_radius;  // r, in texels

out vec4 o_color;

// Each function below is one idea of the lab and is graded on its own: keep their names and
// parameters (README, "How it is graded").

// One texel in uv units: uv runs 0..1 over the whole texture; textureSize(u_scene, 0) tells you
// how many texels that is, across and up.
vec2 texelSize() {
    // TODO(student)
    return vec2(0.0);
}

// The mean of the (2r+1) x (2r+1) texels around uv, r = radius, their centres one texel apart.
vec3 boxBlur(vec2 uv, vec2 texel, int radius) {
    // TODO(student): sum the texels at offsets (x, y), x and y from -r to r, and divide by the
    // number of taps so that the weights sum to one.
    return texture(u_scene, uv).rgb;
}

void main() {
    o_color = vec4(boxBlur(v_uv, texelSize(), u_box_radius), 1.0);
}
