// Lab 07-environment-mapping's irradiance pass checked against the integral it stands for. The
// reference solution's irradiance.frag, rendered on llvmpipe by the project's renderer, must give
// for every texel of the 8x8-per-face output cube map what a brute-force sum in double precision
// gives: the cosine-weighted sum over all 6 x 16 x 16 texels of the small sky
// (labs/shared/sky/sky_small_*.png), each weighted by its exact solid angle, divided by pi
// (Ramamoorthi and Hanrahan, "An Efficient Representation for Irradiance Environment Maps",
// SIGGRAPH 2001, define the irradiance map; this is its definition summed directly). And the
// normalisation holds: a sky of constant radiance gives back that constant, in double precision
// and through the shader.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "../framework/tools/analytic_sky.h"
#include "gl_test_support.h"
#include "grader/metrics/image.h"
#include "shaderlab/lab/lab_spec.h"
#include "shaderlab/render/renderer.h"

namespace fs = std::filesystem;

namespace {

constexpr const char* kLab = "07-environment-mapping";
constexpr int kSkySize = 16;  // texels per side of a small sky face
constexpr int kMapSize = 8;   // texels per side of an irradiance map face
constexpr double kPi = 3.14159265358979323846;
const char* const kFaceNames[6] = {"px", "nx", "py", "ny", "pz", "nz"};

// Solid angle of the face rectangle [0, u] x [0, v] of a cube face at distance 1 from the centre:
// the integral of dA / (1 + u^2 + v^2)^(3/2).
double cornerSolidAngle(double u, double v) { return std::atan2(u * v, std::sqrt(1.0 + u * u + v * v)); }

// Exact solid angle of texel (i, j) of an n x n face, by inclusion-exclusion of four corners.
double texelSolidAngle(int i, int j, int n) {
    const double u0 = 2.0 * i / n - 1.0, u1 = 2.0 * (i + 1) / n - 1.0;
    const double v0 = 2.0 * j / n - 1.0, v1 = 2.0 * (j + 1) / n - 1.0;
    return cornerSolidAngle(u1, v1) - cornerSolidAngle(u0, v1) - cornerSolidAngle(u1, v0) +
           cornerSolidAngle(u0, v0);
}

struct SkyTexel {
    glm::dvec3 direction;  // unit, through the texel's centre
    glm::dvec3 radiance;
    double solid_angle;
};

// Every texel of the six small faces in `dir` (a face image's row j is t = (j + 0.5) / n, as
// analytic_sky.h's faceDirection expects). Empty when a face cannot be read.
std::vector<SkyTexel> readSmallSky(const fs::path& dir, std::string* error) {
    std::vector<SkyTexel> texels;
    for (int f = 0; f < 6; ++f) {
        grader::Image face;
        if (!grader::readPng((dir / (std::string("sky_small_") + kFaceNames[f] + ".png")).string(), &face,
                             error))
            return {};
        if (face.width != kSkySize || face.height != kSkySize || face.channels < 3) {
            *error = std::string("sky_small_") + kFaceNames[f] + ".png is not 16x16 RGB";
            return {};
        }
        for (int j = 0; j < kSkySize; ++j)
            for (int i = 0; i < kSkySize; ++i)
                texels.push_back({shaderlab::sky::faceDirection(f, i, j, kSkySize),
                                  {face.at(i, j, 0), face.at(i, j, 1), face.at(i, j, 2)},
                                  texelSolidAngle(i, j, kSkySize)});
    }
    return texels;
}

// E(n) / pi = (1 / pi) sum_k L_k max(n . w_k, 0) dOmega_k, in double precision.
glm::dvec3 irradianceOverPi(const std::vector<SkyTexel>& sky, const glm::dvec3& n) {
    glm::dvec3 sum(0.0);
    for (const SkyTexel& t : sky)
        sum += t.radiance * (std::max(glm::dot(n, t.direction), 0.0) * t.solid_angle);
    return sum / kPi;
}

// The same sum for a sky of radiance 1 everywhere: what the clamped cosine integrates to, over pi.
double constantSkyOverPi(const glm::dvec3& n) {
    double sum = 0.0;
    for (int f = 0; f < 6; ++f)
        for (int j = 0; j < kSkySize; ++j)
            for (int i = 0; i < kSkySize; ++i)
                sum += std::max(glm::dot(n, shaderlab::sky::faceDirection(f, i, j, kSkySize)), 0.0) *
                       texelSolidAngle(i, j, kSkySize);
    return sum / kPi;
}

// Renders the lab in `lab_dir` (its first scene only) with the reference solution's shaders and
// returns the irradiance pass's image: the six 8x8 faces side by side, rows in GL's order.
grader::Image renderIrradiance(const fs::path& lab_dir, std::string* error) {
    if (!shaderlab::testing::sharedContext(shaderlab::Backend::OSMesa, error)) return {};
    const shaderlab::LabSpecResult parsed = shaderlab::parseLabSpec(lab_dir.string());
    if (!parsed.ok) {
        *error = parsed.errors.empty() ? "lab.json does not parse" : parsed.errors[0];
        return {};
    }
    shaderlab::RenderOptions options;
    options.only_scenes = {parsed.spec.scenes.at(0).name};
    const fs::path reference = fs::path(SHADERLAB_SOURCE_DIR) / "reference_solutions" / kLab;
    const shaderlab::LabRender r = shaderlab::renderLab(parsed.spec, reference.string(), options);
    if (r.status != shaderlab::RenderStatus::Ok || r.scenes.empty()) {
        *error = "render failed: " + r.message;
        return {};
    }
    for (const shaderlab::PassImage& p : r.scenes[0].passes)
        if (p.pass == "irradiance") return p.color;
    *error = "no image of the irradiance pass (is it still graded?)";
    return {};
}

TEST(Irradiance, TexelSolidAnglesCoverTheSphere) {
    double total = 0.0;
    for (int j = 0; j < kSkySize; ++j)
        for (int i = 0; i < kSkySize; ++i) total += 6.0 * texelSolidAngle(i, j, kSkySize);
    EXPECT_NEAR(total, 4.0 * kPi, 1e-12);
}

// The discrete sum's normalisation: for a constant sky, sum max(n.w, 0) dOmega is pi up to the
// error of cutting the hemisphere's rim at texel granularity.
TEST(Irradiance, ConstantSkyGivesBackTheConstantInDoublePrecision) {
    double worst = 0.0;
    for (int f = 0; f < 6; ++f)
        for (int j = 0; j < kMapSize; ++j)
            for (int i = 0; i < kMapSize; ++i)
                worst = std::max(
                    worst,
                    std::abs(constantSkyOverPi(shaderlab::sky::faceDirection(f, i, j, kMapSize)) - 1.0));
    std::printf("constant sky, double precision: max |E/pi - 1| = %.3g\n", worst);
    EXPECT_LT(worst, 1e-3);
}

TEST(Irradiance, ReferenceMatchesTheBruteForceSumInDoublePrecision) {
    std::string error;
    const std::vector<SkyTexel> sky =
        readSmallSky(fs::path(SHADERLAB_SOURCE_DIR) / "labs" / "shared" / "sky", &error);
    ASSERT_EQ(sky.size(), 6u * kSkySize * kSkySize) << error;
    const grader::Image strip = renderIrradiance(fs::path(SHADERLAB_SOURCE_DIR) / "labs" / kLab, &error);
    ASSERT_EQ(strip.width, 6 * kMapSize) << error;
    ASSERT_EQ(strip.height, kMapSize);

    double worst = 0.0;
    int worst_face = 0, worst_i = 0, worst_j = 0;
    for (int f = 0; f < 6; ++f)
        for (int j = 0; j < kMapSize; ++j)
            for (int i = 0; i < kMapSize; ++i) {
                const glm::dvec3 want =
                    irradianceOverPi(sky, shaderlab::sky::faceDirection(f, i, j, kMapSize));
                for (int c = 0; c < 3; ++c) {
                    const double diff = std::abs(strip.at(f * kMapSize + i, j, c) - want[c]);
                    if (diff > worst) {
                        worst = diff;
                        worst_face = f;
                        worst_i = i;
                        worst_j = j;
                    }
                }
            }
    std::printf("irradiance map vs double-precision sum: max abs difference %.3g (face %s, texel %d,%d)\n",
                worst, kFaceNames[worst_face], worst_i, worst_j);
    EXPECT_LT(worst, 1e-3);
}

// Through the shader: the lab copied into a temporary labs root whose small sky is one grey.
TEST(Irradiance, ReferenceGivesBackAConstantSky) {
    const fs::path source = fs::path(SHADERLAB_SOURCE_DIR) / "labs";
    const fs::path root = fs::temp_directory_path() / ("shaderlab_irradiance_" + std::to_string(::getpid()));
    fs::remove_all(root);
    fs::create_directories(root / "labs" / kLab);
    for (const auto& entry : fs::directory_iterator(source / kLab))
        if (entry.is_regular_file())
            fs::copy_file(entry.path(), root / "labs" / kLab / entry.path().filename());
    fs::copy(source / "shared", root / "labs" / "shared", fs::copy_options::recursive);
    fs::copy(source / "scenes", root / "labs" / "scenes", fs::copy_options::recursive);
    const float grey = 153.0f / 255.0f;  // exactly representable in an 8-bit PNG
    std::string error;
    for (const char* face : kFaceNames)
        ASSERT_TRUE(grader::writePng(
            grader::Image(kSkySize, kSkySize, 3, grey),
            (root / "labs" / "shared" / "sky" / (std::string("sky_small_") + face + ".png")).string(),
            &error))
            << error;

    const grader::Image strip = renderIrradiance(root / "labs" / kLab, &error);
    fs::remove_all(root);
    ASSERT_EQ(strip.width, 6 * kMapSize) << error;
    double worst = 0.0;
    for (int f = 0; f < 6; ++f)
        for (int j = 0; j < kMapSize; ++j)
            for (int i = 0; i < kMapSize; ++i)
                for (int c = 0; c < 3; ++c)
                    worst = std::max(worst, std::abs(double(strip.at(f * kMapSize + i, j, c)) - grey));
    std::printf("constant sky %.4f through the shader: max abs difference %.3g\n", grey, worst);
    EXPECT_LT(worst, 1e-3);
}

}  // namespace
