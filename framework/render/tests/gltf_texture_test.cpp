// glTF material textures as a shader samples them (docs/scenes.md, "Materials"): a quad filling
// the frame under an orthographic camera, textured with a 4x4 PNG through a nearest sampler, so
// each texel covers a 16x16 block of the 64x64 picture. Base colour reads sRGB-decoded, metallic-
// roughness raw; images from a file, a data: URI and a bufferView; a malformed image and one whose
// header claims 16000x16000 pixels are refused with a warning and read as the stand-ins.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "gl_test_support.h"
#include "grader/metrics/image.h"
#include "shaderlab/lab/lab_spec.h"
#include "shaderlab/render/renderer.h"

namespace fs = std::filesystem;

namespace {

using Bytes = std::vector<std::uint8_t>;

std::string base64(const Bytes& in) {
    static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (std::size_t i = 0; i < in.size(); i += 3) {
        std::uint32_t v = static_cast<std::uint32_t>(in[i]) << 16;
        if (i + 1 < in.size()) v |= static_cast<std::uint32_t>(in[i + 1]) << 8;
        if (i + 2 < in.size()) v |= in[i + 2];
        out += kAlphabet[(v >> 18) & 63];
        out += kAlphabet[(v >> 12) & 63];
        out += i + 1 < in.size() ? kAlphabet[(v >> 6) & 63] : '=';
        out += i + 2 < in.size() ? kAlphabet[v & 63] : '=';
    }
    return out;
}

template <typename T>
void append(Bytes* b, const std::vector<T>& values) {
    const auto* p = reinterpret_cast<const std::uint8_t*>(values.data());
    b->insert(b->end(), p, p + values.size() * sizeof(T));
}

// The 4x4 texture's byte value of channel c at column i, row j (row 0 on top). Texel (0, 0) is
// 188 in red: sRGB 188/255 decodes to 0.503 linear.
int texel(int i, int j, int c) { return c == 3 ? 255 : (188 + 17 * i + 5 * j + 40 * c) % 256; }

float srgbToLinear(float v) { return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f); }

// The PNG signature, an IHDR chunk claiming 16000x16000 RGBA pixels, and an empty IDAT chunk: no
// data. Newer stb_image (Debian 13's) reads a header up to the first IDAT, looking for tRNS,
// so without one the file would be malformed rather than too large.
Bytes oversizedPng() {
    Bytes b = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A, 0, 0, 0, 13, 'I', 'H', 'D', 'R'};
    for (std::uint32_t v : {16000u, 16000u})
        for (int s = 24; s >= 0; s -= 8) b.push_back(static_cast<std::uint8_t>(v >> s));
    for (std::uint8_t v : {8, 6, 0, 0, 0, 0, 0, 0, 0}) b.push_back(v);         // depth, RGBA, ..., CRC
    const std::uint8_t idat[] = {0, 0, 0, 0, 'I', 'D', 'A', 'T', 0, 0, 0, 0};  // length 0, CRC
    b.insert(b.end(), idat, idat + sizeof idat);
    return b;
}

// A quad from (-1, -1) to (1, 1) at z = 0, seen face on by a camera 2 units tall; its material's
// base colour and metallic-roughness textures are image 0, its normal texture image 1 (when
// there is one). `image0` is a URI, or empty for `image0_bytes` in a bufferView.
std::string quadGltf(const std::string& image0, const Bytes& image0_bytes, const std::string& image1) {
    Bytes buffer;
    append(&buffer, std::vector<float>{-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0});
    append(&buffer, std::vector<float>{0, 1, 1, 1, 1, 0, 0, 0});
    append(&buffer, std::vector<std::uint16_t>{0, 1, 2, 0, 2, 3, 0, 0});  // padded to 4 bytes
    const std::size_t image_offset = buffer.size();
    buffer.insert(buffer.end(), image0_bytes.begin(), image0_bytes.end());
    std::string views =
        R"({"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 32},
           {"buffer": 0, "byteOffset": 80, "byteLength": 12})";
    if (image0.empty())
        views += R"(, {"buffer": 0, "byteOffset": )" + std::to_string(image_offset) + R"(, "byteLength": )" +
                 std::to_string(image0_bytes.size()) + "}";
    const std::string first = image0.empty()
                                  ? R"({"name": "checker", "bufferView": 3, "mimeType": "image/png"})"
                                  : R"({"name": "checker", "uri": ")" + image0 + R"("})";
    const std::string second = image1.empty() ? "" : R"(, {"name": "bumps", "uri": ")" + image1 + R"("})";
    const std::string normal = image1.empty() ? "" : R"(, "normalTexture": {"index": 2, "scale": 0.25})";
    return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 1]}],
  "nodes": [{"mesh": 0}, {"camera": 0, "translation": [0, 0, 2]}],
  "cameras": [{"type": "orthographic", "orthographic": {"xmag": 1, "ymag": 1, "znear": 0.1, "zfar": 10}}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2, "material": 0}]}],
  "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0},
                 "metallicRoughnessTexture": {"index": 1, "texCoord": 1}}, "occlusionTexture": {"index": 1, "strength": 0.75})" +
           normal + R"(}],
  "samplers": [{"magFilter": 9728, "minFilter": 9728}],
  "textures": [{"source": 0, "sampler": 0}, {"source": 0, "sampler": 0})" +
           (image1.empty() ? "" : R"(, {"source": 1, "sampler": 0})") + R"(],
  "images": [)" +
           first + second + R"(],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1, -1, 0], "max": [1, 1, 0]},
                {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"},
                {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}],
  "bufferViews": [)" +
           views + R"(],
  "buffers": [{"byteLength": )" +
           std::to_string(buffer.size()) + R"(, "uri": "data:application/octet-stream;base64,)" +
           base64(buffer) + R"("}]})";
}

