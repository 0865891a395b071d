#version 330 core
// Diffuse irradiance map: every sky texel weighted by Lambert's cosine max(n.w, 0); dividing by
// the sum of the weights makes a constant sky come out as that constant.

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

// Not needed: the cosine weights are normalised by their sum below.
float texelSolidAngle(float u0, float v0, float u1, float v1) {
    // TODO(student): see "The solid angle of a cube-map texel" in the README.
    return 0.0;
}

// The cosine-weighted mean of the sky around n.
vec3 irradiance(vec3 n) {
    vec3 sum = vec3(0.0);
    float weight = 0.0;
    for (int face = 0; face < 6; ++face) {
        for (int j = 0; j < kSkySize; ++j) {
            for (int i = 0; i < kSkySize; ++i) {
                // texel centre in [-1, 1]
                float sc = (float(i) + 0.5) / float(kSkySize) * 2.0 - 1.0;
                float tc = (float(j) + 0.5) / float(kSkySize) * 2.0 - 1.0;
                vec3 w = normalize(faceDirection(face, sc, tc));
                float cos_theta = max(dot(n, w), 0.0);
                sum += texture(u_sky_small, w).rgb * cos_theta;
                weight += cos_theta;
            }
        }
    }
    return sum / weight;
}

void main() {
    // This texel's direction: its face coordinates, from 0..1 to -1..1, through the face table.
    vec3 n = normalize(faceDirection(u_cube_face, 2.0 * v_uv.x - 1.0, 2.0 * v_uv.y - 1.0));
    o_color = vec4(irradiance(n), 1.0);
}
