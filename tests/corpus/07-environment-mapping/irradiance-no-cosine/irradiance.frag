#version 330 core
// Diffuse irradiance map: the mean radiance of the sky over the hemisphere around each
// direction n, each sky texel weighted by the solid angle it covers.

in vec2 v_uv;

uniform int u_cube_face;
uniform samplerCube u_sky_small;

out vec4 o_color;

const int kSkySize = 16;
const float kPi = 3.14159265358979;

vec3 faceDirection(int face, float sc, float tc) {
    if (face == 0) return vec3(1.0, -tc, -sc);
    if (face == 1) return vec3(-1.0, -tc, sc);
    if (face == 2) return vec3(sc, 1.0, tc);
    if (face == 3) return vec3(sc, -1.0, -tc);
    if (face == 4) return vec3(sc, -tc, 1.0);
    return vec3(-sc, -tc, -1.0);
}

float cornerSolidAngle(float u, float v) { return atan(u * v, sqrt(1.0 + u * u + v * v)); }

void main() {
    vec3 n = normalize(faceDirection(u_cube_face, 2.0 * v_uv.x - 1.0, 2.0 * v_uv.y - 1.0));

    vec3 sum = vec3(0.0);
    const float step = 2.0 / float(kSkySize);
    for (int face = 0; face < 6; ++face) {
        for (int j = 0; j < kSkySize; ++j) {
            for (int i = 0; i < kSkySize; ++i) {
                float u0 = float(i) * step - 1.0, u1 = u0 + step;
                float v0 = float(j) * step - 1.0, v1 = v0 + step;
                float solid_angle = cornerSolidAngle(u1, v1) - cornerSolidAngle(u0, v1) -
                                    cornerSolidAngle(u1, v0) + cornerSolidAngle(u0, v0);
                vec3 w = faceDirection(face, 0.5 * (u0 + u1), 0.5 * (v0 + v1));
                // only the light from above the surface reaches it
                if (dot(n, w) > 0.0) {
                    sum += texture(u_sky_small, w).rgb * solid_angle;
                }
            }
        }
    }
    // the hemisphere is 2 pi steradians: the mean radiance over it
    o_color = vec4(sum / (2.0 * kPi), 1.0);
}
