// Numerical stability of the reference solutions under stress: scenes scaled from 1e-3 to 1e4,
// extreme near/far ratios, zero-length normals and degenerate triangles, extreme non-uniform
// scale, Phong exponents 0, 1 and 1000 (pow(0, 0) is undefined in GLSL), HDR light up to the
// half-float limit of 06-bloom's rgba16f targets. The references must produce no NaN or Inf and
// keep their verdicts; renders of multi-pass float labs must be bit-identical across runs and
// across llvmpipe's thread counts. Each case is a temporary course: a lab.json derived from the
// real one, scenes derived from the bundled glTF files, the real reference shaders.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "gl_test_support.h"
#include "grader/metrics/scoring.h"
#include "shaderlab/lab/lab_spec.h"
#include "shaderlab/render/renderer.h"

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

const fs::path kSource = SHADERLAB_SOURCE_DIR;
const fs::path kLabs = kSource / "labs";
const fs::path kReference = kSource / "reference_solutions";

json readJson(const fs::path& p) {
    std::ifstream in(p);
    return json::parse(in);
}

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// A course in a temporary folder: labs/shared copied, scenes written by the test, one lab.
class TempCourse {
  public:
    explicit TempCourse(const std::string& name)
        : root_(fs::temp_directory_path() /
                ("shaderlab_stability_" + name + "_" + std::to_string(::getpid()))) {
        fs::remove_all(root_);
        fs::create_directories(root_ / "scenes");
        // Copied, not linked: instructor files must resolve inside the course folder.
        fs::copy(kLabs / "shared", root_ / "shared", fs::copy_options::recursive);
    }
    ~TempCourse() {
        std::error_code ec;
        fs::remove_all(root_, ec);
    }
    TempCourse(const TempCourse&) = delete;
    TempCourse& operator=(const TempCourse&) = delete;
    const fs::path& root() const { return root_; }

    // The bundled scene `from` (.gltf with one .bin), changed by `edit`, as scenes/<to>.gltf;
    // `edit_bin` may change the binary buffer.
    void writeScene(const std::string& from, const std::string& to, const std::function<void(json&)>& edit,
                    const std::function<void(const json&, std::string&)>& edit_bin = {}) {
        json gltf = readJson(kLabs / "scenes" / (from + ".gltf"));
        std::string bin = slurp(kLabs / "scenes" / gltf["buffers"][0]["uri"].get<std::string>());
        edit(gltf);
        if (edit_bin) edit_bin(gltf, bin);
        gltf["buffers"][0]["uri"] = to + ".bin";
        std::ofstream(root_ / "scenes" / (to + ".gltf")) << gltf.dump(1);
        std::ofstream(root_ / "scenes" / (to + ".bin"), std::ios::binary) << bin;
    }

    // labs/<lab> (its instructor shaders and lab.json) with the scenes replaced, and one goal
    // over every scene and graded pass.
    shaderlab::LabSpec writeLab(const std::string& lab, const json& scenes) {
        fs::create_directories(root_ / lab);
        for (const auto& entry : fs::directory_iterator(kLabs / lab))
            if (entry.is_regular_file()) fs::copy_file(entry.path(), root_ / lab / entry.path().filename());
        json spec = readJson(kLabs / lab / "lab.json");
        spec.erase("$schema");
        spec["scenes"] = scenes;
        json names = json::array();
        for (const json& s : scenes) names.push_back(s["name"]);
        spec["goals"] = {{{"id", "all"}, {"title", "everything"}, {"points", 1}, {"scenes", names}}};
        std::ofstream(root_ / lab / "lab.json") << spec.dump(1);
        const shaderlab::LabSpecResult parsed = shaderlab::parseLabSpec((root_ / lab).string());
        EXPECT_TRUE(parsed.ok) << (parsed.errors.empty() ? "" : parsed.errors[0]);
        return parsed.spec;
    }

  private:
    fs::path root_;
};

