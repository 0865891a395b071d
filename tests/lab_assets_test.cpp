// Lab-local assets (docs/scenes.md, "Lab-local assets"): a lab's own glTF files and textures in
// labs/<id>/assets/.
// - Fresh: every assets folder shaderlab_make_scenes --lab-assets writes is committed exactly as
//   the tool writes it, in both directions (like ScenesFresh for labs/scenes/; PNGs by pixels).
// - WithinLimits: every labs/*/assets/ folder, generated or hand-made, keeps the rules: a flat
//   folder of regular files of the allowed kinds, each at most 1 MiB and 4 MiB together, each
//   used by lab.json, a glTF file beside it or the lab's README (notes excepted).
// - ALabReadsItsOwnSceneAndTexture: a lab outside the course whose scene and texture live in its
//   own folder renders, through the shaderlab program, with the texture's colour.
// - the generator's conventions for 12-normal-mapping: TANGENT unit, perpendicular to NORMAL, w = -1
//   exactly on the mirrored half, the same frame the loader's MikkTSpace computes without it; the
//   normal map's +Y pointing up the image, where the height rises; bent_quad's tangents, those of
//   the flat quad, far from perpendicular to its bent normals (that is what the mesh is for).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "cli_run.h"
#include "grader/metrics/image.h"
#include "shaderlab/scene/gltf_loader.h"

namespace fs = std::filesystem;

namespace {

const fs::path kLabs = fs::path(SHADERLAB_SOURCE_DIR) / "labs";
const char* const kHowToFix = "run scripts/regenerate_scenes.sh and commit the result";
constexpr std::uintmax_t kMaxFileBytes = 1u << 20;
constexpr std::uintmax_t kMaxLabBytes = 4u << 20;

std::string readBytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::set<std::string> fileNames(const fs::path& dir) {
    std::set<std::string> names;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir, ec)) names.insert(e.path().filename().string());
    return names;
}

fs::path scratch(const std::string& what) {
    const fs::path p = fs::temp_directory_path() / ("shaderlab_" + what + "_" + std::to_string(::getpid()));
    fs::remove_all(p);
    return p;
}

// Bytes, except that PNGs compare by their pixels: another zlib may compress the same image into
// other bytes, and that is not stale.
bool sameContent(const fs::path& a, const fs::path& b) {
    if (a.extension() != ".png") return readBytes(a) == readBytes(b);
    grader::Image ia, ib;
    std::string error;
    return grader::readPng(a.string(), &ia, &error) && grader::readPng(b.string(), &ib, &error) &&
           ia.width == ib.width && ia.height == ib.height && ia.channels == ib.channels &&
           ia.pixels == ib.pixels;
}

TEST(LabAssets, Fresh) {
    const fs::path fresh = scratch("lab_assets_fresh");
    const auto run =
        shaderlab_test::runShell(std::string(SHADERLAB_MAKE_SCENES) + " --lab-assets " + fresh.string());
    ASSERT_EQ(run.exit_code, 0) << run.output;
    int folders = 0;
    for (const auto& lab : fs::directory_iterator(fresh)) {
        const std::string id = lab.path().filename().string();
        const fs::path made = lab.path() / "assets", committed = kLabs / id / "assets";
        ASSERT_TRUE(fs::is_directory(made)) << "the tool writes " << lab.path() << " without assets/";
        ++folders;
        const std::set<std::string> generated = fileNames(made), present = fileNames(committed);
        for (const std::string& name : generated) {
            if (present.count(name) == 0) {
                ADD_FAILURE() << "labs/" << id << "/assets/" << name
                              << " is generated but missing: " << kHowToFix;
                continue;
            }
            EXPECT_TRUE(sameContent(made / name, committed / name))
                << "labs/" << id << "/assets/" << name << " differs from what the tool writes: " << kHowToFix;
        }
        for (const std::string& name : present) {
            EXPECT_TRUE(generated.count(name) != 0) << "labs/" << id << "/assets/" << name
                                                    << " is in a folder the tool writes, but the tool does "
                                                       "not write it (a generated assets folder "
                                                       "holds nothing else): "
                                                    << kHowToFix;
        }
    }
    EXPECT_GT(folders, 0) << "the tool wrote no lab's assets";
    fs::remove_all(fresh);
}

bool isNote(const std::string& name) {
    const std::string ext = fs::path(name).extension().string();
    return ext == ".md" || ext == ".txt";
}

