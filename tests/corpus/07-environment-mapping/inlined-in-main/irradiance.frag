#version 330 core
// 07-environment-mapping, the irradiance pass. This shader runs once for every texel of an 8x8
// cube map (six faces, one draw per face). For its texel's direction n it must add up the light
// arriving from the whole sky, every texel of the 16x16 small sky, weighted by
//   max(n . w, 0)   (Lambert's cosine: light from the side counts less)   and
//   dOmega          (the solid angle the sky texel covers: corner texels cover less than centre ones)
// and divide by pi, so that a sky of constant radiance L gives back L:
//   E(n) / pi = (1 / pi) * sum_texels L_k * max(n . w_k, 0) * dOmega_k
// Read labs/07-environment-mapping/README.md first: it derives both weights. Each function below
// is one idea of the lab and is graded on its own: keep their names and parameters.

in vec2 v_uv;  // 0..1 across the face being drawn: s = v_uv.x, t = v_uv.y

uniform int u_cube_face;          // the face this draw writes: 0..5 = +x, -x, +y, -y, +z, -z
uniform samplerCube u_sky_small;  // 16x16 per face, nearest filtering

out vec4 o_color;

const int kSkySize = 16;
const float kPi = 3.14159265358979;

// The (unnormalised) direction through face coordinates sc, tc in [-1, 1] of a cube face.
vec3 faceDirection(int face, float sc, float tc) {
    // TODO(student): one case per face, from the README's table (OpenGL's cube-map face
    // selection, read backwards). For +x the answer is vec3(1.0, -tc, -sc).
    return vec3(0.0, 0.0, 1.0);
}

// The solid angle that the rectangle [u0, u1] x [v0, v1] of a face (the face being the square
// [-1, 1]^2 at distance 1 from the centre) covers, seen from the cube's centre.
float texelSolidAngle(float u0, float v0, float u1, float v1) {
    // TODO(student): see "The solid angle of a cube-map texel" in the README.
    return 0.0;
}

// E(n) / pi for the unit direction n.
vec3 irradiance(vec3 n) {
    vec3 sum = vec3(0.0);
    const float texel_size = 2.0 / float(kSkySize);
    for (int face = 0; face < 6; ++face) {
        for (int j = 0; j < kSkySize; ++j) {
            for (int i = 0; i < kSkySize; ++i) {
                // Texel (i, j) covers [u0, u0 + texel_size] x [v0, v0 + texel_size] on the face.
                float u0 = float(i) * texel_size - 1.0;
                float v0 = float(j) * texel_size - 1.0;

                // TODO(student): the texel's direction w (through its centre), its radiance
                // texture(u_sky_small, w).rgb, its solid angle, and add
                // radiance * max(n . w, 0) * solid_angle to sum (w normalised for the dot).
            }
        }
    }
    // TODO(student): normalise so that a constant sky gives back its constant.
    return sum;
}

void main() {
    // Per face: the major axis, and the axes along which s and t grow (the README's table).
    vec3 major[6] = vec3[6](vec3(1, 0, 0), vec3(-1, 0, 0), vec3(0, 1, 0), vec3(0, -1, 0), vec3(0, 0, 1), vec3(0, 0, -1));
    vec3 along_s[6] = vec3[6](vec3(0, 0, -1), vec3(0, 0, 1), vec3(1, 0, 0), vec3(1, 0, 0), vec3(1, 0, 0), vec3(-1, 0, 0));
    vec3 along_t[6] = vec3[6](vec3(0, -1, 0), vec3(0, -1, 0), vec3(0, 0, 1), vec3(0, 0, -1), vec3(0, -1, 0), vec3(0, -1, 0));

    vec2 st = 2.0 * v_uv - 1.0;
    vec3 n = normalize(major[u_cube_face] + st.x * along_s[u_cube_face] + st.y * along_t[u_cube_face]);

    vec3 sum = vec3(0.0);
    float h = 2.0 / float(kSkySize);
    for (int face = 0; face < 6; ++face) {
        for (int j = 0; j < kSkySize; ++j) {
            for (int i = 0; i < kSkySize; ++i) {
                float u0 = float(i) * h - 1.0, v0 = float(j) * h - 1.0;
                float u1 = u0 + h, v1 = v0 + h;
                // F(U, V) = atan(U V / sqrt(1 + U^2 + V^2)) at the four corners
                float omega = atan(u1 * v1, sqrt(1.0 + u1 * u1 + v1 * v1)) - atan(u0 * v1, sqrt(1.0 + u0 * u0 + v1 * v1)) -
                              atan(u1 * v0, sqrt(1.0 + u1 * u1 + v0 * v0)) + atan(u0 * v0, sqrt(1.0 + u0 * u0 + v0 * v0));
                vec3 w = major[face] + (u0 + 0.5 * h) * along_s[face] + (v0 + 0.5 * h) * along_t[face];
                sum += texture(u_sky_small, w).rgb * max(dot(n, normalize(w)), 0.0) * omega;
            }
        }
    }
    o_color = vec4(sum / kPi, 1.0);
}