const char* const kVert = R"(#version 330 core
in vec3 a_position;
in vec2 a_texcoord;
uniform mat4 u_model_view_projection;
out vec2 v_texcoord;
void main() { v_texcoord = a_texcoord; gl_Position = u_model_view_projection * vec4(a_position, 1.0); }
)";
const char* const kBaseColorFrag = R"(#version 330 core
in vec2 v_texcoord;
uniform sampler2D u_base_color_texture;
uniform bool u_has_base_color_texture;
out vec4 o_color;
void main() { o_color = vec4(texture(u_base_color_texture, v_texcoord).rgb, u_has_base_color_texture ? 1.0 : 0.25); }
)";
const char* const kMetallicRoughnessFrag = R"(#version 330 core
in vec2 v_texcoord;
uniform sampler2D u_metallic_roughness_texture;
uniform int u_metallic_roughness_texcoord;
uniform float u_occlusion_strength;
out vec4 o_color;
void main() { o_color = vec4(texture(u_metallic_roughness_texture, v_texcoord).rgb, float(u_metallic_roughness_texcoord) + u_occlusion_strength); }
)";
// Base colour and normal map together: red and green of the one, blue of the other.
const char* const kStandInFrag = R"(#version 330 core
in vec2 v_texcoord;
uniform sampler2D u_base_color_texture;
uniform sampler2D u_normal_texture;
uniform bool u_has_base_color_texture;
uniform bool u_has_normal_texture;
uniform float u_normal_scale;
out vec4 o_color;
void main() {
    o_color = vec4(texture(u_base_color_texture, v_texcoord).rg, texture(u_normal_texture, v_texcoord).b * 0.5,
                   (u_has_base_color_texture ? 0.5 : 0.0) + (u_has_normal_texture ? 0.25 : 0.0) + u_normal_scale);
}
)";
// Samples no material texture: the images are never decoded.
const char* const kPlainFrag = R"(#version 330 core
in vec2 v_texcoord;
out vec4 o_color;
void main() { o_color = vec4(v_texcoord, 0.0, 1.0); }
)";

class GltfTexture : public ::testing::Test {
  protected:
    void SetUp() override {
        std::string err;
        if (!shaderlab::testing::sharedContext(shaderlab::Backend::OSMesa, &err)) FAIL() << err;
        root_ = fs::temp_directory_path() / ("shaderlab_gltftex_" + std::to_string(::getpid()) + "_" +
                                             ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(root_);
        lab_ = root_ / "labs" / "71-textures";
        scenes_ = root_ / "labs" / "scenes";
        fs::create_directories(lab_);
        fs::create_directories(scenes_);
        grader::Image checker(4, 4, 4);
        for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 4; ++i)
                for (int c = 0; c < 4; ++c) checker.at(i, j, c) = static_cast<float>(texel(i, j, c)) / 255.0f;
        ASSERT_TRUE(grader::writePng(checker, (scenes_ / "checker.png").string(), &err)) << err;
        std::ifstream png(scenes_ / "checker.png", std::ios::binary);
        png_.assign(std::istreambuf_iterator<char>(png), std::istreambuf_iterator<char>());
        ASSERT_GT(png_.size(), 8u);
        std::ofstream(lab_ / "quad.vert") << kVert;
        std::ofstream(lab_ / "base_color.frag") << kBaseColorFrag;
        std::ofstream(lab_ / "metallic_roughness.frag") << kMetallicRoughnessFrag;
        std::ofstream(lab_ / "stand_in.frag") << kStandInFrag;
        std::ofstream(lab_ / "plain.frag") << kPlainFrag;
    }
    void TearDown() override { fs::remove_all(root_); }