TEST(LabAssets, WithinLimits) {
    const std::set<std::string> allowed = {".gltf", ".glb", ".bin", ".png", ".jpg", ".jpeg", ".md", ".txt"};
    int folders = 0;
    for (const auto& lab : fs::directory_iterator(kLabs)) {
        const fs::path dir = lab.path() / "assets";
        if (!fs::is_directory(fs::symlink_status(dir)) || !fs::exists(lab.path() / "lab.json")) continue;
        ++folders;
        const std::string id = lab.path().filename().string();
        const std::string lab_json = readBytes(lab.path() / "lab.json");
        const std::string readme = readBytes(lab.path() / "README.md");
        std::string gltf_text;
        for (const auto& e : fs::directory_iterator(dir))
            if (e.path().extension() == ".gltf") gltf_text += readBytes(e.path());
        std::uintmax_t total = 0;
        for (const auto& e : fs::directory_iterator(dir)) {
            const std::string name = e.path().filename().string();
            const std::string where = "labs/" + id + "/assets/" + name;
            const fs::file_status st = fs::symlink_status(e.path());
            if (!fs::is_regular_file(st)) {
                ADD_FAILURE() << where << ": only regular files (no links, no sub-folders) belong in assets/";
                continue;
            }
            EXPECT_TRUE(allowed.count(e.path().extension().string()) != 0)
                << where
                << ": not a kind of file assets/ holds (glTF, its .bin, PNG or JPEG, a .md or .txt note)";
            const std::uintmax_t size = fs::file_size(e.path());
            EXPECT_LE(size, kMaxFileBytes) << where << " is over 1 MiB";
            total += size;
            if (isNote(name)) continue;
            const bool used = lab_json.find("assets/" + name + "\"") != std::string::npos ||
                              readme.find("assets/" + name) != std::string::npos ||
                              gltf_text.find("\"" + name + "\"") != std::string::npos;
            EXPECT_TRUE(used)
                << where
                << " is used by nothing: neither lab.json, a glTF file beside it nor the lab's README "
                   "names it";
        }
        EXPECT_LE(total, kMaxLabBytes) << "labs/" << id << "/assets/ holds over 4 MiB";
    }
    EXPECT_GT(folders, 0);
}

// A lab of its own, outside the course: its scene is "<id>/assets/mirrored_quad.gltf" (from the labs root,
// like every scene path) and its texture "assets/red.png" (from the lab folder, like every texture
// path). Nothing in labs/scenes/ is involved.
TEST(LabAssets, ALabReadsItsOwnSceneAndTexture) {
    const fs::path root = scratch("lab_assets_local");
    const fs::path lab = root / "labs" / "90-local";
    fs::create_directories(lab / "assets");
    for (const char* f : {"mirrored_quad.gltf", "mirrored_quad.bin"})
        fs::copy_file(kLabs / "12-normal-mapping/assets" / f, lab / "assets" / f);
    grader::Image red(4, 4, 3);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) red.at(x, y, 0) = 1.0f;
    std::string error;
    ASSERT_TRUE(grader::writePng(red, (lab / "assets/red.png").string(), &error)) << error;
    std::ofstream(lab / "lab.json") << R"({
  "schema": 2, "id": "90-local",
  "passes": [{ "name": "shade", "program": { "vertex": "shade.vert", "fragment": "shade.frag" },
               "inputs": { "u_image": { "texture": "assets/red.png" } } }],
  "scenes": [{ "name": "quad", "file": "90-local/assets/mirrored_quad.gltf",
               "camera": { "position": [0, 0, 2], "target": [0, 0, 0] } }]
})";
    std::ofstream(lab / "shade.vert")
        << "#version 330 core\nlayout(location = 0) in vec3 a_position;\n"
           "uniform mat4 u_model_view_projection;\n"
           "void main() { gl_Position = u_model_view_projection * vec4(a_position, 1.0); }\n";
    std::ofstream(lab / "shade.frag") << "#version 330 core\nuniform sampler2D u_image;\nout vec4 o_color;\n"
                                         "void main() { o_color = texture(u_image, vec2(0.5)); }\n";
    const fs::path out = root / "out";
    const auto run = shaderlab_test::runShell(
        std::string(SHADERLAB_CLI) + " render " + (root / "labs").string() + " --labs " +
        (root / "labs").string() + " --lab 90-local --out " + out.string());
    ASSERT_EQ(run.exit_code, 0) << run.output;
    grader::Image picture;
    ASSERT_TRUE(grader::readPng((out / "90-local/quad.png").string(), &picture, &error)) << error;
    const int cx = picture.width / 2, cy = picture.height / 2;
    EXPECT_FLOAT_EQ(picture.at(cx, cy, 0), 1.0f);
    EXPECT_FLOAT_EQ(picture.at(cx, cy, 1), 0.0f);
    fs::remove_all(root);
}