shaderlab::LabRender renderReference(const shaderlab::LabSpec& spec, bool all_passes = false) {
    std::string err;
    if (!shaderlab::testing::sharedContext(shaderlab::Backend::OSMesa, &err)) {
        ADD_FAILURE() << err;
        return {};
    }
    shaderlab::RenderOptions options;
    options.containment_root = kReference.string();
    options.keep_all_passes = all_passes;
    return shaderlab::renderLab(spec, (kReference / spec.id).string(), options);
}

// NaN and Inf values in every image of a render, named for the failure message.
std::string nonFinite(const shaderlab::LabRender& r) {
    std::string out;
    for (const shaderlab::SceneRender& s : r.scenes) {
        for (const shaderlab::PassImage& p : s.passes) {
            std::size_t nan = 0, inf = 0;
            for (float v : p.color.pixels) {
                nan += std::isnan(v);
                inf += std::isinf(v);
            }
            if (nan || inf)
                out += s.scene + "/" + p.pass + "." + p.attachment + ": " + std::to_string(nan) + " NaN, " +
                       std::to_string(inf) + " Inf; ";
        }
    }
    return out;
}

float largestDifference(const grader::Image& a, const grader::Image& b) {
    float worst = 0.0f;
    for (std::size_t i = 0; i < a.pixels.size() && i < b.pixels.size(); ++i)
        worst = std::max(worst, std::fabs(a.pixels[i] - b.pixels[i]));
    return worst;
}

// The sphere scene with every distance multiplied by `scale`: node translations, the mesh's scale,
// the camera's near and far. Phong without attenuation is scale-invariant, so the image must not
// change beyond float rounding.
void scaledSphere(TempCourse& course, const std::string& name, double scale) {
    course.writeScene("sphere", name, [scale](json& g) {
        for (json& node : g["nodes"]) {
            if (node.contains("translation"))
                for (json& t : node["translation"]) t = t.get<double>() * scale;
            if (node.contains("mesh")) node["scale"] = {scale, scale, scale};
        }
        json& p = g["cameras"][0]["perspective"];
        p["znear"] = p["znear"].get<double>() * scale;
        p["zfar"] = p["zfar"].get<double>() * scale;
    });
}

TEST(Stability, PhongIsTheSameFromAThousandthToTenThousandTimesTheSize) {
    TempCourse course("scale");
    const std::vector<double> scales = {1.0, 1e-3, 1e-2, 1e2, 1e4};
    json scenes = json::array();
    for (std::size_t i = 0; i < scales.size(); ++i) {
        scaledSphere(course, "sphere_" + std::to_string(i), scales[i]);
        scenes.push_back({{"name", "scale_" + std::to_string(i)},
                          {"file", "scenes/sphere_" + std::to_string(i) + ".gltf"}});
    }
    const shaderlab::LabRender r = renderReference(course.writeLab("01-phong", scenes));
    ASSERT_EQ(r.status, shaderlab::RenderStatus::Ok) << r.message;
    EXPECT_EQ(nonFinite(r), "");
    const grader::Image& unit = r.scenes[0].passes.back().color;
    for (std::size_t i = 1; i < scales.size(); ++i) {
        const grader::Image& img = r.scenes[i].passes.back().color;
        const float diff = largestDifference(unit, img);
        std::printf("scale %g: largest difference from scale 1: %g\n", scales[i], static_cast<double>(diff));
        EXPECT_LE(diff, 2.0f / 255.0f) << "scale " << scales[i];
        const grader::ImageVerdict v =
            grader::judgeImage(unit, r.scenes[0].passes.back().coverage, img,
                               r.scenes[i].passes.back().coverage, grader::Thresholds{});
        EXPECT_TRUE(v.passed) << "scale " << scales[i] << ": " << (v.reasons.empty() ? "" : v.reasons[0]);
    }
}

