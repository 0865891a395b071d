#version 330 core
// Reference solution, 04-render-to-texture, pass "pattern": an animated procedural texture.
// The pass draws one fullscreen triangle into a 256x256 target, so this shader runs once per
// texel and v_uv is the texture coordinate (s, t) of that texel's centre. It draws soft-edged
// stripes that travel across the texture:
//   p      = uv - velocity * time            (the pattern moves by velocity * time)
//   phase  = frequency . p + wobble * sin(2 pi p.t)   (in cycles; whole numbers tile)
//   stripe = smoothstep(-w, w, sin(2 pi phase))
//   colour = mix(background, stripe colour, stripe)
// A procedural texture is a function of the texture coordinate (here also of time) evaluated
// per texel; drawn into a render target it becomes an ordinary image that the mesh pass samples
// (Akenine-Moller, Haines, Hoffman, "Real-Time Rendering", 4th ed., 2018, sections 6.3
// "Procedural Texturing" and 6.4 "Texture Animation"). smoothstep is the clamped cubic
// 3x^2 - 2x^3 (GLSL 4.50 specification, section 8.3 "Common Functions"): a smooth transition
// several texels wide, so the stripes have no hard edge to alias.

in vec2 v_uv;

uniform float u_time;        // seconds
uniform vec2 u_frequency;    // stripes across the texture along s and t (whole numbers)
uniform vec2 u_velocity;     // how far the pattern travels per second, in texture units
uniform float u_wobble;      // how far the stripes swing sideways, in cycles
uniform float u_softness;    // half width of the smoothstep, in units of the sine
uniform vec3 u_background;
uniform vec3 u_stripe_color;
// (Some scenes also set u_tiling: that is for the mesh passes, which repeat this texture across
// the mesh. This pass draws the texture itself, once.)

out vec4 o_color;

const float PI = 3.14159265358979;

// A picture moved by d shows at x what it showed at x - d, so the point to look up is uv minus
// the distance travelled (velocity in texture widths per second, time in seconds).
vec2 movedPoint(vec2 uv, float time) {
    return uv - u_velocity * time;
}

// The stripe mask at p: 0 in the gaps, 1 on the stripes, a smooth ramp between.
float stripeMask(vec2 p) {
    float phase = dot(u_frequency, p) + u_wobble * sin(2.0 * PI * p.y);
    return smoothstep(-u_softness, u_softness, sin(2.0 * PI * phase));
}

void main() {
    float stripe = stripeMask(movedPoint(v_uv, u_time));
    o_color = vec4(mix(u_background, u_stripe_color, stripe), 1.0);
}
