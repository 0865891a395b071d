// The Phong lab end to end: the reference solution rendered through the framework agrees with the
// Phong model evaluated on the CPU by ray-casting the ideal sphere; rendering is deterministic,
// independent of llvmpipe's thread count, and the same through both backends.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "gl_test_support.h"
#include "shaderlab/lab/lab_spec.h"
#include "shaderlab/render/renderer.h"
#include "shaderlab/scene/gltf_loader.h"

namespace fs = std::filesystem;

namespace {

using shaderlab::Backend;

const std::string kLabs = std::string(SHADERLAB_SOURCE_DIR) + "/labs";
const std::string kReference = std::string(SHADERLAB_SOURCE_DIR) + "/reference_solutions/01-phong";

shaderlab::LabSpec phongSpec() {
    const auto parsed = shaderlab::parseLabSpec(kLabs + "/01-phong");
    EXPECT_TRUE(parsed.ok) << (parsed.errors.empty() ? "" : parsed.errors[0]);
    return parsed.spec;
}

float uniformFloat(const shaderlab::UniformList& list, const std::string& name) {
    for (const auto& u : list)
        if (u.name == name) return u.value.get<float>();
    ADD_FAILURE() << name << " is not set in lab.json";
    return 0.0f;
}

class PhongRender : public ::testing::Test {
  protected:
    void SetUp() override {
        std::string err;
        if (!shaderlab::testing::sharedContext(Backend::OSMesa, &err)) FAIL() << err;
    }
};

// Casts a ray through every pixel centre of the "sphere" scene, intersects the ideal sphere the
// mesh approximates, evaluates the Phong model exactly as the lab's README states it, and
// compares with the rendered image away from the silhouette.
TEST_F(PhongRender, ReferenceMatchesPhongModelOnCpu) {
    shaderlab::LabSpec spec = phongSpec();
    shaderlab::RenderOptions opts;
    opts.only_scenes = {"sphere"};
    const auto r = shaderlab::renderLab(spec, kReference, opts);
    ASSERT_EQ(r.status, shaderlab::RenderStatus::Ok) << r.message;
    ASSERT_EQ(r.scenes.size(), 1u);
    const grader::Image& img = r.scenes[0].passes.back().color;

    shaderlab::Scene scene;
    const auto load = shaderlab::loadGltfScene(kLabs + "/scenes/sphere.gltf", &scene);
    ASSERT_TRUE(load.ok) << load.error;
    ASSERT_FALSE(scene.lights.empty());
    const glm::vec3 centre = (scene.bounds_min + scene.bounds_max) * 0.5f;
    const float radius = (scene.bounds_max.x - scene.bounds_min.x) * 0.5f;
    const shaderlab::Camera& cam = scene.camera;
    const glm::vec3 forward = glm::normalize(cam.target - cam.position);
    const glm::vec3 right = glm::normalize(glm::cross(forward, cam.up));
    const glm::vec3 up = glm::cross(right, forward);
    const float tan_half = std::tan(glm::radians(cam.fov_y_deg) * 0.5f);
    const float aspect = static_cast<float>(img.width) / static_cast<float>(img.height);
    const glm::vec3 base = glm::vec3(scene.materials.at(0).base_color);
    const shaderlab::Light& light = scene.lights[0];
    const glm::vec3 light_color = light.color * light.intensity;
    const auto& u = spec.passes[0].uniforms;
    const float ka = uniformFloat(u, "u_ambient"), kd = uniformFloat(u, "u_diffuse");
    const float ks = uniformFloat(u, "u_specular"), shininess = uniformFloat(u, "u_shininess");

    double sum_err = 0.0;
    float max_err = 0.0f;
    int counted = 0;
    for (int y = 0; y < img.height; ++y) {
        for (int x = 0; x < img.width; ++x) {
            const float ndc_x = (2.0f * (x + 0.5f) / img.width - 1.0f) * tan_half * aspect;
            const float ndc_y = (1.0f - 2.0f * (y + 0.5f) / img.height) * tan_half;
            const glm::vec3 dir = glm::normalize(forward + ndc_x * right + ndc_y * up);
            const glm::vec3 oc = cam.position - centre;
            const float b = glm::dot(oc, dir);
            const float disc = b * b - (glm::dot(oc, oc) - radius * radius);
            // Stay clear of the silhouette, where the tessellated mesh and the sphere differ.
            if (disc < 0.05f * radius * radius) continue;
            const glm::vec3 p = cam.position + (-b - std::sqrt(disc)) * dir;
            const glm::vec3 n = glm::normalize(p - centre);
            const glm::vec3 v = glm::normalize(cam.position - p);
            const glm::vec3 l = glm::normalize(light.position - p);
            glm::vec3 expected = ka * base;
            const float ndl = glm::dot(n, l);
            if (ndl > 0.0f) {
                const glm::vec3 rr = -l - 2.0f * glm::dot(n, -l) * n;
                expected += light_color *
                            (kd * ndl * base + ks * std::pow(std::max(glm::dot(rr, v), 0.0f), shininess));
            }
            for (int c = 0; c < 3; ++c) {
                const float e = std::fabs(img.at(x, y, c) - expected[c]);
                sum_err += e;
                max_err = std::max(max_err, e);
            }
            ++counted;
        }
    }
    ASSERT_GT(counted, img.width * img.height / 20) << "the sphere should cover a good part of the frame";
    std::printf("Phong on the CPU vs rendered, %d interior pixels: mean abs error %.5f, max %.4f\n", counted,
                sum_err / (3.0 * counted), static_cast<double>(max_err));
    EXPECT_LT(sum_err / (3.0 * counted), 0.01);
    EXPECT_LT(max_err, 0.1f);

    // The background is exactly the clear colour, and nothing outside the sphere is covered.
    const auto& clear = *spec.passes[0].state.clear_colors[0];
    EXPECT_FLOAT_EQ(img.at(0, 0, 0), clear.r);
    EXPECT_FLOAT_EQ(img.at(0, 0, 2), clear.b);
    EXPECT_EQ(r.scenes[0].passes.back().coverage[0], 0);
}

TEST_F(PhongRender, StarterDiffersAndReferenceIsRepeatable) {
    shaderlab::LabSpec spec = phongSpec();
    shaderlab::RenderOptions opts;
    opts.only_scenes = {"torus"};
    const auto a = shaderlab::renderLab(spec, kReference, opts);
    const auto b = shaderlab::renderLab(spec, kReference, opts);
    const auto starter = shaderlab::renderLab(spec, kLabs + "/01-phong", opts);
    ASSERT_EQ(a.status, shaderlab::RenderStatus::Ok) << a.message;
    ASSERT_EQ(starter.status, shaderlab::RenderStatus::Ok) << starter.message;
    EXPECT_EQ(a.scenes[0].passes[0].color.pixels, b.scenes[0].passes[0].color.pixels);
    EXPECT_NE(a.scenes[0].passes[0].color.pixels, starter.scenes[0].passes[0].color.pixels);
    // Same geometry, so the same coverage.
    EXPECT_EQ(a.scenes[0].passes[0].coverage, starter.scenes[0].passes[0].coverage);
}

// The float images themselves, before any PNG rounding, agree between the two backends.
TEST(PhongBackends, OsmesaAndEglAgreeInFloat) {
    std::string err;
    const shaderlab::LabSpec spec = phongSpec();
    ASSERT_NE(shaderlab::testing::sharedContext(Backend::OSMesa, &err), nullptr) << err;
    const auto a = shaderlab::renderLab(spec, kReference);
    ASSERT_NE(shaderlab::testing::sharedContext(Backend::Egl, &err), nullptr) << err;
    const auto b = shaderlab::renderLab(spec, kReference);
    ASSERT_EQ(a.status, shaderlab::RenderStatus::Ok) << a.message;
    ASSERT_EQ(b.status, shaderlab::RenderStatus::Ok) << b.message;
    ASSERT_EQ(a.scenes.size(), b.scenes.size());
    float max_diff = 0.0f;
    for (std::size_t s = 0; s < a.scenes.size(); ++s) {
        const auto& pa = a.scenes[s].passes.back().color.pixels;
        const auto& pb = b.scenes[s].passes.back().color.pixels;
        ASSERT_EQ(pa.size(), pb.size());
        for (std::size_t i = 0; i < pa.size(); ++i) max_diff = std::max(max_diff, std::fabs(pa[i] - pb[i]));
    }
    std::printf("largest per-channel difference osmesa vs egl over %zu scenes: %g\n", a.scenes.size(),
                static_cast<double>(max_diff));
    EXPECT_LE(max_diff, 1.0f / 512.0f);  // well inside one 8-bit step
}

// Through the program, in fresh processes: thread count and backend must not change a byte.
std::string renderToDir(const std::string& env, const std::string& backend, const std::string& name) {
    const fs::path out = fs::temp_directory_path() / ("shaderlab_determinism_" + name);
    fs::remove_all(out);
    const std::string cmd = env + " " + SHADERLAB_CLI + " render " + std::string(SHADERLAB_SOURCE_DIR) +
                            "/reference_solutions --lab 01-phong --backend " + backend + " --out " +
                            out.string() + " > /dev/null 2>&1";
    EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
    return out.string();
}

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

TEST(PhongDeterminism, ThreadCountAndBackendDoNotChangeAByte) {
    const std::string base = renderToDir("", "osmesa", "default");
    const std::string one = renderToDir("LP_NUM_THREADS=1", "osmesa", "one_thread");
    const std::string egl = renderToDir("", "egl", "egl");
    int files = 0;
    for (const auto& entry : fs::directory_iterator(fs::path(base) / "01-phong")) {
        const std::string name = entry.path().filename().string();
        const std::string bytes = slurp(entry.path());
        EXPECT_EQ(bytes, slurp(fs::path(one) / "01-phong" / name))
            << name << " differs with LP_NUM_THREADS=1";
        EXPECT_EQ(bytes, slurp(fs::path(egl) / "01-phong" / name))
            << name << " differs between osmesa and egl";
        ++files;
    }
    EXPECT_EQ(files, static_cast<int>(phongSpec().scenes.size()));
}

}  // namespace
