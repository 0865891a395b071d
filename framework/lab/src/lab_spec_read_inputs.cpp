// Step 3 of the lab.json parser, for a pass's inputs: which source feeds each sampler (a target's
// attachment, an image file, the six files of a cube map, or a texture the framework generates),
// how it is filtered and wrapped, and the patterns, sizes and colours of generated textures.
// Whether the target and attachment exist, and are drawn before they are read, is checked later
// (lab_spec_check_passes.cpp); whether the files exist too (lab_spec_check_files.cpp).
#include <cstdint>
#include <string>
#include <vector>

#include "lab_spec_steps.h"

namespace shaderlab::lab_spec_detail {

namespace {

const char* const kCubeFaces[6] = {"px", "nx", "py", "ny", "pz", "nz"};

}  // namespace

PassInput Reader::readInput(const json& v, const std::string& sampler, const std::string& pass_path) {
    PassInput in;
    in.sampler = sampler;
    in.path = joinKey(joinKey(pass_path, "inputs"), sampler);
    auto splitTarget = [&in](const std::string& ref) {
        const std::size_t dot = ref.find('.');
        in.source = InputSource::Target;
        in.target = ref.substr(0, dot);
        in.attachment = dot == std::string::npos ? "" : ref.substr(dot + 1);
    };
    if (v.is_string()) {
        splitTarget(v);
        return in;
    }
    int sources = 0;
    if (v.contains("target")) {
        splitTarget(v["target"]);
        ++sources;
    }
    if (v.contains("texture")) {
        in.source = InputSource::File;
        in.file = v["texture"];
        ++sources;
    }
    if (v.contains("cube")) {
        in.source = InputSource::Cube;
        const json& c = v["cube"];
        if (c.is_string()) {
            const std::string pattern = c;
            const std::size_t at = pattern.find("{face}");
            if (at == std::string::npos)
                diag_.error(joinKey(in.path, "cube"),
                            "a single path must contain {face} (replaced by px, nx, py, ny, pz, nz)");
            else
                for (const char* face : kCubeFaces)
                    in.cube_files.push_back(pattern.substr(0, at) + face + pattern.substr(at + 6));
        } else {
            in.cube_files = c.get<std::vector<std::string>>();
        }
        ++sources;
    }
    if (v.contains("generate")) {
        in.source = InputSource::Generated;
        readGenerated(v["generate"], in);
        ++sources;
    }
    if (sources != 1)
        diag_.error(in.path, sources == 0
                                 ? "give one source: \"target\", \"texture\", \"cube\" or \"generate\""
                                 : "give only one source of \"target\", \"texture\", \"cube\" and "
                                   "\"generate\"");
    if (v.contains("layers") && in.source != InputSource::File)
        diag_.error(joinKey(in.path, "layers"), "only a \"texture\" file can be cut into layers");
    if (v.contains("srgb") && (in.source == InputSource::Target))
        diag_.error(joinKey(in.path, "srgb"),
                    "applies to files and generated textures; a target's encoding is its format (\"srgb8\")");
    if (v.contains("layers")) in.layers = v["layers"];
    if (v.contains("filter")) in.filter = readFilter(v["filter"]);
    if (v.contains("wrap")) in.wrap = readWrap(v["wrap"]);
    in.srgb = v.value("srgb", false);
    return in;
}

// A texture the framework makes: its pattern and size, and the colours the pattern takes (the
// defaults when none are given).
void Reader::readGenerated(const json& g, PassInput& in) {
    GeneratedTexture& t = in.generated;
    t.pattern = g["pattern"];
    const json& size = g["size"];
    t.width = size[0];
    t.height = size.size() > 1 ? size[1].get<int>() : 1;
    t.depth = size.size() > 2 ? size[2].get<int>() : 1;
    if (g.contains("colors"))
        for (const json& c : g["colors"]) t.colors.push_back(readVec4(c));
    if (g.contains("cells")) t.cells = g["cells"];
    if (g.contains("seed")) t.seed = g["seed"].get<std::uint32_t>();
    const std::size_t need = t.pattern == "checker"    ? 2
                             : t.pattern == "gradient" ? 2
                             : t.pattern == "constant" ? 1
                                                       : 0;
    if (t.colors.empty()) {
        if (t.pattern == "checker" || t.pattern == "gradient")
            t.colors = {glm::vec4(0, 0, 0, 1), glm::vec4(1)};
        if (t.pattern == "constant") t.colors = {glm::vec4(1)};
    } else if (t.colors.size() < need || (t.pattern == "constant" && t.colors.size() != 1) ||
               (t.pattern == "checker" && t.colors.size() != 2) || t.pattern == "noise") {
        diag_.error(joinKey(joinKey(in.path, "generate"), "colors"),
                    t.pattern == "noise"
                        ? std::string("noise takes no colours (its values are uniform in [0, 1))")
                    : t.pattern == "gradient" ? std::string("a gradient needs at least two colour stops")
                    : t.pattern == "checker"  ? std::string("a checker takes exactly two colours")
                                              : std::string("a constant texture takes exactly one colour"));
    }
    const double texels = double(t.width) * t.height * t.depth;
    if (texels > 16.0 * 1024 * 1024)
        diag_.error(joinKey(joinKey(in.path, "generate"), "size"),
                    "has " + formatNumber(texels) + " texels; at most 16777216 are allowed");
}

}  // namespace shaderlab::lab_spec_detail