const fs::path kNormalMapping = kLabs / "12-normal-mapping/assets";

shaderlab::Scene load(const fs::path& file) {
    shaderlab::Scene scene;
    const auto r = shaderlab::loadGltfScene(file.string(), &scene);
    EXPECT_TRUE(r.ok) << r.error;
    EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
    return scene;
}

// TANGENT as glTF 2.0 (3.7.2.1) asks: xyz unit and, as the generator promises, perpendicular to the
// normal; w = -1 exactly where the texture is mirrored (x < 0), +1 elsewhere.
TEST(LabAssets, MirroredMeshesHaveUnitTangentsAndTheirHandedness) {
    for (const char* name : {"mirrored_quad.gltf", "mirrored_sphere.gltf"}) {
        const shaderlab::Scene scene = load(kNormalMapping / name);
        ASSERT_EQ(scene.meshes.size(), 1u);
        const shaderlab::Mesh& m = scene.meshes[0];
        ASSERT_FALSE(m.tangents_generated) << name << " has no TANGENT";
        ASSERT_EQ(m.tangents.size(), m.positions.size());
        int mirrored = 0;
        for (std::size_t i = 0; i < m.positions.size(); ++i) {
            const glm::vec4 t = m.tangents[i];
            EXPECT_NEAR(glm::length(glm::vec3(t)), 1.0f, 1e-5f) << name << " vertex " << i;
            EXPECT_NEAR(glm::dot(glm::vec3(t), m.normals[i]), 0.0f, 1e-5f) << name << " vertex " << i;
            EXPECT_TRUE(t.w == 1.0f || t.w == -1.0f) << name << " vertex " << i;
            const float x = m.positions[i].x;
            if (std::abs(x) > 1e-6f) {
                EXPECT_EQ(t.w, x < 0.0f ? -1.0f : 1.0f) << name << " vertex " << i << " x " << x;
            }
            mirrored += t.w < 0.0f;
        }
        EXPECT_GT(mirrored, 0) << name;
    }
}

// bent_quad is mirrored_quad with its normals bent outward and its TANGENT left as computed for
// the flat normals: a tangent baked for other normals, the one case in the lab where the frame's
// Gram-Schmidt step changes the picture (bent_probe). Same positions, texture coordinates and
// tangents as the flat quad, unit normals facing out, and tangents up to about 31 degrees off
// perpendicular to them, and none along the mirror seam x = 0, where the normals lean only up or
// down.
TEST(LabAssets, BentQuadKeepsTheFlatTangentsUnderBentNormals) {
    const shaderlab::Scene flat = load(kNormalMapping / "mirrored_quad.gltf");
    const shaderlab::Scene bent = load(kNormalMapping / "bent_quad.gltf");
    ASSERT_EQ(flat.meshes.size(), 1u);
    ASSERT_EQ(bent.meshes.size(), 1u);
    const shaderlab::Mesh &f = flat.meshes[0], &b = bent.meshes[0];
    ASSERT_FALSE(b.tangents_generated) << "bent_quad has no TANGENT";
    ASSERT_EQ(b.positions.size(), f.positions.size());
    ASSERT_EQ(b.tangents.size(), f.tangents.size());
    ASSERT_EQ(b.texcoords.size(), f.texcoords.size());
    float most_off = 0.0f;
    for (std::size_t i = 0; i < b.positions.size(); ++i) {
        EXPECT_EQ(b.positions[i], f.positions[i]) << "vertex " << i;
        EXPECT_EQ(b.texcoords[i], f.texcoords[i]) << "vertex " << i;
        EXPECT_EQ(b.tangents[i], f.tangents[i]) << "vertex " << i;
        EXPECT_NEAR(glm::length(b.normals[i]), 1.0f, 1e-5f) << "vertex " << i;
        EXPECT_GT(b.normals[i].z, 0.7f) << "vertex " << i;
        const float off = std::abs(glm::dot(glm::vec3(b.tangents[i]), b.normals[i]));
        if (std::abs(b.positions[i].x) < 1e-6f) {
            EXPECT_LT(off, 1e-6f) << "vertex " << i << " on the seam";
        }
        most_off = std::max(most_off, off);
    }
    EXPECT_GT(most_off, std::sin(glm::radians(30.0f))) << "the tangents are all but perpendicular to the "
                                                          "normals: bent_probe would show no frame without "
                                                          "Gram-Schmidt";
}