    void writeScene(const std::string& name, const std::string& gltf) {
        std::ofstream(scenes_ / name, std::ios::binary) << gltf;
    }

    shaderlab::LabRender render(const std::vector<std::string>& files, const std::string& frag) {
        std::string scenes;
        for (const std::string& f : files)
            scenes += std::string(scenes.empty() ? "" : ", ") + "{\"name\": \"" + f.substr(0, f.find('.')) +
                      "\", \"file\": \"scenes/" + f + "\"}";
        std::ofstream(lab_ / "lab.json") << R"({"schema": 2, "id": "71-textures", "resolution": [64, 64],
          "passes": [{"name": "draw", "program": {"vertex": "quad.vert", "fragment": ")" +
                                                frag + R"("},
            "state": {"clear_color": [0, 0, 0, 0], "depth_test": true}, "graded": true}],
          "scenes": [)" + scenes + "]}";
        const shaderlab::LabSpecResult parsed = shaderlab::parseLabSpec(lab_.string());
        std::string errors;
        for (const std::string& e : parsed.errors) errors += "\n" + e;
        EXPECT_TRUE(parsed.ok) << errors;
        spec_ = parsed.spec;
        if (!parsed.ok) return {};
        return shaderlab::renderLab(spec_, lab_.string());
    }

    static const grader::Image* picture(const shaderlab::LabRender& r, const std::string& name) {
        for (const auto& s : r.scenes)
            if (s.scene == name && !s.passes.empty()) return &s.passes[0].color;
        ADD_FAILURE() << "no picture of scene " << name;
        return nullptr;
    }

    // The warnings about images, as "file: message" lines.
    static std::string imageWarnings(const shaderlab::LabRender& r) {
        std::string out;
        for (const auto& d : r.diagnostics)
            if (d.message.find("image '") != std::string::npos) out += d.file + ": " + d.message + "\n";
        return out;
    }

    fs::path root_, lab_, scenes_;
    Bytes png_;
    shaderlab::LabSpec spec_;
};

// Each texel's block, sampled at its centre, against `expected(byte value, channel)`. llvmpipe's
// sRGB decoding is off by up to 1.2e-3 from the exact formula, while an undecoded value would be
// off by up to 0.2 (0.737 against 0.503 for 188).
void expectTexels(const grader::Image& img, float (*expected)(int, int), float tolerance, float alpha,
                  const std::string& what) {
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(img.at(8 + 16 * i, 8 + 16 * j, c), expected(texel(i, j, c), c), tolerance)
                    << what << " texel " << i << "," << j << " channel " << c;
            EXPECT_NEAR(img.at(8 + 16 * i, 8 + 16 * j, 3), alpha, 1e-5f) << what;
        }
}

float asSrgb(int byte, int) { return srgbToLinear(static_cast<float>(byte) / 255.0f); }
float asLinear(int byte, int) { return static_cast<float>(byte) / 255.0f; }

TEST_F(GltfTexture, BaseColourIsDecodedFromSrgbAndMetallicRoughnessIsNot) {
    writeScene("from_file.gltf", quadGltf("checker.png", {}, ""));
    writeScene("from_data_uri.gltf", quadGltf("data:image/png;base64," + base64(png_), {}, ""));
    writeScene("from_buffer_view.gltf", quadGltf("", png_, ""));
    const std::vector<std::string> files = {"from_file.gltf", "from_data_uri.gltf", "from_buffer_view.gltf"};

    const auto base = render(files, "base_color.frag");
    ASSERT_EQ(base.status, shaderlab::RenderStatus::Ok) << base.message;
    EXPECT_EQ(imageWarnings(base), "");
    for (const char* name : {"from_file", "from_data_uri", "from_buffer_view"})
        if (const grader::Image* img = picture(base, name)) expectTexels(*img, asSrgb, 2e-3f, 1.0f, name);
    // The point of the sRGB format: 188 of 255 reads as half intensity, not 0.737.
    if (const grader::Image* img = picture(base, "from_file")) {
        EXPECT_NEAR(img->at(8, 8, 0), 0.5f, 0.005f);
    }

    const auto mr = render(files, "metallic_roughness.frag");
    ASSERT_EQ(mr.status, shaderlab::RenderStatus::Ok) << mr.message;
    // Alpha: TEXCOORD_1 for the metallic-roughness texture, plus the occlusion strength 0.75.
    for (const char* name : {"from_file", "from_data_uri", "from_buffer_view"})
        if (const grader::Image* img = picture(mr, name)) expectTexels(*img, asLinear, 1e-4f, 1.75f, name);
    if (const grader::Image* img = picture(mr, "from_file")) {
        EXPECT_NEAR(img->at(8, 8, 0), 188.0f / 255, 1e-3f);
    }
}