// Near and far planes from 1e-4 / 1e4 (ratio 1e8) to 1 / 10 on the self-occluding torus knot:
// with a 32-bit float depth buffer the image must keep its verdict against the fitted planes.
TEST(Stability, ExtremeNearFarRatiosKeepTheVerdict) {
    TempCourse course("near_far");
    const std::vector<std::pair<double, double>> planes = {
        {0.5, 20.0}, {1e-2, 1e3}, {1e-3, 1e4}, {1e-4, 1e4}};
    json scenes = json::array();
    for (std::size_t i = 0; i < planes.size(); ++i)
        scenes.push_back({{"name", "planes_" + std::to_string(i)},
                          {"file", "scenes/torus_knot.glb"},
                          {"camera",
                           {{"position", {0.0, 1.0, 6.0}},
                            {"target", {0.0, 0.0, 0.0}},
                            {"near", planes[i].first},
                            {"far", planes[i].second}}}});
    fs::copy_file(kLabs / "scenes" / "torus_knot.glb", course.root() / "scenes" / "torus_knot.glb");
    const shaderlab::LabRender r = renderReference(course.writeLab("01-phong", scenes));
    ASSERT_EQ(r.status, shaderlab::RenderStatus::Ok) << r.message;
    EXPECT_EQ(nonFinite(r), "");
    const shaderlab::PassImage& base = r.scenes[0].passes.back();
    grader::Thresholds lab_thresholds;  // 01-phong's: 30 dB, SSIM 0.95, FLIP 0.05, 1 % at 0.05
    for (std::size_t i = 1; i < planes.size(); ++i) {
        const shaderlab::PassImage& img = r.scenes[i].passes.back();
        const grader::ImageVerdict v =
            grader::judgeImage(base.color, base.coverage, img.color, img.coverage, lab_thresholds);
        std::printf("near %g far %g (ratio %g): PSNR %.1f dB, mismatch %.4f\n", planes[i].first,
                    planes[i].second, planes[i].second / planes[i].first, v.covered.psnr_db,
                    v.covered.mismatch_fraction);
        EXPECT_TRUE(v.passed) << "near " << planes[i].first << " far " << planes[i].second << ": "
                              << (v.reasons.empty() ? "" : v.reasons[0]);
    }
}

// Zero-length normals (every seventh vertex), degenerate triangles (every fifth collapsed onto
// its first corner) and an extreme non-uniform scale: the loader and the reference keep every
// pixel finite.
TEST(Stability, ZeroNormalsDegenerateTrianglesAndExtremeNonUniformScaleStayFinite) {
    TempCourse course("normals");
    course.writeScene(
        "sphere", "broken_sphere", [](json&) {},
        [](const json& g, std::string& bin) {
            const json& prim = g["meshes"][0]["primitives"][0];
            auto view_of = [&](int accessor) {
                const json& a = g["accessors"][accessor];
                const json& v = g["bufferViews"][a["bufferView"].get<int>()];
                return std::make_tuple(v.value("byteOffset", 0) + a.value("byteOffset", 0),
                                       a["count"].get<int>(), a["componentType"].get<int>());
            };
            const auto [normal_offset, normal_count, normal_type] =
                view_of(prim["attributes"]["NORMAL"].get<int>());
            ASSERT_EQ(normal_type, 5126);  // FLOAT
            for (int i = 0; i < normal_count; i += 7)
                std::fill_n(&bin[static_cast<std::size_t>(normal_offset + i * 12)], 12, '\0');
            const auto [index_offset, index_count, index_type] = view_of(prim["indices"].get<int>());
            ASSERT_EQ(index_type, 5123);  // UNSIGNED_SHORT
            for (int t = 0; t + 2 < index_count; t += 15) {
                // corner 1 := corner 0
                std::copy_n(&bin[static_cast<std::size_t>(index_offset + t * 2)], 2,
                            &bin[static_cast<std::size_t>(index_offset + (t + 1) * 2)]);
            }
        });
    for (const auto& [name, s] : {std::make_pair("squashed", json{1e-4, 1.0, 1.0}),
                                  std::make_pair("stretched", json{0.05, 1.0, 20.0})}) {
        course.writeScene("sphere", name, [&s](json& g) {
            for (json& node : g["nodes"])
                if (node.contains("mesh")) node["scale"] = s;
        });
    }
    json scenes = json::array();
    for (const char* name : {"broken_sphere", "squashed", "stretched"})
        scenes.push_back({{"name", name}, {"file", std::string("scenes/") + name + ".gltf"}});
    const shaderlab::LabRender r = renderReference(course.writeLab("01-phong", scenes));
    ASSERT_EQ(r.status, shaderlab::RenderStatus::Ok) << r.message;
    EXPECT_EQ(nonFinite(r), "");
    // The broken sphere still shades: most of it is lit as a sphere is.
    const grader::Image& img = r.scenes[0].passes.back().color;
    float brightest = 0.0f;
    for (float v : img.pixels) brightest = std::max(brightest, v);
    EXPECT_GT(brightest, 0.5f);
}

