// Sphere tessellation against an analytic ground truth: renders a UV sphere of 6 to 256
// segments with the 01-phong reference shaders (llvmpipe, the grader's path) and compares every
// image with a double-precision CPU ray cast of the same Phong-lit unit sphere (same camera,
// light, material and uniforms as the lab's `sphere` scene would use). Prints one CSV row per
// level: the error (mean and largest absolute error over pixels both cover, PSNR and FLIP over
// the frame, silhouette pixels that disagree) and the time to draw the scene once the mesh is
// uploaded, and the time to load and upload the mesh.
//
//   bench_tessellation <labs_root> <reference_root> [resolution]   (CSV on stdout)
//
// The lab folder it renders is written to a temporary directory: a copy of 01-phong's one pass
// with one scene per level, meshes written as glTF here. It does not judge anything.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "grader/metrics/metrics.h"
#include "shaderlab/gl/gl_context.h"
#include "shaderlab/lab/lab_spec.h"
#include "shaderlab/render/renderer.h"

namespace fs = std::filesystem;

namespace {

constexpr double kPi = 3.14159265358979323846;

// The scene: unit sphere at the origin, camera on +z, one white point light. The material and
// the lighting uniforms are 01-phong's pass defaults.
const glm::dvec3 kEye(0.0, 0.0, 3.2), kLight(3.0, 4.0, 5.0);
const glm::dvec3 kBase(0.8, 0.35, 0.25), kClear(0.05, 0.05, 0.08);
constexpr double kFovYDeg = 45.0, kAmbient = 0.12, kDiffuse = 0.75, kSpecular = 0.6, kShininess = 32.0;

struct MeshData {
    std::vector<float> positions;  // xyz, also the normals (unit sphere)
    std::vector<std::uint32_t> indices;
};

// UV sphere as shaderlab_make_scenes builds it: `segments` around, segments / 2 rings, seam
// vertices doubled, the degenerate triangles at the poles left out, counter-clockwise outside.
MeshData uvSphere(int segments) {
    const int rings = std::max(2, segments / 2);
    MeshData m;
    for (int i = 0; i <= rings; ++i) {
        const double theta = kPi * i / rings;
        for (int j = 0; j <= segments; ++j) {
            const double phi = 2.0 * kPi * j / segments;
            m.positions.push_back(static_cast<float>(std::sin(theta) * std::sin(phi)));
            m.positions.push_back(static_cast<float>(std::cos(theta)));
            m.positions.push_back(static_cast<float>(std::sin(theta) * std::cos(phi)));
        }
    }
    const auto at = [&](int i, int j) { return static_cast<std::uint32_t>(i * (segments + 1) + j); };
    for (int i = 0; i < rings; ++i) {
        for (int j = 0; j < segments; ++j) {
            if (i != 0) m.indices.insert(m.indices.end(), {at(i, j), at(i + 1, j), at(i, j + 1)});
            if (i != rings - 1)
                m.indices.insert(m.indices.end(), {at(i, j + 1), at(i + 1, j), at(i + 1, j + 1)});
        }
    }
    return m;
}

// Writes `<dir>/<name>.gltf` and `.bin`: one mesh, one node, one material.
bool writeGltf(const fs::path& dir, const std::string& name, const MeshData& m) {
    std::vector<char> bin;
    auto append = [&bin](const void* data, std::size_t n) {
        bin.insert(bin.end(), static_cast<const char*>(data), static_cast<const char*>(data) + n);
        while (bin.size() % 4) bin.push_back(0);
    };
    const std::size_t pos_bytes = m.positions.size() * sizeof(float);
    append(m.positions.data(), pos_bytes);
    const std::size_t index_offset = bin.size();
    append(m.indices.data(), m.indices.size() * sizeof(std::uint32_t));
    float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
    for (std::size_t i = 0; i < m.positions.size(); ++i) {
        lo[i % 3] = std::min(lo[i % 3], m.positions[i]);
        hi[i % 3] = std::max(hi[i % 3], m.positions[i]);
    }
    const std::size_t vertices = m.positions.size() / 3;
    nlohmann::json j = {
        {"asset", {{"version", "2.0"}, {"generator", "shaderlab bench_tessellation"}}},
        {"scene", 0},
        {"scenes", {{{"nodes", {0}}}}},
        {"nodes", {{{"mesh", 0}}}},
        {"materials", {{{"pbrMetallicRoughness", {{"baseColorFactor", {kBase.x, kBase.y, kBase.z, 1.0}}}}}}},
        {"meshes",
         {{{"primitives",
            {{{"attributes", {{"POSITION", 0}, {"NORMAL", 0}}}, {"indices", 1}, {"material", 0}}}}}}},
        {"buffers", {{{"uri", name + ".bin"}, {"byteLength", bin.size()}}}},
        {"bufferViews",
         {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", pos_bytes}, {"target", 34962}},
          {{"buffer", 0},
           {"byteOffset", index_offset},
           {"byteLength", m.indices.size() * sizeof(std::uint32_t)},
           {"target", 34963}}}},
        {"accessors",
         {{{"bufferView", 0},
           {"componentType", 5126},
           {"count", vertices},
           {"type", "VEC3"},
           {"min", {lo[0], lo[1], lo[2]}},
           {"max", {hi[0], hi[1], hi[2]}}},
          {{"bufferView", 1}, {"componentType", 5125}, {"count", m.indices.size()}, {"type", "SCALAR"}}}}};
    std::ofstream(dir / (name + ".gltf")) << j.dump(1);
    std::ofstream out(dir / (name + ".bin"), std::ios::binary);
    out.write(bin.data(), static_cast<std::streamsize>(bin.size()));
    return static_cast<bool>(out);
}

// The ground truth: one ray through each pixel centre, the exact sphere, Phong in double.
// Returns RGBA top row first, and coverage.
grader::Image rayCast(int size, std::vector<std::uint8_t>* coverage) {
    grader::Image img(size, size, 4);
    coverage->assign(static_cast<std::size_t>(size) * size, 0);
    const glm::dvec3 forward = glm::normalize(-kEye), right(1.0, 0.0, 0.0), up(0.0, 1.0, 0.0);
    const double t = std::tan(kFovYDeg * kPi / 360.0);
    for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
            const double sx = (2.0 * (x + 0.5) / size - 1.0) * t, sy = (1.0 - 2.0 * (y + 0.5) / size) * t;
            const glm::dvec3 d = glm::normalize(forward + sx * right + sy * up);
            glm::dvec3 c = kClear;
            const double b = glm::dot(kEye, d), disc = b * b - (glm::dot(kEye, kEye) - 1.0);
            if (disc >= 0.0) {
                const glm::dvec3 p = kEye + (-b - std::sqrt(disc)) * d;
                const glm::dvec3 n = glm::normalize(p), v = glm::normalize(kEye - p),
                                 l = glm::normalize(kLight - p);
                c = kAmbient * kBase;
                const double ndl = glm::dot(n, l);
                if (ndl > 0.0) {
                    const glm::dvec3 r = -l - 2.0 * glm::dot(n, -l) * n;
                    c += kDiffuse * ndl * kBase +
                         kSpecular * std::pow(std::max(glm::dot(r, v), 0.0), kShininess);
                }
                (*coverage)[static_cast<std::size_t>(y) * size + x] = 1;
            }
            for (int k = 0; k < 3; ++k) img.at(x, y, k) = static_cast<float>(c[k]);
            img.at(x, y, 3) = 1.0f;
        }
    }
    return img;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: %s <labs_root> <reference_root> [resolution]\n", argv[0]);
        return 2;
    }
    const fs::path labs_root = fs::absolute(argv[1]), reference_root = fs::absolute(argv[2]);
    const int size = argc > 3 ? std::atoi(argv[3]) : 256;
    const std::vector<int> levels = {6, 8, 12, 16, 24, 32, 48, 64, 96, 128, 192, 256};
    const fs::path tmp = fs::temp_directory_path() / ("shaderlab-tess-" + std::to_string(getpid()));
    fs::create_directories(tmp / "scenes");
    fs::create_directories(tmp / "01-phong");
    nlohmann::json lab = nlohmann::json::parse(std::ifstream(labs_root / "01-phong" / "lab.json"));
    lab.erase("$schema");
    lab["resolution"] = {size, size};
    nlohmann::json scenes = nlohmann::json::array();
    const auto scene_of = [&](const std::string& name, int n) {
        return nlohmann::json{
            {"name", name},
            {"file", "scenes/sphere_" + std::to_string(n) + ".gltf"},
            {"camera",
             {{"position", {kEye.x, kEye.y, kEye.z}},
              {"target", {0.0, 0.0, 0.0}},
              {"fov_y_deg", kFovYDeg},
              {"near", 1.0},
              {"far", 10.0}}},
            {"lights", {{{"type", "point"}, {"position", {kLight.x, kLight.y, kLight.z}}}}}};
    };
    // First a scene that takes llvmpipe's compilation of the shader variants at first draw.
    scenes.push_back(scene_of("warm_up", levels.back()));
    for (int n : levels) {
        if (!writeGltf(tmp / "scenes", "sphere_" + std::to_string(n), uvSphere(n))) return 2;
        // Twice: the first run loads and uploads the mesh, the second only draws and reads back.
        for (const char* run : {"load", "draw"})
            scenes.push_back(scene_of("s" + std::to_string(n) + "_" + run, n));
    }
    lab["scenes"] = scenes;
    nlohmann::json names = nlohmann::json::array();
    for (const nlohmann::json& scene : scenes) names.push_back(scene["name"]);
    lab["goals"] = {{{"id", "all"}, {"title", "all"}, {"points", 1}, {"scenes", names}}};
    // The lab's own files (the starter shaders lab.json names), then the new lab.json.
    for (const auto& entry : fs::directory_iterator(labs_root / "01-phong"))
        if (entry.is_regular_file()) fs::copy_file(entry.path(), tmp / "01-phong" / entry.path().filename());
    std::ofstream(tmp / "01-phong" / "lab.json") << lab.dump(1);
    std::error_code ec;

    int rc = 0;
    {
        shaderlab::ContextResult ctx = shaderlab::createHeadlessContext(shaderlab::Backend::OSMesa);
        const shaderlab::LabSpecResult parsed = shaderlab::parseLabSpec((tmp / "01-phong").string());
        if (!ctx.context || !parsed.ok) {
            std::fprintf(stderr, "bench_tessellation: %s%s\n", ctx.error.c_str(),
                         parsed.errors.empty() ? "" : parsed.errors[0].c_str());
            rc = 2;
        } else {
            std::vector<std::uint8_t> truth_cov;
            const grader::Image truth = rayCast(size, &truth_cov);
            shaderlab::RenderOptions options;
            options.containment_root = reference_root.string();
            // Best of five whole-lab runs for the times; the images are the same every run.
            std::vector<double> load_ms(levels.size(), 1e30), draw_ms(levels.size(), 1e30);
            shaderlab::LabRender render;
            for (int rep = 0; rep < 5; ++rep) {
                render = shaderlab::renderLab(parsed.spec, (reference_root / "01-phong").string(), options);
                if (render.status != shaderlab::RenderStatus::Ok) break;
                for (std::size_t i = 0; i < levels.size(); ++i) {
                    load_ms[i] = std::min(load_ms[i], render.scenes[2 * i + 1].render_ms);
                    draw_ms[i] = std::min(draw_ms[i], render.scenes[2 * i + 2].render_ms);
                }
            }
            if (render.status != shaderlab::RenderStatus::Ok) {
                std::fprintf(stderr, "bench_tessellation: %s\n", render.message.c_str());
                rc = 1;
            } else {
                std::printf(
                    "segments,triangles,mean_abs_error,max_abs_error,psnr_db,flip_mean,silhouette_pixels,"
                    "draw_ms,load_and_draw_ms\n");
                for (std::size_t i = 0; i < levels.size(); ++i) {
                    const shaderlab::PassImage& img = render.scenes[2 * i + 2].passes.back();
                    double sum = 0.0, worst = 0.0;
                    std::size_t both = 0, silhouette = 0;
                    for (std::size_t p = 0; p < truth_cov.size(); ++p) {
                        const bool a = truth_cov[p] != 0, b = img.coverage[p] != 0;
                        if (a != b) ++silhouette;
                        if (!(a && b)) continue;
                        ++both;
                        for (int k = 0; k < 3; ++k) {
                            const double e = std::abs(static_cast<double>(img.color.pixels[p * 4 + k]) -
                                                      truth.pixels[p * 4 + k]);
                            sum += e;
                            worst = std::max(worst, e);
                        }
                    }
                    const grader::PsnrResult psnr = grader::computePsnr(truth, img.color);
                    grader::FlipConfig fc;
                    fc.want_map = false;
                    const grader::FlipResult flip = grader::computeFlip(truth, img.color, fc);
                    const int n = levels[i];
                    const int rings = std::max(2, n / 2);
                    std::printf("%d,%d,%.6g,%.6g,%.3f,%.6f,%zu,%.3f,%.3f\n", n, 2 * n * (rings - 1),
                                both ? sum / (3.0 * both) : 0.0, worst, psnr.psnr_db, flip.mean, silhouette,
                                draw_ms[i], load_ms[i]);
                }
            }
        }
    }
    fs::remove_all(tmp, ec);
    return rc;
}