TEST_F(GltfTexture, UnusableImagesWarnAndReadTheStandIns) {
    Bytes malformed(png_.begin(), png_.begin() + 8);  // the signature, then noise
    for (int i = 0; i < 200; ++i) malformed.push_back(static_cast<std::uint8_t>(i * 37 + 11));
    writeScene("malformed.gltf", quadGltf("", malformed, ""));
    writeScene("oversized.gltf", quadGltf("data:image/png;base64," + base64(oversizedPng()), {}, ""));
    writeScene("normal_mapped.gltf", quadGltf("checker.png", {}, "checker.png"));
    const std::vector<std::string> files = {"malformed.gltf", "oversized.gltf", "normal_mapped.gltf"};

    const auto r = render(files, "stand_in.frag");
    ASSERT_EQ(r.status, shaderlab::RenderStatus::Ok) << r.message;
    ASSERT_EQ(r.scenes.size(), 3u);
    // White base colour, a flat normal's blue (1) halved, neither texture usable; the normal
    // scale is 1 without a normal texture.
    for (const char* name : {"malformed", "oversized"}) {
        const grader::Image* img = picture(r, name);
        if (!img) continue;
        for (int y : {5, 40})
            for (int x : {3, 60}) {
                EXPECT_FLOAT_EQ(img->at(x, y, 0), 1.0f) << name;
                EXPECT_FLOAT_EQ(img->at(x, y, 1), 1.0f) << name;
                EXPECT_FLOAT_EQ(img->at(x, y, 2), 0.5f) << name;
                EXPECT_FLOAT_EQ(img->at(x, y, 3), 1.0f) << name;
            }
    }
    // The normal map reads linear values; both textures usable, scale 0.25.
    if (const grader::Image* img = picture(r, "normal_mapped")) {
        EXPECT_NEAR(img->at(8, 8, 0), srgbToLinear(188.0f / 255), 2e-3f);
        EXPECT_NEAR(img->at(8, 8, 2), 0.5f * static_cast<float>(texel(0, 0, 2)) / 255, 1e-3f);
        EXPECT_FLOAT_EQ(img->at(8, 8, 3), 1.0f);
    }
    const std::string warnings = imageWarnings(r);
    EXPECT_NE(warnings.find("../scenes/malformed.gltf: "), std::string::npos) << warnings;
    EXPECT_NE(warnings.find("malformed.gltf: image 'checker' (texture 0, u_base_color_texture) cannot be"),
              std::string::npos)
        << warnings;
    EXPECT_NE(warnings.find("../scenes/oversized.gltf: "), std::string::npos) << warnings;
    EXPECT_NE(warnings.find("16000x16000 pixels is more than the limit"), std::string::npos) << warnings;
    EXPECT_NE(warnings.find("white stand-in"), std::string::npos) << warnings;
    EXPECT_EQ(warnings.find("normal_mapped"), std::string::npos) << warnings;
}

TEST_F(GltfTexture, ProgramsWithoutMaterialSamplersDecodeNothing) {
    Bytes malformed(png_.begin(), png_.begin() + 8);
    writeScene("malformed.gltf", quadGltf("", malformed, ""));
    const auto plain = render({"malformed.gltf"}, "plain.frag");
    ASSERT_EQ(plain.status, shaderlab::RenderStatus::Ok) << plain.message;
    EXPECT_EQ(imageWarnings(plain), "");
    // The same scene sampled: now the image is decoded, and refused.
    const auto sampled = render({"malformed.gltf"}, "base_color.frag");
    ASSERT_EQ(sampled.status, shaderlab::RenderStatus::Ok) << sampled.message;
    EXPECT_NE(imageWarnings(sampled).find("malformed.gltf"), std::string::npos);
}

TEST_F(GltfTexture, AMaterialSamplerOfTheWrongTypeIsReported) {
    writeScene("from_file.gltf", quadGltf("checker.png", {}, ""));
    std::ofstream(lab_ / "wrong.frag") << R"(#version 330 core
uniform samplerCube u_base_color_texture;
out vec4 o_color;
void main() { o_color = texture(u_base_color_texture, vec3(1.0)); }
)";
    const auto r = render({"from_file.gltf"}, "wrong.frag");
    ASSERT_EQ(r.status, shaderlab::RenderStatus::Ok) << r.message;
    bool reported = false;
    for (const auto& d : r.diagnostics)
        reported =
            reported || (d.file == "wrong.frag" &&
                         d.message.find("u_base_color_texture is provided by the framework as sampler2D") !=
                             std::string::npos);
    EXPECT_TRUE(reported);
}

}  // namespace
