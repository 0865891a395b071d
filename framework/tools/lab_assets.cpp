// The labs' own generated assets (lab_assets.h). One lab has them today, 12-normal-mapping:
//
// - bricks_height.png: a tileable height field (8-bit grey, 0 = mortar, white = highest), running
//   bond bricks whose faces bulge like pillows and tilt a little, each its own way;
// - bricks_normal.png: the tangent-space normal map of that height field. The normal is
//   n = normalize(-k dh/dx, -k dh/dy, 1) from central differences of the height (one texel either
//   side, wrapping), with x to the right and y up the image, and stored as n * 0.5 + 0.5 rounded
//   to 8 bits: the convention glTF 2.0 gives normalTexture ("+X is right and +Y is up. +Z points
//   toward the viewer", 3.9.3), also called OpenGL style (DirectX style flips green);
// - meshes with TANGENT (VEC4, xyz unit, w = +1 or -1, glTF 2.0 3.7.2.1) from Lengyel's method
//   (computeTangents in scene_writer.h): a quad and a sphere whose left half (x < 0) has its
//   texture mirrored, u running the other way, so w = -1 there, as an artist mirrors half a model
//   to reuse its texture; and the same sphere unmirrored (w = +1 everywhere) under a turned and
//   under a stretched node, for judging the tangent frame's transform to world space;
// - bent_quad: the mirrored quad with its normals bent outward as on a shallow dome and its flat
//   tangents kept, a tangent baked for other normals: the one mesh whose TANGENT is not
//   perpendicular to NORMAL, for judging the step that makes it so again (Gram-Schmidt).
//
// The meshes carry no material textures: the lab feeds the map to its shaders through lab.json
// `inputs` ("texture": "assets/bricks_normal.png").
#include "lab_assets.h"

#include <string>
#include <vector>

#include "grader/metrics/image.h"
#include "scene_writer.h"

