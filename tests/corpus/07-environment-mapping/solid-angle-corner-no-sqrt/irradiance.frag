#version 330 core
// The diffuse irradiance map.
// One output texel of the 8x8-per-face cube target per fragment: its direction n, then the
// cosine-weighted integral of the sky's radiance over the hemisphere around n, as a sum over every
// texel of the 16x16-per-face small sky, each weighted by the solid angle it covers:
//   E(n) / pi = (1 / pi) * sum_texels L_k * max(n . w_k, 0) * dOmega_k
// (irradiance environment maps: Ramamoorthi and Hanrahan, "An Efficient Representation for
// Irradiance Environment Maps", SIGGRAPH 2001; the same integral done brute force.) Divided by pi,
// a sky of constant radiance L gives back L, since the clamped cosine integrates to pi.

in vec2 v_uv;  // 0..1 across the face being drawn: s = v_uv.x, t = v_uv.y

uniform int u_cube_face;          // the face this draw writes: 0..5 = +x, -x, +y, -y, +z, -z
uniform samplerCube u_sky_small;  // 16x16 per face, nearest filtering

out vec4 o_color;

const int kSkySize = 16;
const float kPi = 3.14159265358979;

// The (unnormalised) direction through face coordinates sc, tc in [-1, 1] of a cube face: the
// OpenGL face selection table read backwards (OpenGL 4.5 core, section 8.13, table 8.19).
vec3 faceDirection(int face, float sc, float tc) {
    if (face == 0) return vec3(1.0, -tc, -sc);
    if (face == 1) return vec3(-1.0, -tc, sc);
    if (face == 2) return vec3(sc, 1.0, tc);
    if (face == 3) return vec3(sc, -1.0, -tc);
    if (face == 4) return vec3(sc, -tc, 1.0);
    return vec3(-sc, -tc, -1.0);
}

// Solid angle of the face rectangle [0, u] x [0, v] seen from the cube's centre (the face plane at
// distance 1): the integral of dA / (1 + u^2 + v^2)^(3/2), which is atan(u v / sqrt(1 + u^2 + v^2)).
float cornerSolidAngle(float u, float v) { return atan(u * v, 1.0 + u * u + v * v); }

// The solid angle a face rectangle [u0, u1] x [v0, v1] covers, exactly: inclusion-exclusion of the
// four rectangles from the face's centre to its corners.
float texelSolidAngle(float u0, float v0, float u1, float v1) {
    return cornerSolidAngle(u1, v1) - cornerSolidAngle(u0, v1) - cornerSolidAngle(u1, v0) +
           cornerSolidAngle(u0, v0);
}

// E(n) / pi for the unit direction n: every texel of the small sky, weighted by Lambert's cosine
// and by the solid angle it covers.
vec3 irradiance(vec3 n) {
    vec3 sum = vec3(0.0);
    const float texel_size = 2.0 / float(kSkySize);
    for (int face = 0; face < 6; ++face) {
        for (int j = 0; j < kSkySize; ++j) {
            for (int i = 0; i < kSkySize; ++i) {
                float u0 = float(i) * texel_size - 1.0, u1 = u0 + texel_size;
                float v0 = float(j) * texel_size - 1.0, v1 = v0 + texel_size;
                float solid_angle = texelSolidAngle(u0, v0, u1, v1);
                // Sampling at the texel centre with nearest filtering reads exactly that texel.
                vec3 w = faceDirection(face, 0.5 * (u0 + u1), 0.5 * (v0 + v1));
                vec3 radiance = texture(u_sky_small, w).rgb;
                float cos_theta = max(dot(n, normalize(w)), 0.0);
                sum += radiance * cos_theta * solid_angle;
            }
        }
    }
    return sum / kPi;
}

void main() {
    // This texel's direction: its face coordinates, from 0..1 to -1..1, through the face table.
    vec3 n = normalize(faceDirection(u_cube_face, 2.0 * v_uv.x - 1.0, 2.0 * v_uv.y - 1.0));
    o_color = vec4(irradiance(n), 1.0);
}
