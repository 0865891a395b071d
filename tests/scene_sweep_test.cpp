// `shaderlab scene-sweep` on a small course in the temp directory: one pass shading a sphere with
// an ambient term and a clamped Lambert term, a goal for each, one mistake per goal and one
// alternative. The Lambert mistake (abs instead of max) shows only where the sphere faces away from
// the light, so a sweep of the light's direction must rank a light from behind above the lab's
// light from the camera, which shows nothing of it; a candidate with the ambient term on also
// fails the ambient goal's mistake and must say so. Bad --vary text, a candidate that is no valid
// scene and a sweep over the cap are refused before anything is drawn; the scene printed for the
// best candidate parses as a scene of the lab.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_run.h"
#include "shaderlab/lab/lab_spec.h"

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

const fs::path kRoot = SHADERLAB_SOURCE_DIR;

using shaderlab_test::CliRun;

// The student file; NDOTL and AMBIENT say what each submission computes.
const char* const kFragment = R"(#version 330 core
in vec3 v_world_normal;
uniform vec4 u_light_position;  // w = 0: xyz points toward the light
uniform float u_ambient;
uniform float u_diffuse;
out vec4 o_color;
void main() {
    vec3 n = normalize(v_world_normal);
    vec3 l = normalize(u_light_position.xyz);
    o_color = vec4(vec3(AMBIENT + u_diffuse * NDOTL), 1.0);
}
)";

const char* const kVertex = R"(#version 330 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
uniform mat4 u_model;
uniform mat4 u_view;
uniform mat4 u_projection;
uniform mat3 u_normal_matrix;
out vec3 v_world_normal;
void main() {
    v_world_normal = u_normal_matrix * a_normal;
    gl_Position = u_projection * u_view * u_model * vec4(a_position, 1.0);
}
)";

std::string fragment(const std::string& ndotl, const std::string& ambient) {
    std::string text = kFragment;
    text.replace(text.find("AMBIENT"), 7, ambient);
    text.replace(text.find("NDOTL"), 5, ndotl);
    return text;
}

