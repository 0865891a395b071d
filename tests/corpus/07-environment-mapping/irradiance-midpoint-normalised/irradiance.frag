#version 330 core
// Diffuse irradiance map, written with a basis per face and the midpoint rule for the solid
// angle of a texel: dOmega ~ dA / (1 + u^2 + v^2)^(3/2), dA = (2/16)^2. The sum of the weights
// replaces pi as the normaliser, so a constant sky gives back exactly its constant.

in vec2 v_uv;

uniform int u_cube_face;
uniform samplerCube u_sky_small;

out vec4 o_color;

const int N = 16;

// Per face: the major axis, and the axes along which s and t grow (OpenGL's table 8.19).
const vec3 kMajor[6] = vec3[6](vec3(1, 0, 0), vec3(-1, 0, 0), vec3(0, 1, 0), vec3(0, -1, 0), vec3(0, 0, 1),
                               vec3(0, 0, -1));
const vec3 kAlongS[6] = vec3[6](vec3(0, 0, -1), vec3(0, 0, 1), vec3(1, 0, 0), vec3(1, 0, 0), vec3(1, 0, 0),
                                vec3(-1, 0, 0));
const vec3 kAlongT[6] = vec3[6](vec3(0, -1, 0), vec3(0, -1, 0), vec3(0, 0, 1), vec3(0, 0, -1), vec3(0, -1, 0),
                                vec3(0, -1, 0));

vec3 faceDirection(int face, float sc, float tc) { return kMajor[face] + sc * kAlongS[face] + tc * kAlongT[face]; }

// The midpoint rule: the texel's area over the cube of its centre's distance.
float texelSolidAngle(float u0, float v0, float u1, float v1) {
    vec2 c = 0.5 * vec2(u0 + u1, v0 + v1);
    float len2 = 1.0 + dot(c, c);
    return (u1 - u0) * (v1 - v0) / (len2 * sqrt(len2));
}

vec3 irradiance(vec3 n) {
    float step = 2.0 / float(N);
    vec3 sum = vec3(0.0);
    float total_weight = 0.0;
    for (int face = 0; face < 6; ++face) {
        for (int j = 0; j < N; ++j) {
            for (int i = 0; i < N; ++i) {
                vec2 st0 = vec2(i, j) * step - 1.0;
                vec3 w = faceDirection(face, st0.x + 0.5 * step, st0.y + 0.5 * step);
                float weight = max(dot(n, normalize(w)), 0.0) * texelSolidAngle(st0.x, st0.y, st0.x + step, st0.y + step);
                sum += weight * texture(u_sky_small, w).rgb;
                total_weight += weight;
            }
        }
    }
    return sum / total_weight;
}

void main() {
    vec2 st = 2.0 * v_uv - 1.0;
    o_color = vec4(irradiance(normalize(faceDirection(u_cube_face, st.x, st.y))), 1.0);
}
