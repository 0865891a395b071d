#version 330 core
// 04-render-to-texture, pass "pattern": draw an animated procedural texture into a render target.
// This pass draws one triangle that covers the whole 256x256 target, so this shader runs once
// per texel, and v_uv is that texel's texture coordinate (s, t), 0..1 across the target
// ((0, 0) is the texel at the bottom left, as OpenGL stores it). Whatever colour you write here
// becomes the texel the mesh pass reads at (s, t). Read labs/04-render-to-texture/README.md.
//
// The picture to draw: soft-edged stripes, wobbling sideways, travelling across the texture:
//   p      = uv - velocity * time
//   phase  = frequency . p + wobble * sin(2 pi p.t)     (measured in cycles)
//   stripe = smoothstep(-softness, softness, sin(2 pi phase))
//   colour = mix(background, stripe colour, stripe)

in vec2 v_uv;  // (s, t) of this texel
// (gl_FragCoord.xy / u_resolution is the same (s, t) in this pass. If you use that instead, delete
// the v_uv line above, or the grader warns that it is never used.)

uniform vec2 u_resolution;   // the target's size in texels, 256 x 256
uniform float u_time;        // seconds, fixed per graded scene
uniform vec2 u_frequency;    // stripes across the texture along s and t (whole numbers, so it tiles)
uniform vec2 u_velocity;     // how far the pattern travels per second, in texture units
uniform float u_wobble;      // how far the stripes swing sideways, in cycles
uniform float u_softness;    // half width of the smoothstep, in units of the sine
uniform vec3 u_background;
uniform vec3 u_stripe_color;
// (Some scenes also set u_tiling: that is for the mesh passes, which repeat this texture across
// the mesh. This pass draws the texture itself, once.)

out vec4 o_color;

const float PI = 3.14159265358979;

// Each function below is one idea of the lab and is graded on its own: keep their names and
// parameters (README, "How it is graded").

// Where the content of the texel at uv was at time 0. The pattern at time t is the pattern at
// time 0 shifted by velocity * t, so look it up at the point that was here t seconds ago.
vec2 movedPoint(vec2 uv, float time) {
    return uv - u_velocity * time;
}

// The stripe mask at p, between 0 (the background) and 1 (a stripe).
float stripeMask(vec2 p) {
    float phase = dot(u_frequency, p) + u_wobble * sin(p.y);
    return smoothstep(-u_softness, u_softness, sin(phase));
}

void main() {
    float stripe = stripeMask(movedPoint(v_uv, u_time));

    o_color = vec4(mix(u_background, u_stripe_color, stripe), 1.0);
}