class SceneSweep : public ::testing::Test {
  protected:
    void SetUp() override {
        tmp_ = fs::temp_directory_path() / ("shaderlab_sweep_" + std::to_string(::getpid()) + "_" +
                                            ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(tmp_);
        fs::create_directories(lab());
        fs::create_directories(tmp_ / "labs" / "scenes");
        for (const char* f : {"sphere.gltf", "sphere.bin"})
            fs::copy_file(kRoot / "labs" / "scenes" / f, tmp_ / "labs" / "scenes" / f);
        fs::copy(kRoot / "labs" / "shared", tmp_ / "labs" / "shared", fs::copy_options::recursive);
        // The lab's light travels from the camera (at [0, 0.8, 3.6]) to the sphere: every point the
        // camera sees is lit, so abs(n.l) and max(n.l, 0) draw the same picture there.
        const json doc = {
            {"schema", 2},
            {"id", "sweep"},
            {"title", "Ambient and clamped Lambert"},
            {"resolution", {48, 48}},
            {"student_files", {"shade.frag"}},
            {"goals",
             {{{"id", "diffuse"}, {"title", "Lambert clamped at zero"}, {"points", 1}, {"scenes", {"lit"}}},
              {{"id", "ambient"},
               {"title", "The ambient term"},
               {"points", 1},
               {"scenes", {"ambient_only"}}}}},
            {"passes",
             {{{"name", "shade"},
               {"program", {{"vertex", "shade.vert"}, {"fragment", "shade.frag"}}},
               {"draw", "scene"},
               {"uniforms", {{"u_ambient", 0.0}, {"u_diffuse", 1.0}}},
               {"graded", true}}}},
            {"scenes",
             {{{"name", "lit"},
               {"file", "scenes/sphere.gltf"},
               {"lights", {{{"type", "directional"}, {"direction", {0, -0.8, -3.6}}}}}},
              {{"name", "ambient_only"},
               {"file", "scenes/sphere.gltf"},
               {"uniforms", {{"u_diffuse", 0.0}, {"u_ambient", 0.3}}}}}}};
        std::ofstream(lab() / "lab.json") << doc.dump(2);
        std::ofstream(lab() / "shade.vert") << kVertex;
        std::ofstream(lab() / "shade.frag") << fragment("0.0", "0.0");  // the starter
        write(tmp_ / "reference_solutions" / "sweep", fragment("max(dot(n, l), 0.0)", "u_ambient"));
        const fs::path corpus = tmp_ / "tests" / "corpus" / "sweep";
        write(corpus / "abs-ndotl", fragment("abs(dot(n, l))", "u_ambient"));
        write(corpus / "ambient-doubled", fragment("max(dot(n, l), 0.0)", "2.0 * u_ambient"));
        write(corpus / "clamp-ndotl", fragment("clamp(dot(n, l), 0.0, 1.0)", "u_ambient"));
        const json cases = {
            {"lab", "sweep"},
            {"cases",
             {{{"name", "abs-ndotl"}, {"kind", "mistake"}, {"fails", {"diffuse"}}, {"about", "abs(n.l)"}},
              {{"name", "ambient-doubled"},
               {"kind", "mistake"},
               {"fails", {"ambient"}},
               {"about", "2 ambient"}},
              {{"name", "clamp-ndotl"}, {"kind", "alternative"}, {"about", "clamp(n.l, 0, 1)"}}}}};
        std::ofstream(corpus / "cases.json") << cases.dump(2);
    }
    void TearDown() override { fs::remove_all(tmp_); }

    fs::path lab() const { return tmp_ / "labs" / "sweep"; }
    fs::path out() const { return tmp_ / "out"; }
    static void write(const fs::path& dir, const std::string& text) {
        fs::create_directories(dir);
        std::ofstream(dir / "shade.frag") << text;
    }
    CliRun sweep(const std::string& options) const {
        return shaderlab_test::runShell(std::string(SHADERLAB_CLI) + " scene-sweep sweep --labs " +
                                        (tmp_ / "labs").string() + " --out " + out().string() + " " +
                                        options);
    }
    // A refusal: exit code 2, `reason` said, nothing drawn.
    void expectRefused(const std::string& options, const std::string& reason) const {
        const CliRun r = sweep(options);
        EXPECT_EQ(r.exit_code, 2) << options << "\n" << r.output;
        EXPECT_NE(r.output.find(reason), std::string::npos) << options << "\n" << r.output;
        EXPECT_FALSE(fs::exists(out() / "sweep.json")) << options;
        EXPECT_FALSE(fs::exists(out() / "pictures")) << options;
        EXPECT_FALSE(fs::exists(out() / "work")) << options;
    }

    fs::path tmp_;
};

// The candidate of the sweep with these values.
const json* findCandidate(const json& doc, const json& direction, double ambient) {
    for (const json& c : doc["candidates"])
        if (c["values"]["lights[0].direction"] == direction && c["values"]["uniforms.u_ambient"] == ambient)
            return &c;
    return nullptr;
}

TEST_F(SceneSweep, RanksTheLightThatShowsTheMistakeFirstAndNamesWhatElseFails) {
    const CliRun r = sweep(
        "--scene lit --vary 'lights[0].direction=[0,-0.8,-3.6],[1,0,0],[0,0.8,3.6]' "
        "--vary uniforms.u_ambient=0,0.2");
    ASSERT_EQ(r.exit_code, 0) << r.output;  // the best candidate separates the goal
    const json doc = json::parse(std::ifstream(out() / "sweep.json"), nullptr, false);
    ASSERT_TRUE(doc.is_object()) << r.output;
    EXPECT_EQ(doc["goals"], json::array({"diffuse"}));
    ASSERT_EQ(doc["candidates"].size(), 7u) << r.output;  // the base and 3 x 2

    const json& best = doc["candidates"][0];
    EXPECT_EQ(best["values"]["lights[0].direction"], json::array({0, 0.8, 3.6})) << best.dump(2);
    EXPECT_EQ(best["values"]["uniforms.u_ambient"], 0) << best.dump(2);
    EXPECT_TRUE(best["goals"][0]["separates"].get<bool>()) << best.dump(2);
    EXPECT_TRUE(best["goals"][0]["isolates"].get<bool>()) << best.dump(2);
    EXPECT_GT(best["goals"][0]["mistake_factor"].get<double>(), 2.0) << best.dump(2);
    EXPECT_TRUE(fs::exists(out() / best["picture"].get<std::string>())) << best.dump(2);

    // The lab's own light shows nothing of the mistake: it ranks below, and says what it misses.
    const json* base = nullptr;
    for (const json& c : doc["candidates"])
        if (c["base"].get<bool>()) base = &c;
    ASSERT_NE(base, nullptr);
    EXPECT_GT((*base)["rank"].get<int>(), best["rank"].get<int>());
    EXPECT_FALSE((*base)["goals"][0]["separates"].get<bool>());
    EXPECT_EQ((*base)["goals"][0]["missed"], json::array({"abs-ndotl"})) << base->dump(2);
    const json* side = findCandidate(doc, {1, 0, 0}, 0);
    ASSERT_NE(side, nullptr);
    EXPECT_LT((*side)["rank"].get<int>(), (*base)["rank"].get<int>());

    // With the ambient term on, the ambient goal's mistake fails here too: not isolating.
    const json* ambient = findCandidate(doc, {0, 0.8, 3.6}, 0.2);
    ASSERT_NE(ambient, nullptr);
    EXPECT_FALSE((*ambient)["goals"][0]["isolates"].get<bool>());
    EXPECT_EQ((*ambient)["goals"][0]["also_fails"],
              json::parse(R"([{"case": "ambient-doubled", "goal": "ambient"}])"));
    EXPECT_GT((*ambient)["rank"].get<int>(), best["rank"].get<int>());
    EXPECT_NE(r.output.find("also fails: ambient-doubled (goal ambient)"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("misses: abs-ndotl"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("candidates/s"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(out() / "work")) << "the swept lab is removed without --keep";

    // The scene printed for the best candidate is a scene of the lab, as printed and as stored.
    const std::string printed = "{ \"name\": \"lit_" + best["id"].get<std::string>() + "\"";
    const std::size_t at = r.output.find(printed);
    ASSERT_NE(at, std::string::npos) << r.output;
    const json scene = json::parse(r.output.substr(at, r.output.find('\n', at) - at), nullptr, false);
    ASSERT_TRUE(scene.is_object()) << r.output;
    EXPECT_EQ(scene, best["scene"]);
    json lab_doc = json::parse(std::ifstream(lab() / "lab.json"));
    lab_doc["scenes"].push_back(scene);
    lab_doc["goals"][0]["scenes"].push_back(scene["name"]);
    std::ofstream(lab() / "lab.json") << lab_doc.dump(2);
    const shaderlab::LabSpecResult parsed = shaderlab::parseLabSpec(lab().string());
    EXPECT_TRUE(parsed.ok) << (parsed.errors.empty() ? "" : parsed.errors.front());
}

TEST_F(SceneSweep, AFileOfWholeCandidatesAndAMistakeToCatch) {
    std::ofstream(tmp_ / "sweep.json") << R"({
      "scene": "lit", "goals": ["diffuse"], "mistakes": ["abs-ndotl"],
      "candidates": [
        { "name": "from-behind", "lights": [{ "type": "directional", "direction": [0, 0.8, 3.6] }] },
        { "name": "point-at-camera", "lights": [{ "type": "point", "position": [0, 0.8, 3.6] }] }
      ]
    })";
    const CliRun r = sweep("--sweep " + (tmp_ / "sweep.json").string() + " --top 1");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const json doc = json::parse(std::ifstream(out() / "sweep.json"), nullptr, false);
    ASSERT_TRUE(doc.is_object()) << r.output;
    ASSERT_EQ(doc["candidates"].size(), 3u);
    EXPECT_EQ(doc["candidates"][0]["label"], "from-behind") << r.output;
    EXPECT_EQ(doc["candidates"][0]["scene"]["lights"][0]["direction"], json::array({0, 0.8, 3.6}));
    EXPECT_EQ(doc["candidates"][0]["scene"]["name"], "lit_" + doc["candidates"][0]["id"].get<std::string>());
}

TEST_F(SceneSweep, RefusesBadVariationsBeforeDrawing) {
    expectRefused("--scene lit --vary uniforms.u_ambient=0..1", "a range needs its number of values: A..B:N");
    expectRefused("--scene lit --vary 'lights[0].direction=[0,0,1]..[1,0]:3'",
                  "the range's ends differ in shape");
    expectRefused("--scene lit --vary 'camra.position=[0,0,3]'", "did you mean \"camera\"");
    expectRefused("--scene lit --vary 'lights[0].direction=[0,0,1'", "is not valid JSON");
    expectRefused("--scene lit --vary uniforms.u_ambient", "expected PATH=VALUES");
    expectRefused("--scene lit --vary uniforms.u_ambent=0,1", "no shader of sweep mentions u_ambent");
    expectRefused("--scene ambient_only --vary 'lights[0].direction=[0,0,1]'", "give it a \"lights\" list");
    expectRefused("--scene lt --vary uniforms.u_ambient=0,1", "did you mean \"lit\"");
    expectRefused("--scene lit --goal difuse --vary uniforms.u_ambient=0,1", "did you mean \"diffuse\"");
    expectRefused("--scene lit --vary uniforms.u_ambient=0,1 --mistake ambient-doubled",
                  "which the candidates are not judged under");
    // A value that is no valid scene is the lab parser's to refuse, naming the candidate.
    expectRefused("--scene lit --vary 'lights[0].direction=[0,-1,0],[0,0,0]'",
                  "candidate c02 (lights[0].direction=[0,0,0])");
}

TEST_F(SceneSweep, RefusesMoreCandidatesThanTheCap) {
    expectRefused("--scene lit --vary uniforms.u_ambient=0..1:70", "70 candidates, more than the cap of 64");
    expectRefused(
        "--scene lit --max-candidates 8 --vary uniforms.u_ambient=0..1:5 --vary "
        "'lights[0].direction=[0,0,1],[1,0,0]'",
        "the variations make 5 x 2 = 10 candidates, more than the cap of 8");
    expectRefused("--scene lit --max-candidates 2 --vary uniforms.u_ambient=0,0.1,0.2",
                  "more than the cap of 2");
}

}  // namespace
