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

vec3 direction(int face, vec2 st) { return kMajor[face] + st.x * kAlongS[face] + st.y * kAlongT[face]; }

void main() {
    vec3 n = normalize(direction(u_cube_face, 2.0 * v_uv - 1.0));
    float texel_area = (2.0 / float(N)) * (2.0 / float(N));

    vec3 sum = vec3(0.0);
    float total_weight = 0.0;
    for (int face = 0; face < 6; ++face) {
        for (int j = 0; j < N; ++j) {
            for (int i = 0; i < N; ++i) {
                vec2 st = (vec2(i, j) + 0.5) * (2.0 / float(N)) - 1.0;
                vec3 w = direction(face, st);
                float len2 = dot(w, w);  // 1 + u^2 + v^2
                float solid_angle = texel_area / (len2 * sqrt(len2));
                float weight = max(dot(n, w) / sqrt(len2), 0.0) * solid_angle;
                sum += weight * texture(u_sky_small, w).rgb;
                total_weight += weight;
            }
        }
    }
    o_color = vec4(sum / total_weight, 1.0);
}
