// The course's sky cube map (labs/shared/sky/): the committed faces are exactly what
// shaderlab_make_sky writes today, and OpenGL, sampling them as a samplerCube along a texel's
// direction, returns that texel of the analytic sky: the tool and the driver agree on the
// cube-map face convention (OpenGL 4.5 core, table 8.19).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "../framework/tools/analytic_sky.h"
#include "gl_test_support.h"
#include "grader/metrics/image.h"
#include "shaderlab/lab/lab_spec.h"
#include "shaderlab/render/renderer.h"

namespace fs = std::filesystem;

namespace {

std::string readBytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

TEST(SkyFresh, CommittedFacesMatchTheGenerator) {
    const fs::path committed = fs::path(SHADERLAB_SOURCE_DIR) / "labs" / "shared" / "sky";
    const fs::path fresh = fs::temp_directory_path() / ("shaderlab_sky_fresh_" + std::to_string(::getpid()));
    fs::remove_all(fresh);
    ASSERT_EQ(std::system((std::string(SHADERLAB_MAKE_SKY) + " " + fresh.string()).c_str()), 0);
    int files = 0;
    for (const auto& entry : fs::directory_iterator(fresh)) {
        ++files;
        EXPECT_EQ(readBytes(entry.path()), readBytes(committed / entry.path().filename()))
            << entry.path().filename()
            << " is stale: run scripts/regenerate_scenes.sh and commit labs/shared/sky/";
    }
    EXPECT_EQ(files, 12);
    fs::remove_all(fresh);
}

TEST(SkyCubeMap, SamplingAlongATexelsDirectionGivesThatTexel) {
    std::string err;
    ASSERT_TRUE(shaderlab::testing::sharedContext(shaderlab::Backend::OSMesa, &err)) << err;
    const fs::path root = fs::temp_directory_path() / ("shaderlab_sky_" + std::to_string(::getpid()));
    fs::remove_all(root);
    const fs::path lab = root / "labs" / "71-sky";
    fs::create_directories(lab);
    fs::copy(fs::path(SHADERLAB_SOURCE_DIR) / "labs" / "shared", root / "labs" / "shared",
             fs::copy_options::recursive);

    // Twelve texels: two per face, one near a corner and one near the middle.
    struct Probe {
        int face, i, j;
    };
    const Probe probes[12] = {{0, 3, 5},   {0, 40, 33}, {1, 60, 2}, {1, 31, 30}, {2, 7, 50},  {2, 33, 33},
                              {3, 12, 18}, {3, 45, 40}, {4, 0, 63}, {4, 20, 41}, {5, 38, 22}, {5, 55, 60}};
    std::string dirs;
    for (const Probe& p : probes) {
        const glm::dvec3 d = shaderlab::sky::faceDirection(p.face, p.i, p.j, 64);
        dirs += std::string(dirs.empty() ? "" : ", ") + "[" + std::to_string(d.x) + ", " +
                std::to_string(d.y) + ", " + std::to_string(d.z) + "]";
    }
    std::ofstream(lab / "fullscreen.vert")
        << "#version 330 core\nlayout(location = 0) in vec3 a_position;\n"
           "layout(location = 2) in vec2 a_texcoord;\nout vec2 v_uv;\n"
           "void main() { v_uv = a_texcoord; gl_Position = vec4(a_position, 1.0); }\n";
    std::ofstream(lab / "probe.frag")
        << "#version 330 core\nin vec2 v_uv;\nuniform samplerCube u_sky;\n"
           "uniform vec3 u_dirs[12];\nout vec4 o_color;\n"
           "void main() { o_color = texture(u_sky, u_dirs[int(v_uv.x * 12.0)]); }\n";
    std::ofstream(lab / "lab.json") << R"({"schema": 2, "id": "71-sky", "resolution": [12, 1], "passes": [
        {"name": "probe", "program": {"vertex": "fullscreen.vert", "fragment": "probe.frag"}, "draw": "fullscreen",
         "inputs": {"u_sky": {"cube": "shared/sky/sky_{face}.png", "filter": "nearest"}},
         "uniforms": {"u_dirs": [)" << dirs
                                    << R"(]}}], "scenes": [{"name": "s"}]})";
    const shaderlab::LabSpecResult parsed = shaderlab::parseLabSpec(lab.string());
    ASSERT_TRUE(parsed.ok) << (parsed.errors.empty() ? "" : parsed.errors[0]);
    const shaderlab::LabRender r = shaderlab::renderLab(parsed.spec, lab.string());
    ASSERT_EQ(r.status, shaderlab::RenderStatus::Ok) << r.message;
    const grader::Image& img = r.scenes.at(0).passes.at(0).color;
    for (int k = 0; k < 12; ++k) {
        const glm::dvec3 want = shaderlab::sky::texel(probes[k].face, probes[k].i, probes[k].j, 64);
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(img.at(k, 0, c), want[c], 0.6 / 255.0)
                << "face " << probes[k].face << " texel " << probes[k].i << "," << probes[k].j << " channel "
                << c;
    }
    fs::remove_all(root);
}

}  // namespace