// The generator's tangents (Lengyel's method) and the ones the loader computes for the same mesh
// without TANGENT (MikkTSpace, docs/scenes.md) are the same frame: same w, tangents within 3 degrees.
TEST(LabAssets, GeneratedTangentsAgreeWithTheLoadersMikkTSpace) {
    const fs::path dir = scratch("lab_assets_mikk");
    fs::create_directories(dir);
    for (const char* base : {"mirrored_quad", "mirrored_sphere", "turned_sphere"}) {
        nlohmann::json gltf =
            nlohmann::json::parse(readBytes(kNormalMapping / (std::string(base) + ".gltf")));
        for (auto& mesh : gltf["meshes"])
            for (auto& prim : mesh["primitives"]) prim["attributes"].erase("TANGENT");
        std::ofstream(dir / (std::string(base) + ".gltf")) << gltf.dump();
        fs::copy_file(kNormalMapping / (std::string(base) + ".bin"), dir / (std::string(base) + ".bin"),
                      fs::copy_options::overwrite_existing);
        const shaderlab::Scene given = load(kNormalMapping / (std::string(base) + ".gltf"));
        shaderlab::Scene computed;
        const auto r = shaderlab::loadGltfScene((dir / (std::string(base) + ".gltf")).string(), &computed);
        ASSERT_TRUE(r.ok) << r.error;
        const shaderlab::Mesh &a = given.meshes.at(0), &b = computed.meshes.at(0);
        ASSERT_TRUE(b.tangents_generated);
        ASSERT_EQ(a.tangents.size(), b.tangents.size());
        // Not the poles: there every direction is a tangent and the two methods may pick others.
        for (std::size_t i = 0; i < a.tangents.size(); ++i) {
            if (std::abs(a.positions[i].y) > 0.999f) continue;
            EXPECT_EQ(a.tangents[i].w, b.tangents[i].w) << base << " vertex " << i;
            EXPECT_GT(glm::dot(glm::vec3(a.tangents[i]), glm::vec3(b.tangents[i])),
                      std::cos(glm::radians(3.0f)))
                << base << " vertex " << i;
        }
    }
    fs::remove_all(dir);
}

// The map is OpenGL style, as glTF 2.0 defines normalTexture: green above 1/2 (the normal leans up
// the image) where the height falls toward the top of the image, red above 1/2 where it falls
// toward the right; and every texel decodes to a unit normal facing out (z > 0).
TEST(LabAssets, NormalMapPointsUpTheImageWhereTheHeightRisesDownIt) {
    grader::Image height, normal;
    std::string error;
    ASSERT_TRUE(grader::readPng((kNormalMapping / "bricks_height.png").string(), &height, &error)) << error;
    ASSERT_TRUE(grader::readPng((kNormalMapping / "bricks_normal.png").string(), &normal, &error)) << error;
    ASSERT_EQ(height.width, normal.width);
    ASSERT_EQ(height.height, normal.height);
    const int w = height.width, h = height.height;
    int checked = 0;
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const glm::vec3 n(normal.at(x, y, 0) * 2.0f - 1.0f, normal.at(x, y, 1) * 2.0f - 1.0f,
                              normal.at(x, y, 2) * 2.0f - 1.0f);
            EXPECT_NEAR(glm::length(n), 1.0f, 0.01f) << x << "," << y;
            EXPECT_GT(n.z, 0.0f) << x << "," << y;
            const float up = height.at(x, (y + h - 1) % h) - height.at(x, (y + 1) % h);
            const float right = height.at((x + 1) % w, y) - height.at((x + w - 1) % w, y);
            if (std::abs(up) > 0.05f) {
                EXPECT_EQ(n.y > 0.0f, up < 0.0f) << x << "," << y;
                ++checked;
            }
            if (std::abs(right) > 0.05f) {
                EXPECT_EQ(n.x > 0.0f, right < 0.0f) << x << "," << y;
                ++checked;
            }
        }
    }
    EXPECT_GT(checked, 1000);
}

}  // namespace
