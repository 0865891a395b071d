// What the tests of the lab.json parser share (lab_spec*_test.cpp): a labs root in the temp
// directory holding every file their specs name, the valid base spec that the error table breaks
// one mistake at a time, the smallest valid spec, and the assertions on messages
// "<origin>: <json path>: <problem>". Nothing here renders, and nothing here is a test.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "shaderlab/lab/lab_spec.h"

namespace lab_spec_test {

namespace fs = std::filesystem;
using nlohmann::json;
using shaderlab::LabSpecResult;

inline const char* const kOrigin = "labs/01-phong/lab.json";

// A valid lab that the error table of lab_spec_broken_test.cpp breaks one mistake at a time: a
// shadow pass into a sampled depth, a fullscreen pass into a cube target, a scene pass into a
// two-attachment target reading both, a repeated blur that reads its own half-size target, and a
// last pass from the same template; two goals; a scene with lights and one graded at two times.
inline const char* const kBaseSpec = R"({
  "schema": 2,
  "id": "01-phong",
  "title": "The base of the error table",
  "resolution": [256, 128],
  "goals": [
    {"id": "shading", "title": "Shade into the G-buffer", "points": 6, "passes": ["shade"]},
    {"id": "post", "title": "Blur it", "points": 4, "passes": ["final"]}
  ],
  "targets": {
    "gbuf": {"format": "rgba16f", "attachments": ["albedo", "normal"]},
    "shadow": {"size": [64, 64], "depth": "texture"},
    "half": {"scale": 0.5, "depth": "none"},
    "env": {"type": "cube", "size": [32, 32], "depth": "none"}
  },
  "templates": {
    "post": {"program": {"vertex": "shared/fullscreen.vert", "fragment": "post.frag"}, "draw": "fullscreen"}
  },
  "passes": [
    {"name": "shadow", "program": {"vertex": "phong.vert", "fragment": "depth.frag"}, "target": "shadow",
     "camera": {"light": 0}},
    {"name": "sky", "extends": "post", "program": {"fragment": "sky.frag"}, "target": "env"},
    {"name": "shade", "program": {"vertex": "phong.vert", "fragment": "phong.frag"}, "target": "gbuf",
     "inputs": {"u_shadow": "shadow.depth", "u_env": "env", "u_ramp": {"texture": "ramp.png"}},
     "uniforms": {"u_shininess": 32, "u_light_matrix": "@shadow.view_projection"},
     "graded": true},
    {"name": "blur", "extends": "post", "target": "half",
     "inputs": {"u_image": "gbuf.albedo", "u_prev": "half"}, "repeat": 4},
    {"name": "final", "extends": "post", "inputs": {"u_image": "half", "u_normal": "gbuf.normal"}}
  ],
  "scenes": [
    {"name": "sphere", "file": "scenes/sphere.gltf",
     "camera": {"position": [0, 0, 3], "target": [0, 0, 0], "up": [0, 1, 0], "near": 0.1, "far": 100},
     "lights": [{"type": "point", "position": [2, 2, 2]}, {"type": "directional", "direction": [0, -1, 0]}]},
    {"name": "teapot", "file": "scenes/teapot.gltf", "times": [0, 1], "repeats": {"blur": 2}}
  ],
  "grading": {"psnr_min_db": 30}
})";

// The smallest valid file of docs/lab-format.md (lab_spec_docs_test.cpp also reads it
// from there).
inline const char* const kMinimalSpec = R"({
  "schema": 2,
  "id": "01-phong",
  "passes": [{"name": "shade", "program": {"vertex": "phong.vert", "fragment": "phong.frag"}}],
  "scenes": [{"name": "sphere", "file": "scenes/sphere.gltf"}]
})";

inline std::string sanitized(std::string s) {
    for (char& c : s)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    return s;
}

inline void writeFile(const fs::path& p, const std::string& text) {
    fs::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << text;
}

inline std::string allErrors(const LabSpecResult& r) {
    std::string s;
    for (const std::string& e : r.errors) s += "\n  " + e;
    return s.empty() ? " (none)" : s;
}

// Whether some message reads "<origin>: <path>: ..." and contains `problem` after the path.
inline ::testing::AssertionResult hasError(const LabSpecResult& r, const std::string& path,
                                           const std::string& problem, const std::string& origin = kOrigin) {
    const std::string prefix = origin + ": " + (path.empty() ? "" : path + ": ");
    for (const std::string& e : r.errors)
        if (e.rfind(prefix, 0) == 0 && e.find(problem, prefix.size()) != std::string::npos)
            return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "no error starting with \"" << prefix << "\" and containing \""
                                         << problem << "\"; errors were:" << allErrors(r);
}

// A labs root in the temp directory with the lab folder 01-phong holding every file the specs
// here name, the course's shared folder, the scenes, and a file outside the labs root.
class LabSpecFixture : public ::testing::Test {
  protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        root_ = fs::temp_directory_path() /
                ("shaderlab_labspec_" + std::to_string(::getpid()) + "_" +
                 sanitized(std::string(info->test_suite_name()) + "_" + info->name()));
        fs::remove_all(root_);
        labs_ = root_ / "labs";
        lab_ = labs_ / "01-phong";
        for (const char* f : {"phong.vert", "phong.frag", "depth.frag", "sky.frag", "post.frag", "final.frag",
                              "blur.frag", "scene.vert", "gbuffer.frag", "outline.frag", "combine.frag",
                              "advect.frag", "particles.vert", "particles.frag"})
            writeFile(lab_ / f, "// shader\n");
        for (const char* f : {"ramp.png", "volume.png"}) writeFile(lab_ / f, "not really a png");
        for (const char* face : {"px", "nx", "py", "ny", "pz", "nz"}) {
            writeFile(lab_ / "sky" / (std::string(face) + ".png"), "face");
            if (std::string(face) != "ny") writeFile(lab_ / "partial" / (std::string(face) + ".png"), "face");
        }
        writeFile(labs_ / "shared" / "fullscreen.vert", "// shared\n");
        for (const char* f : {"sphere.gltf", "teapot.gltf", "ground_plane.gltf", "cube.glb"})
            writeFile(labs_ / "scenes" / f, "{}");
        writeFile(root_ / "outside.frag", "// outside every lab\n");
    }
    void TearDown() override { fs::remove_all(root_); }

    LabSpecResult parseText(const std::string& text) const {
        return shaderlab::parseLabSpecText(text, kOrigin, lab_.string());
    }
    LabSpecResult parseJson(const json& doc) const { return parseText(doc.dump(2)); }

    fs::path root_, labs_, lab_;
};

}  // namespace lab_spec_test