// pow(x, 0) with x = 0 is undefined in GLSL (4.60, 8.2: "undefined if x = 0 and y <= 0"); the
// reference must give a number where r.v <= 0 for every exponent a lab may use.
TEST(Stability, PhongExponentsZeroOneAndAThousandGiveNumbers) {
    TempCourse course("shininess");
    fs::copy_file(kLabs / "scenes" / "sphere.gltf", course.root() / "scenes" / "sphere.gltf");
    fs::copy_file(kLabs / "scenes" / "sphere.bin", course.root() / "scenes" / "sphere.bin");
    json scenes = json::array();
    for (double s : {0.0, 1.0, 1000.0})
        scenes.push_back({{"name", "shininess_" + std::to_string(static_cast<int>(s))},
                          {"file", "scenes/sphere.gltf"},
                          // A light behind and to the side: much of the lit sphere has r.v < 0.
                          {"lights", {{{"type", "point"}, {"position", {4.0, 1.0, -2.0}}}}},
                          {"uniforms", {{"u_shininess", s}}}});
    const shaderlab::LabRender r = renderReference(course.writeLab("01-phong", scenes));
    ASSERT_EQ(r.status, shaderlab::RenderStatus::Ok) << r.message;
    EXPECT_EQ(nonFinite(r), "");
}

// 06-bloom's scene and blur targets are rgba16f: light strong enough that the scene reaches a
// few thousand below 65504, the largest half float. Every pass stays finite.
TEST(Stability, BloomUpToTheHalfFloatLimitStaysFinite) {
    TempCourse course("hdr");
    fs::copy_file(kLabs / "scenes" / "cube_flat.gltf", course.root() / "scenes" / "cube_flat.gltf");
    fs::copy_file(kLabs / "scenes" / "cube_flat.bin", course.root() / "scenes" / "cube_flat.bin");
    json scenes = json::array();
    // u_diffuse 0.9 + u_specular 1.5 over a white cube: 2.4 x intensity at most, plus ambient.
    // (0.44 x intensity at the brightest pixel on llvmpipe: 135000 gives about 59000.)
    for (double intensity : {1.0, 1000.0, 135000.0})
        scenes.push_back(
            {{"name", "intensity_" + std::to_string(static_cast<int>(intensity))},
             {"file", "scenes/cube_flat.gltf"},
             {"lights", {{{"type", "point"}, {"position", {3.0, 4.0, 5.0}}, {"intensity", intensity}}}}});
    const shaderlab::LabRender r = renderReference(course.writeLab("06-bloom", scenes), true);
    ASSERT_EQ(r.status, shaderlab::RenderStatus::Ok) << r.message;
    EXPECT_EQ(nonFinite(r), "");
    float peak = 0.0f;
    for (const shaderlab::PassImage& p : r.scenes.back().passes)
        if (p.pass == "scene")
            for (float v : p.color.pixels) peak = std::max(peak, v);
    std::printf("brightest scene value at the strongest light: %g (half-float limit 65504)\n",
                static_cast<double>(peak));
    EXPECT_GT(peak, 50000.0f);  // the test reaches the range it is about
    EXPECT_LE(peak, 65504.0f);
}