namespace shaderlab::scenegen {
namespace {

// ---- the height field and its normal map --------------------------------------------------------

constexpr int kMapSize = 256;     // texels per side; the pattern tiles
constexpr int kBrickRows = 4;     // rows of bricks per tile
constexpr int kBricksPerRow = 2;  // bricks per row; odd rows are shifted by half a brick
constexpr double kMortar = 8.0;   // width of the mortar joints, texels
constexpr double kRelief = 24.0;  // k: the height of a brick's crown, in texels

// Heights in [0, 1.1] at texel centres, row 0 at the top of the image.
std::vector<double> bricksHeight() {
    const double brick_w = double(kMapSize) / kBricksPerRow, brick_h = double(kMapSize) / kBrickRows;
    std::vector<double> h(static_cast<std::size_t>(kMapSize * kMapSize), 0.0);
    for (int y = 0; y < kMapSize; ++y) {
        const int row = y / static_cast<int>(brick_h);
        for (int x = 0; x < kMapSize; ++x) {
            const double xs = x + 0.5 + (row % 2 == 1 ? 0.5 * brick_w : 0.0);
            const int column = static_cast<int>(xs / brick_w) % kBricksPerRow;
            const double a = (std::fmod(xs, brick_w) - 0.5 * kMortar) / (brick_w - kMortar);
            const double b = (std::fmod(y + 0.5, brick_h) - 0.5 * kMortar) / (brick_h - kMortar);
            if (a <= 0.0 || a >= 1.0 || b <= 0.0 || b >= 1.0) continue;  // mortar
            // A pillow, (sin(pi a) sin(pi b))^0.4: full in the middle, steep at the edges.
            const double pillow = std::pow(std::sin(kPi * a) * std::sin(kPi * b), 0.4);
            // Each brick leans its own way: a tilt from its row and column, the same every run.
            const int id = row * kBricksPerRow + column;
            const double tilt_x = 0.18 * std::sin(2.1 * id + 0.7), tilt_y = 0.14 * std::cos(1.7 * id + 0.3);
            h[static_cast<std::size_t>(y * kMapSize + x)] =
                pillow * (1.0 + tilt_x * (a - 0.5) + tilt_y * (0.5 - b));
        }
    }
    return h;
}

// The byte a value in [-1, 1] is stored as: n * 0.5 + 0.5, rounded to 8 bits. The image holds
// byte / 255 exactly, so writePng stores that byte.
float encodeUnit(double n) {
    const double byte = std::round((n * 0.5 + 0.5) * 255.0);
    return static_cast<float>(std::min(255.0, std::max(0.0, byte)) / 255.0);
}

grader::Image normalMap(const std::vector<double>& h) {
    grader::Image img(kMapSize, kMapSize, 3);
    const auto at = [&h](int x, int y) {
        x = (x + kMapSize) % kMapSize;
        y = (y + kMapSize) % kMapSize;
        return h[static_cast<std::size_t>(y * kMapSize + x)];
    };
    for (int y = 0; y < kMapSize; ++y) {
        for (int x = 0; x < kMapSize; ++x) {
            const double dh_dx = 0.5 * (at(x + 1, y) - at(x - 1, y));
            const double dh_dy = 0.5 * (at(x, y - 1) - at(x, y + 1));  // up the image: row y - 1
            const glm::dvec3 n = glm::normalize(glm::dvec3(-kRelief * dh_dx, -kRelief * dh_dy, 1.0));
            for (int c = 0; c < 3; ++c) img.at(x, y, c) = encodeUnit(n[c]);
        }
    }
    return img;
}

grader::Image heightImage(const std::vector<double>& h) {
    grader::Image img(kMapSize, kMapSize, 1);
    for (std::size_t i = 0; i < h.size(); ++i)
        img.pixels[i] = static_cast<float>(std::round(std::min(1.0, h[i] / 1.1) * 255.0) / 255.0);
    return img;
}

bool writeImage(const grader::Image& img, const fs::path& file) {
    std::string error;
    if (!grader::writePng(img, file.string(), &error)) {
        std::fprintf(stderr, "shaderlab_make_scenes: %s\n", error.c_str());
        return false;
    }
    std::printf("wrote %s\n", file.string().c_str());
    return true;
}

// ---- meshes with tangents -----------------------------------------------------------------------

void append(Geometry* to, const Geometry& from) {
    const auto base = static_cast<std::uint32_t>(to->vertices.size());
    to->vertices.insert(to->vertices.end(), from.vertices.begin(), from.vertices.end());
    for (std::uint32_t i : from.indices) to->indices.push_back(base + i);
}

// The quad x, y in [-1, 1] facing +Z. u = |x| (the left half mirrors the right), v = 1 - y, so the
// texture stands upright and tiles once across each half and twice up. Each half has its own
// vertices along x = 0, where the tangent turns round.
Geometry mirroredQuad(int cols, int rows) {
    Geometry g;
    for (const double side : {1.0, -1.0}) {
        Geometry half;
        for (int i = 0; i <= rows; ++i) {
            const double y = 1.0 - 2.0 * i / rows;
            for (int j = 0; j <= cols; ++j) {
                const double x = side * double(j) / cols;
                half.vertices.push_back({{x, y, 0.0}, {0.0, 0.0, 1.0}, {std::abs(x), 1.0 - y}});
            }
        }
        addGridTriangles(&half, rows, cols, false);
        append(&g, half);
    }
    computeTangents(&g);
    g.write_tangents = true;
    return g;
}

// mirroredQuad(4, 8) with each normal bent outward to normalize(0.6 x, 0.6 y, 1), its tangents
// left as they were computed for the flat normals, (+-1, 0, 0): up to 31 degrees from
// perpendicular at the middle of the left and right edges, none along x = 0. Interpolation does
// not bring them back, so a frame that skips the Gram-Schmidt step (or gets it wrong) turns the
// probe elsewhere on this mesh, and on no other mesh of the lab.
Geometry bentQuad() {
    Geometry g = mirroredQuad(4, 8);
    for (Vertex& v : g.vertices)
        v.normal = glm::normalize(glm::dvec3(0.6 * v.position.x, 0.6 * v.position.y, 1.0));
    return g;
}

// Part of a UV sphere (as uvSphere: phi from +Z towards +X, theta from the north pole) for phi in
// [phi0, phi1], with u = u_of_phi(phi) and v = 2 theta / pi, so texels are square at the equator
// when u gains 2 per half turn.
template <typename UOfPhi>
Geometry sphereSlice(double phi0, double phi1, int segments, int rings, UOfPhi u_of_phi) {
    Geometry g;
    for (int i = 0; i <= rings; ++i) {
        const double theta = kPi * i / rings;
        for (int j = 0; j <= segments; ++j) {
            const double phi = phi0 + (phi1 - phi0) * j / segments;
            const glm::dvec3 n(std::sin(theta) * std::sin(phi), std::cos(theta),
                               std::sin(theta) * std::cos(phi));
            g.vertices.push_back({n, n, glm::dvec2(u_of_phi(phi), 2.0 * theta / kPi)});
        }
    }
    addGridTriangles(&g, rings, segments, true);
    return g;
}

// The unit sphere with u = 2 phi / pi on the right half (x >= 0) and mirrored on the left
// (u = 2 (2 pi - phi) / pi): the mirror seams run down the front (phi = 0) and the back.
Geometry mirroredSphere() {
    Geometry g = sphereSlice(0.0, kPi, 32, 32, [](double phi) { return 2.0 * phi / kPi; });
    append(&g, sphereSlice(kPi, 2.0 * kPi, 32, 32, [](double phi) { return 2.0 * (2.0 * kPi - phi) / kPi; }));
    computeTangents(&g);
    g.write_tangents = true;
    return g;
}

// The unit sphere with u = 2 phi / pi all round: w = +1 everywhere.
Geometry plainSphere() {
    Geometry g = sphereSlice(0.0, 2.0 * kPi, 64, 32, [](double phi) { return 2.0 * phi / kPi; });
    computeTangents(&g);
    g.write_tangents = true;
    return g;
}

const glm::dvec4 kBrickRed(0.72, 0.36, 0.24, 1.0);

double round6(double v) { return std::round(v * 1e6) / 1e6 + 0.0; }

bool writeMesh(const fs::path& dir, const std::string& name, const Geometry& g, const glm::dvec3& eye,
               const glm::dvec3& scale = glm::dvec3(1.0),
               const glm::dquat& turn = glm::dquat(1.0, 0.0, 0.0, 0.0)) {
    SceneWriter w;
    const int mat = w.addMaterial("bricks", kBrickRed);
    const int n = w.addMeshNode(name, w.addMesh(name, g, mat, kUShort, Layout::Separate));
    if (scale != glm::dvec3(1.0)) w.node(n).scale = {scale.x, scale.y, scale.z};
    if (turn != glm::dquat(1.0, 0.0, 0.0, 0.0))
        w.node(n).rotation = {round6(turn.x), round6(turn.y), round6(turn.z), round6(turn.w)};
    w.addCamera(eye, {0.0, 0.0, 0.0});
    w.addPointLight({-2.0, 4.0, 5.0}, {1.0, 1.0, 1.0}, 1.0);
    return w.write(dir, name, false);
}

bool writeNormalMappingAssets(const fs::path& dir) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) {
        std::fprintf(stderr, "shaderlab_make_scenes: cannot create %s\n", dir.string().c_str());
        return false;
    }
    const std::vector<double> h = bricksHeight();
    const Geometry sphere = plainSphere();
    // The turned sphere leans 50 degrees about a slanted axis; the stretched one is squashed along
    // its own y and drawn out along x (a normal matrix unlike the model matrix), then turned 35
    // degrees about z, so that neither frame lines up with the world's axes.
    const glm::dquat lean = glm::angleAxis(50.0 * kPi / 180.0, glm::normalize(glm::dvec3(1.0, 0.4, 0.3)));
    const glm::dquat roll = glm::angleAxis(35.0 * kPi / 180.0, glm::dvec3(0.0, 0.0, 1.0));
    return writeImage(heightImage(h), dir / "bricks_height.png") &&
           writeImage(normalMap(h), dir / "bricks_normal.png") &&
           writeMesh(dir, "mirrored_quad", mirroredQuad(4, 8), {0.0, 0.0, 3.2}) &&
           writeMesh(dir, "bent_quad", bentQuad(), {0.0, 0.0, 3.2}) &&
           writeMesh(dir, "mirrored_sphere", mirroredSphere(), {0.0, 0.8, 3.6}) &&
           writeMesh(dir, "turned_sphere", sphere, {0.0, 0.8, 3.6}, glm::dvec3(1.0), lean) &&
           writeMesh(dir, "stretched_sphere", sphere, {0.0, 0.8, 4.4}, {1.8, 0.6, 1.0}, roll);
}

}  // namespace

bool writeLabAssets(const fs::path& labs_dir) {
    return writeNormalMappingAssets(labs_dir / "12-normal-mapping" / "assets");
}

}  // namespace shaderlab::scenegen