// Beyond the limit: GL lets a conversion to half float that overflows give Inf or the largest
// value (GL 4.6, 2.3.4.2 leaves it to the implementation); llvmpipe clamps to 65504, so even a
// light far too strong leaves every pass finite. Checked so docs/performance.md stays true.
TEST(Stability, BloomBeyondTheHalfFloatLimitSaturates) {
    TempCourse course("hdr_over");
    fs::copy_file(kLabs / "scenes" / "cube_flat.gltf", course.root() / "scenes" / "cube_flat.gltf");
    fs::copy_file(kLabs / "scenes" / "cube_flat.bin", course.root() / "scenes" / "cube_flat.bin");
    json scenes = {{{"name", "over"},
                    {"file", "scenes/cube_flat.gltf"},
                    {"lights", {{{"type", "point"}, {"position", {3.0, 4.0, 5.0}}, {"intensity", 1e6}}}}}};
    const shaderlab::LabRender r = renderReference(course.writeLab("06-bloom", scenes), true);
    ASSERT_EQ(r.status, shaderlab::RenderStatus::Ok) << r.message;
    EXPECT_EQ(nonFinite(r), "");
    float peak = 0.0f;
    for (const shaderlab::PassImage& p : r.scenes.back().passes)
        if (p.pass == "scene")
            for (float v : p.color.pixels) peak = std::max(peak, v);
    EXPECT_EQ(peak, 65504.0f);
}

// Through the program, in fresh processes: llvmpipe's thread count and a second run must not
// change a byte of any pass of the float, multi-pass and iterative labs.
std::string renderAllPasses(const std::string& lab, const std::string& env, const std::string& name) {
    const fs::path out = fs::temp_directory_path() /
                         ("shaderlab_stability_threads_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(out);
    const std::string cmd = env + " " + SHADERLAB_CLI + " render " + kReference.string() + " --lab " + lab +
                            " --all-passes --out " + out.string() + " > /dev/null 2>&1";
    EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
    return out.string();
}

class ThreadDeterminism : public ::testing::TestWithParam<std::string> {};

TEST_P(ThreadDeterminism, EveryPassIsTheSameWithOneOrTwoThreadsAndOnEveryRun) {
    const std::string lab = GetParam();
    const std::string one = renderAllPasses(lab, "LP_NUM_THREADS=1", lab + "_1");
    const std::string two = renderAllPasses(lab, "LP_NUM_THREADS=2", lab + "_2");
    const std::string again = renderAllPasses(lab, "LP_NUM_THREADS=2", lab + "_2_again");
    int files = 0;
    for (const auto& entry : fs::recursive_directory_iterator(one)) {
        if (!entry.is_regular_file()) continue;
        const fs::path rel = fs::relative(entry.path(), one);
        const std::string bytes = slurp(entry.path());
        EXPECT_EQ(bytes, slurp(fs::path(two) / rel)) << rel << " differs between 1 and 2 llvmpipe threads";
        EXPECT_EQ(bytes, slurp(fs::path(again) / rel)) << rel << " differs between two runs";
        ++files;
    }
    EXPECT_GT(files, 5);
    for (const std::string& d : {one, two, again}) fs::remove_all(d);
}

INSTANTIATE_TEST_SUITE_P(Labs, ThreadDeterminism,
                         ::testing::Values("06-bloom", "10-particles", "11-shadow-mapping"),
                         [](const ::testing::TestParamInfo<std::string>& param_info) {
                             std::string n = param_info.param;
                             std::replace(n.begin(), n.end(), '-', '_');
                             return n;
                         });

}  // namespace
