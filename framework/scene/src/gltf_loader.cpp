// Loads a glTF 2.0 file (.gltf or .glb) into a shaderlab::Scene.
//
// tinygltf parses the JSON and decodes buffers; everything that indexes into those buffers is
// done here, and every index, offset, length and stride is checked before a byte is read, so a
// malformed or hostile file ends as an error "<path>: <problem>", never as a crash or an
// out-of-bounds read. The file itself is read here (not by tinygltf) so that the GLB chunk layout
// and `extensionsRequired` can be checked first, and tinygltf reaches external files only through
// callbacks that refuse anything outside the scene's folder.
//
// What it does: the default scene (or scene 0, or every root node), node transforms composed
// (matrix or TRS, mirroring ones flagged), triangle lists, strips and fans (converted to lists),
// POSITION / NORMAL / TEXCOORD_0 / TEXCOORD_1 / COLOR_0 / TANGENT with any layout the
// specification allows (KHR_mesh_quantization included), sparse accessors, interleaved views,
// Draco (KHR_draco_mesh_compression, decoded with libdraco) and meshopt (EXT_meshopt_compression,
// decoded with libmeshoptimizer) compressed data, EXT_mesh_gpu_instancing (one draw item per
// instance), flat normals when NORMAL is absent, MikkTSpace tangents when TANGENT is absent,
// metallic-roughness materials (factors and texture references), the first camera (perspective
// or orthographic), KHR_lights_punctual lights with spot cones, world-space bounds.
// What it does not: decode images (their PNG or JPEG bytes are kept; the renderer decodes those a
// program samples, see material_textures.cpp), skins and morph targets (drawn in
// their bind pose, with a warning), animations, points and lines (refused with a warning), any
// other required extension (refused, naming it; docs/scenes.md lists them).
// Buffers are read as little-endian, which is what glTF stores and what the hosts we run on are.
#include "shaderlab/scene/gltf_loader.h"

#include <draco/compression/decode.h>
#include <meshoptimizer.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <limits>
#include <map>
#include <memory>
#include <new>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "shaderlab/base/paths.h"
#include "tangent_space.h"

namespace fs = std::filesystem;

namespace shaderlab {

namespace {

// Caps that keep a hostile file from making us allocate or loop without bound. The bundled
// scenes are tens of thousands of vertices; a lab never needs anything near these. Data read
// from a bufferView is already bounded by the file size; the caps matter where a few bytes of
// JSON can ask for a lot: accessors without a bufferView (all zeros), flat-normal expansion,
// and one big mesh instanced by many nodes.
constexpr std::size_t kMaxFileBytes = std::size_t{256} << 20;
constexpr std::size_t kMaxVertices = 10'000'000;     // per accessor and per scene (~320 MB of Mesh)
constexpr std::size_t kMaxIndices = 30'000'000;      // per accessor and per scene
constexpr std::size_t kMaxUnbackedCount = 1u << 20;  // accessors without a bufferView
constexpr std::size_t kMaxDrawItems = 100'000;
constexpr std::size_t kExactBoundsBudget = 20'000'000;  // vertex transforms for exact bounds

// Thrown by the conversion code and caught in loadGltfScene: the checks sit deep in helpers, and
// unwinding to one place keeps each check a single line.
struct LoadError {
    std::string message;
};

[[noreturn]] void fail(const std::string& message) { throw LoadError{message}; }

std::string inQuotes(const std::string& s) { return "'" + s + "'"; }

// ---------------------------------------------------------------------------------------------
// External files: tinygltf asks through these callbacks, which only answer for files inside the
// scene's folder. tinygltf also retries a missing file relative to the working directory; that
// lookup is answered "does not exist", since nothing is resolved against the working directory.

struct FsGuard {
    std::string folder;   // absolute folder of the scene file, as handed to tinygltf
    std::string prefix;   // `folder` with exactly one trailing '/', what tinygltf joins URIs onto
    std::string refusal;  // first URI refused (escapes the folder, not a regular file, ...)
    std::string missing;  // first URI whose file does not exist
    std::map<std::string, std::string> approved;  // path tinygltf asked about -> canonical path
};

// Why `uri` (already percent-decoded by tinygltf) may not be read, or "" when it may.
std::string uriProblem(const std::string& uri) {
    if (uri.empty()) return "a buffer or image has an empty URI";
    if (uri.find('\0') != std::string::npos) return "URI " + inQuotes(uri) + " contains a NUL byte";
    if (uri.front() == '/') {
        return "URI " + inQuotes(uri) + " is an absolute path; it escapes the scene's folder";
    }
    const auto colon = uri.find(':');
    if (colon != std::string::npos && colon < uri.find('/')) {
        return "URI " + inQuotes(uri) + " has a scheme; only relative file names are supported";
    }
    const fs::path normal = fs::path(uri).lexically_normal();
    if (!normal.empty() && *normal.begin() == "..") {
        return "URI " + inQuotes(uri) + " uses '..' and escapes the scene's folder";
    }
    return "";
}

bool guardFileExists(const std::string& abs_filename, void* user) {
    auto* guard = static_cast<FsGuard*>(user);
    if (abs_filename.compare(0, guard->prefix.size(), guard->prefix) != 0) return false;
    const std::string uri = abs_filename.substr(guard->prefix.size());
    const std::string problem = uriProblem(uri);
    if (!problem.empty()) {
        if (guard->refusal.empty()) guard->refusal = problem;
        return false;
    }
    std::error_code ec;
    if (!fs::exists(fs::symlink_status(fs::path(guard->folder) / uri, ec))) {
        if (guard->missing.empty()) guard->missing = uri;
        return false;
    }
    const PathResult resolved = resolveInside(guard->folder, uri);
    if (!resolved.ok) {
        if (guard->refusal.empty()) guard->refusal = "URI " + inQuotes(uri) + " refused: " + resolved.error;
        return false;
    }
    guard->approved[abs_filename] = resolved.path;
    return true;
}

std::string guardExpandFilePath(const std::string& path, void*) { return path; }

bool guardReadWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                        void* user) {
    auto* guard = static_cast<FsGuard*>(user);
    const auto it = guard->approved.find(path);
    if (it == guard->approved.end()) {
        if (err) *err = "not a file inside the scene's folder";
        return false;
    }
    const FileText file = readFile(it->second, kMaxFileBytes);
    if (!file.ok) {
        if (err) *err = file.error;
        return false;
    }
    out->assign(file.text.begin(), file.text.end());
    return true;
}

bool guardWriteWholeFile(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
    if (err) *err = "the loader never writes files";
    return false;
}

// Images are kept encoded, never decoded here (the renderer decodes the ones a program samples,
// with its own checks: material_textures.cpp); this keeps tinygltf from running its image
// decoder on untrusted bytes. tinygltf hands over the bytes of a data: URI or an external file;
// an image in a bufferView is read later through the Converter's checked bufferView().
struct ImageBytes {
    std::map<int, std::vector<unsigned char>> by_image;
    std::size_t total = 0;
    std::vector<int> dropped;  // images past the kMaxFileBytes budget
};

bool keepImage(tinygltf::Image* image, const int index, std::string*, std::string*, int, int,
               const unsigned char* bytes, int size, void* user) {
    auto* kept = static_cast<ImageBytes*>(user);
    if (image == nullptr || image->bufferView >= 0 || bytes == nullptr || size <= 0) return true;
    const auto n = static_cast<std::size_t>(size);
    if (kept->total + n > kMaxFileBytes) {
        kept->dropped.push_back(index);
        return true;
    }
    kept->total += n;
    kept->by_image[index].assign(bytes, bytes + n);
    return true;
}

// ---------------------------------------------------------------------------------------------
// GLB layout. tinygltf 2.7.0 checks the BIN chunk's length without its 8-byte chunk header, so a
// BIN chunk that claims up to 8 bytes more than the file holds gets read past the end. Checking
// the whole chunk layout here first closes that.

std::uint32_t readU32(const std::string& bytes, std::size_t at) {
    std::uint32_t v = 0;
    std::memcpy(&v, bytes.data() + at, 4);
    return v;
}

// Returns the number of bytes the GLB declares (<= bytes.size()) or fails.
std::size_t checkGlbLayout(const std::string& bytes, std::vector<std::string>* warnings) {
    const std::uint64_t size = bytes.size();
    if (size < 20) {
        fail("truncated GLB: " + std::to_string(size) + " bytes, shorter than the 20-byte header");
    }
    const std::uint32_t version = readU32(bytes, 4);
    if (version != 2) fail("GLB container version " + std::to_string(version) + ", only 2 is supported");
    const std::uint64_t length = readU32(bytes, 8);
    if (length > size) {
        fail("truncated GLB: the header declares " + std::to_string(length) + " bytes but the file has " +
             std::to_string(size));
    }
    if (length < 20)
        fail("GLB header declares " + std::to_string(length) + " bytes, too few for a JSON chunk");
    if (length < size) {
        warnings->push_back(std::to_string(size - length) +
                            " bytes after the declared end of the GLB ignored");
    }
    const std::uint64_t json_length = readU32(bytes, 12);
    if (readU32(bytes, 16) != 0x4E4F534Au) fail("bad GLB: the first chunk is not a JSON chunk");
    if (json_length == 0) fail("bad GLB: the JSON chunk is empty");
    if (20 + json_length > length) {
        fail("truncated GLB: the JSON chunk of " + std::to_string(json_length) +
             " bytes runs past the end of the data (" + std::to_string(length) + " bytes)");
    }
    const std::uint64_t bin_header = 20 + json_length;
    if (bin_header < length) {
        if (bin_header + 8 > length) {
            fail("truncated GLB: the chunk header at byte " + std::to_string(bin_header) + " is cut off");
        }
        const std::uint64_t bin_length = readU32(bytes, static_cast<std::size_t>(bin_header));
        if (bin_header + 8 + bin_length > length) {
            fail("truncated GLB: the BIN chunk of " + std::to_string(bin_length) + " bytes at byte " +
                 std::to_string(bin_header) + " runs past the end of the data (" + std::to_string(length) +
                 " bytes)");
        }
    }
    return static_cast<std::size_t>(length);
}

// tinygltf turns "extras" and "extensions" into its Value type recursively, so a file nesting
// arrays a hundred thousand deep overflows the stack inside tinygltf. Real glTF nests about ten
// levels; this limit leaves generous room for extras.
constexpr int kMaxJsonDepth = 128;

void checkJsonDepth(const char* begin, const char* end) {
    int depth = 0;
    bool in_string = false;
    bool escaped = false;
    for (const char* p = begin; p != end; ++p) {
        const char c = *p;
        if (in_string) {
            if (escaped) {
                escaped = false;
            } else if (c == '\\') {
                escaped = true;
            } else if (c == '"') {
                in_string = false;
            }
        } else if (c == '"') {
            in_string = true;
        } else if (c == '[' || c == '{') {
            if (++depth > kMaxJsonDepth) {
                fail("JSON nests deeper than " + std::to_string(kMaxJsonDepth) + " levels");
            }
        } else if ((c == ']' || c == '}') && depth > 0) {
            --depth;
        }
    }
}

// JSON is checked here before tinygltf sees it, so that "not JSON" reads as that rather than as
// a parser exception text.
void checkJson(const char* begin, const char* end) {
    if (nlohmann::json::accept(begin, end)) {
        checkJsonDepth(begin, end);
        return;
    }
    try {
        const nlohmann::json parsed = nlohmann::json::parse(begin, end);
        (void)parsed;
    } catch (const nlohmann::json::exception& e) {
        fail(std::string("not valid glTF JSON (") + e.what() + ")");
    }
    fail("not valid glTF JSON");
}

// ---------------------------------------------------------------------------------------------
// Extensions. `extensionsRequired` is read from the JSON before tinygltf decodes anything, so a
// file that cannot be drawn right is refused with the extension's name and what to do, rather
// than with whatever tinygltf or the accessor checks would trip over first.

constexpr const char* kDraco = "KHR_draco_mesh_compression";
constexpr const char* kMeshopt = "EXT_meshopt_compression";
constexpr const char* kQuantization = "KHR_mesh_quantization";
constexpr const char* kInstancing = "EXT_mesh_gpu_instancing";
constexpr const char* kLights = "KHR_lights_punctual";

// Extensions the loader implements in full.
bool implemented(const std::string& ext) {
    return ext == kDraco || ext == kMeshopt || ext == kQuantization || ext == kInstancing || ext == kLights;
}

// Extensions that only change shading or texture lookups, which the lab's shaders do: the file
// still draws right without them, so they load with a warning even when required.
bool shadingOnly(const std::string& ext) {
    return ext.rfind("KHR_materials_", 0) == 0 || ext == "KHR_texture_transform";
}

std::string refusalAdvice(const std::string& ext) {
    if (ext == "KHR_texture_basisu" || ext == "EXT_texture_webp" || ext == "EXT_texture_avif" ||
        ext == "MSFT_texture_dds") {
        return "its textures use an image format shaderlab does not read; re-export the scene with "
               "PNG or JPEG textures (Blender's glTF exporter, or gltf-transform's png/jpeg commands)";
    }
    if (ext == "KHR_meshopt_compression" || ext == "MSFT_lod") {
        return "shaderlab cannot read its geometry; re-export the scene without it";
    }
    return "shaderlab does not implement it; re-export the scene without it (docs/scenes.md lists the "
           "extensions shaderlab reads)";
}

// Strings of a top-level array such as "extensionsRequired"; a malformed entry is left to
// tinygltf's own checks.
std::vector<std::string> stringArray(const nlohmann::json& doc, const char* key) {
    std::vector<std::string> out;
    const auto it = doc.find(key);
    if (it == doc.end() || !it->is_array()) return out;
    for (const auto& v : *it)
        if (v.is_string()) out.push_back(v.get<std::string>());
    return out;
}

// Checks the extensions and returns the JSON tinygltf should parse: the file's own, or a copy
// where meshopt fallback buffers (declared without data, since every view in them is compressed
// elsewhere) carry three placeholder bytes and Draco primitives lose their data-less indices
// accessor, both of which tinygltf would otherwise refuse. Empty: unchanged.
std::string checkExtensions(const char* begin, const char* end, std::vector<std::string>* warnings,
                            std::set<int>* fallback_buffers) {
    nlohmann::json doc = nlohmann::json::parse(begin, end, nullptr, false);
    if (!doc.is_object()) return "";
    const std::vector<std::string> required = stringArray(doc, "extensionsRequired");
    for (const std::string& ext : required) {
        if (implemented(ext) || shadingOnly(ext)) continue;
        fail("requires extension " + inQuotes(ext) + ": " + refusalAdvice(ext));
    }
    std::vector<std::string> used = stringArray(doc, "extensionsUsed");
    used.insert(used.end(), required.begin(), required.end());
    std::set<std::string> warned;
    for (const std::string& ext : used) {
        if (implemented(ext) || !warned.insert(ext).second) continue;
        warnings->push_back("extension " + inQuotes(ext) +
                            " is ignored: what it adds is not passed to the shaders");
    }
    bool changed = false;
    // A Draco primitive's indices accessor has no bufferView (its indices are in the compressed
    // data), which tinygltf 2.7.0 rejects; the indices come from the Draco decoder anyway.
    const auto uses = [&used](const char* ext) {
        return std::find(used.begin(), used.end(), ext) != used.end();
    };
    auto meshes = doc.find("meshes");
    if (uses(kDraco) && meshes != doc.end() && meshes->is_array()) {
        for (nlohmann::json& mesh : *meshes) {
            auto prims = mesh.is_object() ? mesh.find("primitives") : mesh.end();
            if (!mesh.is_object() || prims == mesh.end() || !prims->is_array()) continue;
            for (nlohmann::json& prim : *prims) {
                if (!prim.is_object() || !prim.contains("indices")) continue;
                const auto e = prim.find("extensions");
                if (e != prim.end() && e->is_object() && e->contains(kDraco)) {
                    prim.erase("indices");
                    changed = true;
                }
            }
        }
    }
    auto buffers = doc.find("buffers");
    if (!uses(kMeshopt) || buffers == doc.end() || !buffers->is_array()) return changed ? doc.dump() : "";
    for (std::size_t i = 0; i < buffers->size(); ++i) {
        nlohmann::json& buffer = (*buffers)[i];
        if (!buffer.is_object() || buffer.contains("uri")) continue;
        const nlohmann::json* ext = nullptr;
        if (const auto e = buffer.find("extensions"); e != buffer.end() && e->is_object())
            if (const auto m = e->find(kMeshopt); m != e->end() && m->is_object()) ext = &*m;
        if (!ext || !ext->value("fallback", false)) continue;
        buffer["uri"] = "data:application/octet-stream;base64,AAAA";
        buffer["byteLength"] = 3;
        fallback_buffers->insert(static_cast<int>(i));
        changed = true;
    }
    return changed ? doc.dump() : "";
}

// A GLB with its JSON chunk replaced (padded with spaces to 4 bytes, as the container requires).
std::string replaceGlbJson(const std::string& glb, std::size_t length, const std::string& json) {
    const std::size_t old_json = readU32(glb, 12);
    std::string padded = json;
    padded.append((4 - padded.size() % 4) % 4, ' ');
    const std::string rest = glb.substr(20 + old_json, length - 20 - old_json);
    std::string out = glb.substr(0, 12);
    const auto put = [&out](std::uint32_t v, std::size_t at) { std::memcpy(&out[at], &v, 4); };
    out.resize(20);
    put(static_cast<std::uint32_t>(20 + padded.size() + rest.size()), 8);
    put(static_cast<std::uint32_t>(padded.size()), 12);
    put(0x4E4F534Au, 16);
    return out + padded + rest;
}

// tinygltf reports several problems as lines in one string.
void appendLines(const std::string& text, const std::string& prefix, std::vector<std::string>* out) {
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line)) {
        while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
        // tinygltf quotes whole data URIs in some messages; megabytes of base64 help nobody.
        constexpr std::size_t kMaxLine = 240;
        if (line.size() > kMaxLine) line = line.substr(0, kMaxLine) + "...";
        if (!line.empty()) out->push_back(prefix + line);
    }
}

std::string joinLines(const std::string& text) {
    std::vector<std::string> lines;
    appendLines(text, "", &lines);
    std::string joined;
    for (const auto& l : lines) joined += (joined.empty() ? "" : "; ") + l;
    return joined;
}

// ---------------------------------------------------------------------------------------------
// Accessors.

// "first..end" for error messages, without wrapping when a hostile offset is near 2^64.
std::string byteRange(std::uint64_t offset, std::uint64_t length) {
    if (length > std::numeric_limits<std::uint64_t>::max() - offset) {
        return std::to_string(offset) + ".." + std::to_string(offset) + "+" + std::to_string(length);
    }
    return std::to_string(offset) + ".." + std::to_string(offset + length);
}

const char* typeName(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR:
            return "SCALAR";
        case TINYGLTF_TYPE_VEC2:
            return "VEC2";
        case TINYGLTF_TYPE_VEC3:
            return "VEC3";
        case TINYGLTF_TYPE_VEC4:
            return "VEC4";
        case TINYGLTF_TYPE_MAT2:
            return "MAT2";
        case TINYGLTF_TYPE_MAT3:
            return "MAT3";
        case TINYGLTF_TYPE_MAT4:
            return "MAT4";
        default:
            return "an unknown type";
    }
}

const char* componentTypeName(int component_type) {
    switch (component_type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
            return "BYTE";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return "UNSIGNED_BYTE";
        case TINYGLTF_COMPONENT_TYPE_SHORT:
            return "SHORT";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            return "UNSIGNED_SHORT";
        case TINYGLTF_COMPONENT_TYPE_INT:
            return "INT";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
            return "UNSIGNED_INT";
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
            return "FLOAT";
        case TINYGLTF_COMPONENT_TYPE_DOUBLE:
            return "DOUBLE";
        default:
            return "an unknown component type";
    }
}

std::size_t componentSize(int component_type) {
    switch (component_type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return 1;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            return 2;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
            return 4;
        default:
            return 0;  // INT and DOUBLE are not valid in glTF 2.0 accessors we read
    }
}

// Reads one component; the caller has checked that `p` has componentSize() readable bytes.
double readComponent(const unsigned char* p, int component_type, bool normalized) {
    switch (component_type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
            std::int8_t v;
            std::memcpy(&v, p, 1);
            return normalized ? std::max(v / 127.0, -1.0) : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
            std::uint8_t v;
            std::memcpy(&v, p, 1);
            return normalized ? v / 255.0 : v;
        }
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            std::int16_t v;
            std::memcpy(&v, p, 2);
            return normalized ? std::max(v / 32767.0, -1.0) : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            std::uint16_t v;
            std::memcpy(&v, p, 2);
            return normalized ? v / 65535.0 : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
            std::uint32_t v;
            std::memcpy(&v, p, 4);
            return v;
        }
        case TINYGLTF_COMPONENT_TYPE_FLOAT: {
            float v;
            std::memcpy(&v, p, 4);
            return v;
        }
        default:
            return 0.0;
    }
}

// What an accessor is used for decides which layouts are accepted (glTF 2.0 spec, 3.7.2.1;
// KHR_mesh_quantization widens the integer layouts of positions, normals, tangents, texcoords and
// instance transforms).
enum class Use { Position, Normal, Tangent, Texcoord, Color, Indices, Translation, Rotation, Scale };

bool isComponent(int ct, std::initializer_list<int> allowed) {
    return std::find(allowed.begin(), allowed.end(), ct) != allowed.end();
}

bool layoutAllowed(Use use, int type, int ct, bool normalized, bool quantized) {
    constexpr int kByte = TINYGLTF_COMPONENT_TYPE_BYTE, kUByte = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
    constexpr int kShort = TINYGLTF_COMPONENT_TYPE_SHORT, kUShort = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
    constexpr int kFloat = TINYGLTF_COMPONENT_TYPE_FLOAT;
    const bool any_small_int = isComponent(ct, {kByte, kUByte, kShort, kUShort});
    const bool signed_normalized = normalized && isComponent(ct, {kByte, kShort});
    switch (use) {
        case Use::Position:
        case Use::Translation:
        case Use::Scale:
            return type == TINYGLTF_TYPE_VEC3 && (ct == kFloat || (quantized && any_small_int));
        case Use::Normal:
            return type == TINYGLTF_TYPE_VEC3 && (ct == kFloat || (quantized && signed_normalized));
        case Use::Tangent:
            return type == TINYGLTF_TYPE_VEC4 && (ct == kFloat || (quantized && signed_normalized));
        case Use::Rotation:
            return type == TINYGLTF_TYPE_VEC4 && (ct == kFloat || signed_normalized);
        case Use::Texcoord:
            return type == TINYGLTF_TYPE_VEC2 &&
                   (ct == kFloat || (normalized && isComponent(ct, {kUByte, kUShort})) ||
                    (quantized && any_small_int));
        case Use::Color:
            return (type == TINYGLTF_TYPE_VEC3 || type == TINYGLTF_TYPE_VEC4) &&
                   (ct == kFloat || (normalized && isComponent(ct, {kUByte, kUShort})));
        case Use::Indices:
            return type == TINYGLTF_TYPE_SCALAR && !normalized &&
                   isComponent(ct, {kUByte, kUShort, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT});
    }
    return false;
}

const char* layoutExpected(Use use) {
    switch (use) {
        case Use::Position:
        case Use::Normal:
        case Use::Translation:
        case Use::Scale:
            return "VEC3 of FLOAT";
        case Use::Tangent:
            return "VEC4 of FLOAT";
        case Use::Rotation:
            return "VEC4 of FLOAT, or of normalized BYTE / SHORT";
        case Use::Texcoord:
            return "VEC2 of FLOAT, or of normalized UNSIGNED_BYTE / UNSIGNED_SHORT";
        case Use::Color:
            return "VEC3 or VEC4 of FLOAT, or of normalized UNSIGNED_BYTE / UNSIGNED_SHORT";
        case Use::Indices:
            return "SCALAR of UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT";
    }
    return "";
}

std::size_t typeComponents(int type) {
    switch (type) {
        case TINYGLTF_TYPE_VEC2:
            return 2;
        case TINYGLTF_TYPE_VEC3:
            return 3;
        case TINYGLTF_TYPE_VEC4:
            return 4;
        default:
            return 1;
    }
}

struct Bytes {
    const unsigned char* data = nullptr;
    std::size_t size = 0;
};

class Converter {
  public:
    Converter(const tinygltf::Model& model, Scene* scene, std::vector<std::string>* warnings,
              std::set<int> fallback_buffers, ImageBytes* images)
        : model_(model),
          scene_(*scene),
          warnings_(*warnings),
          fallback_buffers_(std::move(fallback_buffers)),
          images_(*images) {}

    void run();

  private:
    // Validates bufferView `index` and the buffer it lies in; `who` names the referrer. A view
    // compressed with EXT_meshopt_compression answers with its decoded bytes.
    Bytes bufferView(int index, const std::string& who) const {
        if (index < 0 || static_cast<std::size_t>(index) >= model_.bufferViews.size()) {
            fail(who + ": bufferView " + std::to_string(index) + " does not exist (the file has " +
                 std::to_string(model_.bufferViews.size()) + ")");
        }
        if (const auto it = decoded_views_.find(index); it != decoded_views_.end())
            return Bytes{it->second.data(), it->second.size()};
        const tinygltf::BufferView& view = model_.bufferViews[static_cast<std::size_t>(index)];
        const std::string name = "bufferView " + std::to_string(index);
        if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model_.buffers.size()) {
            fail(name + ": buffer " + std::to_string(view.buffer) + " does not exist (the file has " +
                 std::to_string(model_.buffers.size()) + ")");
        }
        if (fallback_buffers_.count(view.buffer)) {
            fail(name + " lies in buffer " + std::to_string(view.buffer) +
                 ", a meshopt fallback buffer without data, and is not itself meshopt-compressed");
        }
        const auto& data = model_.buffers[static_cast<std::size_t>(view.buffer)].data;
        if (view.byteLength > data.size() || view.byteOffset > data.size() - view.byteLength) {
            fail(name + ": bytes " + byteRange(view.byteOffset, view.byteLength) + " lie outside buffer " +
                 std::to_string(view.buffer) + " which has " + std::to_string(data.size()) + " bytes");
        }
        return Bytes{data.data() + view.byteOffset, view.byteLength};
    }

    // Decodes accessor `index` into `out` (count * components values, components from the
    // accessor's type) after checking that every element it names lies inside its bufferView.
    // `role` reads like "POSITION of mesh 'torus'".
    template <typename T>
    std::size_t readAccessor(int index, const std::string& role, Use use, std::vector<T>* out,
                             std::size_t* components_out = nullptr) const {
        if (index < 0 || static_cast<std::size_t>(index) >= model_.accessors.size()) {
            fail("accessor " + std::to_string(index) + " (" + role + ") does not exist (the file has " +
                 std::to_string(model_.accessors.size()) + ")");
        }
        const tinygltf::Accessor& acc = model_.accessors[static_cast<std::size_t>(index)];
        const std::string who = "accessor " + std::to_string(index) + " (" + role + ")";
        if (!layoutAllowed(use, acc.type, acc.componentType, acc.normalized, quantized_)) {
            fail(who + ": is " + typeName(acc.type) + " of " + (acc.normalized ? "normalized " : "") +
                 componentTypeName(acc.componentType) + ", expected " + layoutExpected(use) +
                 (quantized_ ? " (or a KHR_mesh_quantization layout)" : ""));
        }
        const std::size_t limit = use == Use::Indices ? kMaxIndices : kMaxVertices;
        if (acc.count == 0) fail(who + ": count is 0");
        if (acc.count > limit) {
            fail(who + ": count " + std::to_string(acc.count) + " is over the limit of " +
                 std::to_string(limit));
        }
        const std::size_t components = typeComponents(acc.type);
        if (components_out) *components_out = components;
        const std::size_t comp_size = componentSize(acc.componentType);
        const std::size_t element = comp_size * components;
        out->assign(acc.count * components, T{});

        if (acc.bufferView == -1 && acc.count > kMaxUnbackedCount) {
            fail(who + ": count " + std::to_string(acc.count) +
                 " without a bufferView is over the limit of " + std::to_string(kMaxUnbackedCount));
        }
        if (acc.bufferView != -1) {
            const Bytes view = bufferView(acc.bufferView, who);
            const std::size_t declared = viewStride(acc.bufferView);
            if (declared != 0 && (declared < element || declared > 252 || declared % 4 != 0)) {
                fail(who + ": byteStride " + std::to_string(declared) + " of bufferView " +
                     std::to_string(acc.bufferView) + " is invalid for " + std::to_string(element) +
                     "-byte elements (must be 0, or a multiple of 4 in " + std::to_string(element) +
                     "..252)");
            }
            const std::size_t stride = declared != 0 ? declared : element;
            // Both fit in 64 bits: count <= 150M, stride <= 252, offset checked against size first.
            const std::uint64_t span = static_cast<std::uint64_t>(stride) * (acc.count - 1) + element;
            if (acc.byteOffset > view.size || span > view.size - acc.byteOffset) {
                fail(who + ": reads bytes " + byteRange(acc.byteOffset, span) + " of bufferView " +
                     std::to_string(acc.bufferView) + " which has " + std::to_string(view.size) + " bytes");
            }
            const unsigned char* base = view.data + acc.byteOffset;
            for (std::size_t i = 0; i < acc.count; ++i) {
                const unsigned char* element_start = base + i * stride;
                for (std::size_t c = 0; c < components; ++c) {
                    (*out)[i * components + c] = static_cast<T>(
                        readComponent(element_start + c * comp_size, acc.componentType, acc.normalized));
                }
            }
        }
        // else: an accessor without a bufferView is all zeros (spec 3.6.2.3), sparse or not.

        if (acc.sparse.isSparse) applySparse(acc, who, components, comp_size, out);
        return acc.count;
    }

    // A view's byteStride; a meshopt-compressed view's is its extension's.
    std::size_t viewStride(int index) const {
        const auto it = meshopt_strides_.find(index);
        if (it != meshopt_strides_.end()) return it->second;
        return model_.bufferViews[static_cast<std::size_t>(index)].byteStride;
    }

    // Overwrites the elements a sparse accessor names (spec 3.6.2.3): indices strictly
    // increasing and below count, values tightly packed.
    template <typename T>
    void applySparse(const tinygltf::Accessor& acc, const std::string& who, std::size_t components,
                     std::size_t comp_size, std::vector<T>* out) const {
        const auto& sparse = acc.sparse;
        if (sparse.count <= 0 || static_cast<std::size_t>(sparse.count) > acc.count) {
            fail(who + ": sparse count " + std::to_string(sparse.count) + " must be in 1.." +
                 std::to_string(acc.count));
        }
        const int index_type = sparse.indices.componentType;
        if (index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
            index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
            index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
            fail(who + ": sparse indices are " + componentTypeName(index_type) +
                 ", expected UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
        }
        const std::size_t n = static_cast<std::size_t>(sparse.count);
        const std::size_t index_size = componentSize(index_type);
        const std::size_t element = comp_size * components;
        const Bytes idx_view = bufferView(sparse.indices.bufferView, who + " sparse indices");
        const Bytes val_view = bufferView(sparse.values.bufferView, who + " sparse values");
        const auto fits = [&](const Bytes& view, int offset, std::uint64_t bytes, const char* what) {
            if (offset < 0)
                fail(who + ": sparse " + what + " byteOffset " + std::to_string(offset) + " is negative");
            if (static_cast<std::size_t>(offset) > view.size ||
                bytes > view.size - static_cast<std::size_t>(offset)) {
                fail(who + ": sparse " + what + " read bytes " +
                     byteRange(static_cast<std::uint64_t>(offset), bytes) + " of a bufferView which has " +
                     std::to_string(view.size) + " bytes");
            }
        };
        fits(idx_view, sparse.indices.byteOffset, static_cast<std::uint64_t>(n) * index_size, "indices");
        fits(val_view, sparse.values.byteOffset, static_cast<std::uint64_t>(n) * element, "values");
        const unsigned char* indices = idx_view.data + sparse.indices.byteOffset;
        const unsigned char* values = val_view.data + sparse.values.byteOffset;
        double previous = -1.0;
        for (std::size_t k = 0; k < n; ++k) {
            const double target = readComponent(indices + k * index_size, index_type, false);
            if (target >= static_cast<double>(acc.count) || target <= previous) {
                fail(who + ": sparse index " + std::to_string(static_cast<std::uint64_t>(target)) +
                     " at position " + std::to_string(k) + " is out of range or not increasing (count " +
                     std::to_string(acc.count) + ")");
            }
            previous = target;
            const std::size_t at = static_cast<std::size_t>(target);
            for (std::size_t c = 0; c < components; ++c) {
                (*out)[at * components + c] = static_cast<T>(
                    readComponent(values + k * element + c * comp_size, acc.componentType, acc.normalized));
            }
        }
    }

    std::string meshLabel(std::size_t mesh_index) const {
        const std::string& name = model_.meshes[mesh_index].name;
        return name.empty() ? "mesh " + std::to_string(mesh_index) : "mesh " + inQuotes(name);
    }

    void decodeMeshoptViews();
    void decodeDraco(const tinygltf::Primitive& prim, const std::string& where,
                     std::map<std::string, std::pair<std::vector<float>, std::size_t>>* attributes,
                     std::vector<std::uint32_t>* indices, bool* has_indices) const;
    int convertPrimitive(std::size_t mesh_index, std::size_t prim_index);
    std::vector<glm::mat4> instanceTransforms(std::size_t node_index) const;
    void convertImages();
    void convertMaterials();
    glm::mat4 localMatrix(std::size_t node_index) const;
    glm::mat4 localMatrixUnchecked(std::size_t node_index) const;
    std::vector<int> rootNodes() const;
    void walkNodes();
    void visitNode(std::size_t node_index, const glm::mat4& world);
    void addLight(std::size_t node_index, const glm::mat4& world);
    void computeBounds();
    void placeCamera();
    void checkCamera() const;

    const tinygltf::Model& model_;
    Scene& scene_;
    std::vector<std::string>& warnings_;
    std::set<int> fallback_buffers_;
    ImageBytes& images_;
    bool quantized_ = false;                                   // KHR_mesh_quantization is used
    std::map<int, std::vector<unsigned char>> decoded_views_;  // meshopt view -> its bytes
    std::map<int, std::size_t> meshopt_strides_;
    std::set<std::string> warned_;                                  // one warning per kind and mesh
    std::map<std::pair<std::size_t, std::size_t>, int> converted_;  // (mesh, primitive) -> Scene mesh
    std::size_t total_vertices_ = 0;
    std::size_t total_indices_ = 0;
    int camera_node_ = -1;
    glm::mat4 camera_world_{1.0f};
};

bool finite(const std::vector<double>& values) {
    return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
}

// glTF numbers are doubles; 1e300 is finite there but infinite as the float we store.
bool finiteMatrix(const glm::mat4& m) {
    for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) {
            if (!std::isfinite(m[c][r])) return false;
        }
    }
    return true;
}

bool finiteVec(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

glm::vec3 faceNormal(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
    const glm::vec3 n = glm::cross(b - a, c - a);
    const float len = glm::length(n);
    // A degenerate triangle has no normal; any unit vector keeps the shader's normalize() finite.
    return len > 0.0f && std::isfinite(len) ? n / len : glm::vec3(0.0f, 0.0f, 1.0f);
}

// A whole number from an extension object; `fallback` when absent and not required.
std::uint64_t extensionNumber(const tinygltf::Value& object, const char* key, const std::string& who,
                              bool required, std::uint64_t fallback = 0) {
    if (!object.Has(key)) {
        if (required) fail(who + ": \"" + key + "\" is missing");
        return fallback;
    }
    const tinygltf::Value& v = object.Get(key);
    const double d = v.IsNumber() ? v.GetNumberAsDouble() : -1.0;
    if (!(d >= 0.0) || d != std::floor(d) || d > 9.0e15) {
        fail(who + ": \"" + key + "\" must be a whole number >= 0");
    }
    return static_cast<std::uint64_t>(d);
}

std::string extensionString(const tinygltf::Value& object, const char* key, const std::string& who,
                            const std::string& fallback) {
    if (!object.Has(key)) return fallback;
    const tinygltf::Value& v = object.Get(key);
    if (!v.IsString()) fail(who + ": \"" + key + "\" must be a string");
    return v.Get<std::string>();
}

// EXT_meshopt_compression: every compressed view is decoded once, up front, with the decoder and
// filters of libmeshoptimizer (which is written to be safe on untrusted input; its parameter
// asserts are checked here first).
void Converter::decodeMeshoptViews() {
    constexpr std::uint64_t kMaxDecodedBytes = std::uint64_t{512} << 20;
    std::uint64_t total = 0;
    for (std::size_t i = 0; i < model_.bufferViews.size(); ++i) {
        const tinygltf::BufferView& view = model_.bufferViews[i];
        const auto ext = view.extensions.find(kMeshopt);
        if (ext == view.extensions.end()) continue;
        const tinygltf::Value& e = ext->second;
        const std::string who = "bufferView " + std::to_string(i) + " (" + kMeshopt + ")";
        if (!e.IsObject()) fail(who + ": the extension must be an object");
        const std::uint64_t buffer = extensionNumber(e, "buffer", who, true);
        const std::uint64_t offset = extensionNumber(e, "byteOffset", who, false, 0);
        const std::uint64_t length = extensionNumber(e, "byteLength", who, true);
        const std::uint64_t stride = extensionNumber(e, "byteStride", who, true);
        const std::uint64_t count = extensionNumber(e, "count", who, true);
        const std::string mode = extensionString(e, "mode", who, "");
        const std::string filter = extensionString(e, "filter", who, "NONE");
        if (buffer >= model_.buffers.size()) {
            fail(who + ": buffer " + std::to_string(buffer) + " does not exist (the file has " +
                 std::to_string(model_.buffers.size()) + ")");
        }
        if (fallback_buffers_.count(static_cast<int>(buffer)))
            fail(who + ": its compressed data lies in a fallback buffer, which holds none");
        const auto& data = model_.buffers[buffer].data;
        if (length > data.size() || offset > data.size() - length) {
            fail(who + ": bytes " + byteRange(offset, length) + " lie outside buffer " +
                 std::to_string(buffer) + " which has " + std::to_string(data.size()) + " bytes");
        }
        if (count == 0 || count > kMaxIndices)
            fail(who + ": count must be in 1.." + std::to_string(kMaxIndices));
        if (stride == 0 || stride > 256) fail(who + ": byteStride must be in 1..256");
        total += count * stride;
        if (total > kMaxDecodedBytes) fail(who + ": the decoded data would exceed 512 MiB");
        std::vector<unsigned char> out(static_cast<std::size_t>(count * stride));
        const unsigned char* src = data.data() + offset;
        int rc = 0;
        if (mode == "ATTRIBUTES") {
            if (stride % 4 != 0) fail(who + ": ATTRIBUTES need a byteStride that is a multiple of 4");
            rc = meshopt_decodeVertexBuffer(out.data(), count, stride, src, length);
        } else if (mode == "TRIANGLES" || mode == "INDICES") {
            if (stride != 2 && stride != 4) fail(who + ": " + mode + " need a byteStride of 2 or 4");
            if (mode == "TRIANGLES" && count % 3 != 0) fail(who + ": TRIANGLES need a count divisible by 3");
            rc = mode == "TRIANGLES" ? meshopt_decodeIndexBuffer(out.data(), count, stride, src, length)
                                     : meshopt_decodeIndexSequence(out.data(), count, stride, src, length);
        } else {
            fail(who + ": unknown mode " + inQuotes(mode) + " (ATTRIBUTES, TRIANGLES or INDICES)");
        }
        if (rc != 0)
            fail(who + ": the compressed data is corrupt (meshopt error " + std::to_string(rc) + ")");
        if (filter != "NONE" && mode != "ATTRIBUTES")
            fail(who + ": filter " + inQuotes(filter) + " needs ATTRIBUTES");
        if (filter == "OCTAHEDRAL") {
            if (stride != 4 && stride != 8)
                fail(who + ": the OCTAHEDRAL filter needs a byteStride of 4 or 8");
            meshopt_decodeFilterOct(out.data(), count, stride);
        } else if (filter == "QUATERNION") {
            if (stride != 8) fail(who + ": the QUATERNION filter needs a byteStride of 8");
            meshopt_decodeFilterQuat(out.data(), count, stride);
        } else if (filter == "EXPONENTIAL") {
            meshopt_decodeFilterExp(out.data(), count, stride);
        } else if (filter != "NONE") {
            fail(who + ": unknown filter " + inQuotes(filter));
        }
        if (mode == "ATTRIBUTES" && view.byteStride == 0) meshopt_strides_[static_cast<int>(i)] = stride;
        decoded_views_[static_cast<int>(i)] = std::move(out);
    }
}

// KHR_draco_mesh_compression: the primitive's geometry is in one Draco-compressed bufferView; its
// accessors describe the decoded data and name no bufferView. Decoded with libdraco; every
// attribute comes out as floats (normalized integers scaled as the accessor says).
void Converter::decodeDraco(const tinygltf::Primitive& prim, const std::string& where,
                            std::map<std::string, std::pair<std::vector<float>, std::size_t>>* attributes,
                            std::vector<std::uint32_t>* indices, bool* has_indices) const {
    const tinygltf::Value& e = prim.extensions.at(kDraco);
    const std::string who = where + " (" + kDraco + ")";
    if (!e.IsObject() || !e.Has("attributes") || !e.Get("attributes").IsObject())
        fail(who + ": the extension needs \"bufferView\" and an \"attributes\" object");
    const std::uint64_t view_index = extensionNumber(e, "bufferView", who, true);
    if (view_index > static_cast<std::uint64_t>(std::numeric_limits<int>::max()))
        fail(who + ": bufferView is out of range");
    const Bytes bytes = bufferView(static_cast<int>(view_index), who);
    draco::DecoderBuffer buffer;
    buffer.Init(reinterpret_cast<const char*>(bytes.data), bytes.size);
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
    if (!decoded.ok())
        fail(who + ": Draco could not decode the data (" + decoded.status().error_msg_string() + ")");
    const std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
    if (!mesh) fail(who + ": Draco decoded no mesh");
    const std::size_t points = mesh->num_points();
    if (points == 0 || points > kMaxVertices) fail(who + ": " + std::to_string(points) + " decoded vertices");
    if (static_cast<std::uint64_t>(mesh->num_faces()) * 3 > kMaxIndices) fail(who + ": too many faces");
    const tinygltf::Value& names = e.Get("attributes");
    for (const std::string& name : names.Keys()) {
        const tinygltf::Value& id = names.Get(name);
        if (!id.IsNumber()) fail(who + ": attribute " + inQuotes(name) + " must name a Draco attribute id");
        const draco::PointAttribute* att =
            mesh->GetAttributeByUniqueId(static_cast<std::uint32_t>(id.GetNumberAsInt()));
        if (!att) fail(who + ": attribute " + inQuotes(name) + " names a Draco attribute the data lacks");
        const int components = att->num_components();
        if (components < 1 || components > 4)
            fail(who + ": attribute " + inQuotes(name) + " has " + std::to_string(components) +
                 " components");
        std::vector<float> values(points * static_cast<std::size_t>(components));
        for (std::size_t p = 0; p < points; ++p) {
            const draco::AttributeValueIndex v =
                att->mapped_index(draco::PointIndex(static_cast<std::uint32_t>(p)));
            if (v.value() >= att->size() ||
                !att->ConvertValue<float>(v, static_cast<std::int8_t>(components),
                                          &values[p * static_cast<std::size_t>(components)]))
                fail(who + ": attribute " + inQuotes(name) + " could not be read as numbers");
        }
        (*attributes)[name] = {std::move(values), static_cast<std::size_t>(components)};
    }
    indices->clear();
    indices->reserve(static_cast<std::size_t>(mesh->num_faces()) * 3);
    for (draco::FaceIndex f(0); f < mesh->num_faces(); ++f) {
        const auto& face = mesh->face(f);
        for (int k = 0; k < 3; ++k) indices->push_back(face[k].value());
    }
    *has_indices = true;
}

// Triangle-list indices for a primitive's mode; strips and fans as the glTF 2.0 specification
// (3.7.2.1) numbers their triangles, so the winding of every triangle matches the first's.
std::vector<std::uint32_t> triangleList(int mode, const std::vector<std::uint32_t>& in) {
    if (mode == TINYGLTF_MODE_TRIANGLE_STRIP || mode == TINYGLTF_MODE_TRIANGLE_FAN) {
        std::vector<std::uint32_t> out;
        if (in.size() < 3) return out;
        out.reserve((in.size() - 2) * 3);
        for (std::size_t i = 0; i + 2 < in.size(); ++i) {
            if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
                out.insert(out.end(), {in[i], in[i + 1 + i % 2], in[i + 2 - i % 2]});
            } else {
                out.insert(out.end(), {in[i + 1], in[i + 2], in[0]});
            }
        }
        return out;
    }
    return in;
}

int Converter::convertPrimitive(std::size_t mesh_index, std::size_t prim_index) {
    const auto key = std::make_pair(mesh_index, prim_index);
    if (const auto it = converted_.find(key); it != converted_.end()) return it->second;

    const tinygltf::Mesh& src = model_.meshes[mesh_index];
    const tinygltf::Primitive& prim = src.primitives[prim_index];
    const std::string label = meshLabel(mesh_index);
    const std::string where =
        label + (src.primitives.size() > 1 ? " primitive " + std::to_string(prim_index) : "");

    Mesh mesh;
    mesh.name = src.name.empty() ? "mesh" + std::to_string(mesh_index) : src.name;
    if (src.primitives.size() > 1) mesh.name += "#" + std::to_string(prim_index);

    if (prim.attributes.count("POSITION") == 0) fail(where + " has no POSITION attribute");
    if (!prim.targets.empty() && warned_.insert("morph " + label).second) {
        warnings_.push_back(where + ": " + std::to_string(prim.targets.size()) +
                            " morph targets ignored; drawn in its base shape");
    }

    // Draco-compressed primitives bring their attributes and indices decoded.
    std::map<std::string, std::pair<std::vector<float>, std::size_t>> draco_attributes;
    std::vector<std::uint32_t> draco_indices;
    bool draco = false;
    if (prim.extensions.count(kDraco) != 0)
        decodeDraco(prim, where, &draco_attributes, &draco_indices, &draco);

    // Reads attribute `name` as floats; returns its element count, 0 when the primitive has none.
    std::vector<float> values;
    const auto read = [&](const char* name, Use use, std::size_t* components) -> std::size_t {
        const auto it = prim.attributes.find(name);
        if (it == prim.attributes.end()) return 0;
        const std::string role = std::string(name) + " of " + label;
        if (draco) {
            const auto d = draco_attributes.find(name);
            if (d != draco_attributes.end()) {
                values = d->second.first;
                *components = d->second.second;
                const std::size_t want = use == Use::Texcoord  ? 2
                                         : use == Use::Color   ? *components
                                         : use == Use::Tangent ? 4
                                                               : 3;
                if (*components != want || (use == Use::Color && want < 3))
                    fail(where + ": Draco attribute " + name + " has " + std::to_string(*components) +
                         " components");
                return values.size() / *components;
            }
        }
        return readAccessor(it->second, role, use, &values, components);
    };
    std::size_t components = 0;
    const std::size_t vertex_count = read("POSITION", Use::Position, &components);
    if (!std::all_of(values.begin(), values.end(), [](float v) { return std::isfinite(v); })) {
        fail(where + ": POSITION contains non-finite values");
    }
    mesh.positions.resize(vertex_count);
    for (std::size_t i = 0; i < vertex_count; ++i) {
        mesh.positions[i] = glm::vec3(values[3 * i], values[3 * i + 1], values[3 * i + 2]);
    }
    const auto sameCount = [&](const char* name, std::size_t n) {
        if (n != vertex_count) {
            fail(where + ": " + name + " has " + std::to_string(n) + " elements but POSITION has " +
                 std::to_string(vertex_count));
        }
    };

    if (const std::size_t n = read("NORMAL", Use::Normal, &components)) {
        sameCount("NORMAL", n);
        mesh.normals.resize(n);
        for (std::size_t i = 0; i < n; ++i) {
            const glm::vec3 v(values[3 * i], values[3 * i + 1], values[3 * i + 2]);
            const float len = glm::length(v);
            // The spec requires unit normals; exporters are sloppy, and a shader that forgets to
            // normalize should not be graded on someone else's rounding.
            mesh.normals[i] = len > 0.0f && std::isfinite(len) ? v / len : glm::vec3(0.0f, 0.0f, 1.0f);
        }
    }

    // glTF puts (0, 0) at an image's top-left, OpenGL texture coordinates at the row uploaded
    // first, which the framework makes the image's bottom row: t = 1 - v keeps an image upright on
    // a mesh as in a fullscreen pass.
    const auto texcoords = [&](const char* name, std::vector<glm::vec2>* out) {
        const std::size_t n = read(name, Use::Texcoord, &components);
        if (n == 0) return false;
        sameCount(name, n);
        out->resize(n);
        for (std::size_t i = 0; i < n; ++i) {
            const glm::vec2 uv(values[2 * i], 1.0f - values[2 * i + 1]);
            (*out)[i] = std::isfinite(uv.x) && std::isfinite(uv.y) ? uv : glm::vec2(0.0f);
        }
        return true;
    };
    mesh.had_texcoords = texcoords("TEXCOORD_0", &mesh.texcoords);
    if (!mesh.had_texcoords) mesh.texcoords.assign(vertex_count, glm::vec2(0.0f));
    texcoords("TEXCOORD_1", &mesh.texcoords1);

    if (const std::size_t n = read("COLOR_0", Use::Color, &components)) {
        sameCount("COLOR_0", n);
        mesh.colors.resize(n);
        for (std::size_t i = 0; i < n; ++i) {
            glm::vec4 c(1.0f);
            for (std::size_t k = 0; k < components; ++k) c[static_cast<int>(k)] = values[i * components + k];
            mesh.colors[i] = std::isfinite(c.r + c.g + c.b + c.a) ? c : glm::vec4(1.0f);
        }
    }
    if (const std::size_t n = read("TANGENT", Use::Tangent, &components)) {
        sameCount("TANGENT", n);
        mesh.tangents.resize(n);
        for (std::size_t i = 0; i < n; ++i) {
            const glm::vec3 t(values[4 * i], values[4 * i + 1], values[4 * i + 2]);
            const float len = glm::length(t);
            mesh.tangents[i] =
                glm::vec4(len > 0.0f && std::isfinite(len) ? t / len : glm::vec3(1.0f, 0.0f, 0.0f),
                          values[4 * i + 3] < 0.0f ? -1.0f : 1.0f);
        }
    }
    for (const auto& [name, accessor] : prim.attributes) {
        (void)accessor;
        if ((name.rfind("JOINTS_", 0) == 0 || name.rfind("WEIGHTS_", 0) == 0) &&
            warned_.insert("skin " + label).second)
            warnings_.push_back(where + ": skinning attributes ignored; drawn in its bind pose");
    }

    std::vector<std::uint32_t> indices;
    if (draco) {
        indices = std::move(draco_indices);
    } else if (prim.indices != -1) {
        readAccessor(prim.indices, std::string("indices of ") + label, Use::Indices, &indices);
    } else {
        indices.resize(vertex_count);
        for (std::size_t i = 0; i < vertex_count; ++i) indices[i] = static_cast<std::uint32_t>(i);
    }
    for (std::size_t i = 0; i < indices.size(); ++i) {
        if (indices[i] >= vertex_count) {
            fail((draco ? where + " (" + kDraco + ")"
                        : "accessor " + std::to_string(prim.indices) + " (indices of " + label + ")") +
                 ": index " + std::to_string(indices[i]) + " at position " + std::to_string(i) +
                 " is out of range: the primitive has " + std::to_string(vertex_count) + " vertices");
        }
    }
    const int mode = prim.mode == -1 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
    if (mode == TINYGLTF_MODE_TRIANGLES && indices.size() % 3 != 0) {
        fail(where + ": " + std::to_string(indices.size()) + " indices is not a whole number of triangles");
    }
    mesh.indices = triangleList(mode, indices);
    if (mesh.indices.empty()) fail(where + ": fewer than 3 vertices, so no triangle to draw");

    if (mesh.normals.empty()) {
        // Flat normals need one vertex per triangle corner: un-share every vertex.
        const std::size_t corners = mesh.indices.size();
        if (corners > kMaxVertices) fail(where + ": too many triangles to generate flat normals");
        const auto unshare = [&](auto* attribute) {
            if (attribute->empty()) return;
            std::remove_reference_t<decltype(*attribute)> out(corners);
            for (std::size_t i = 0; i < corners; ++i) out[i] = (*attribute)[mesh.indices[i]];
            *attribute = std::move(out);
        };
        unshare(&mesh.positions);
        unshare(&mesh.texcoords);
        unshare(&mesh.texcoords1);
        unshare(&mesh.colors);
        unshare(&mesh.tangents);
        mesh.normals.resize(corners);
        for (std::size_t t = 0; t < corners; t += 3) {
            const glm::vec3 n = faceNormal(mesh.positions[t], mesh.positions[t + 1], mesh.positions[t + 2]);
            mesh.normals[t] = mesh.normals[t + 1] = mesh.normals[t + 2] = n;
        }
        for (std::size_t i = 0; i < corners; ++i) mesh.indices[i] = static_cast<std::uint32_t>(i);
        mesh.had_normals = false;
        warnings_.push_back("normals generated flat for " + where);
    }
    if (mesh.tangents.empty() && mesh.had_texcoords) {
        mesh.tangents = generateTangents(mesh.positions, mesh.normals, mesh.texcoords, mesh.indices);
        mesh.tangents_generated = true;
    }

    total_vertices_ += mesh.positions.size();
    total_indices_ += mesh.indices.size();
    if (total_vertices_ > kMaxVertices || total_indices_ > kMaxIndices) {
        fail("the scene has more than " + std::to_string(kMaxVertices) + " vertices or " +
             std::to_string(kMaxIndices) + " indices");
    }

    scene_.meshes.push_back(std::move(mesh));
    const int id = static_cast<int>(scene_.meshes.size() - 1);
    converted_[key] = id;
    return id;
}

void Converter::convertImages() {
    for (int i : images_.dropped)
        warnings_.push_back("image " + std::to_string(i) + ": the scene's images exceed " +
                            std::to_string(kMaxFileBytes >> 20) + " MiB in all; this one is not kept");
    for (std::size_t i = 0; i < model_.images.size(); ++i) {
        const tinygltf::Image& src = model_.images[i];
        TextureImage image;
        image.name = src.name.empty() ? "image" + std::to_string(i) : src.name;
        if (src.bufferView >= 0) {
            // A bad view loses this image only: the renderer binds a white texture in its place.
            try {
                const Bytes view = bufferView(src.bufferView, "image " + std::to_string(i));
                image.bytes.assign(view.data, view.data + view.size);
            } catch (const LoadError& e) {
                warnings_.push_back(e.message + "; the image is left out");
            }
        } else if (auto it = images_.by_image.find(static_cast<int>(i)); it != images_.by_image.end()) {
            image.bytes = std::move(it->second);
        }
        scene_.images.push_back(std::move(image));
    }
}

void Converter::convertMaterials() {
    convertImages();
    for (std::size_t i = 0; i < model_.textures.size(); ++i) {
        const tinygltf::Texture& src = model_.textures[i];
        Texture t;
        if (src.source >= 0 && static_cast<std::size_t>(src.source) < model_.images.size()) {
            const tinygltf::Image& image = model_.images[static_cast<std::size_t>(src.source)];
            t.image = src.source;
            t.image_uri = image.uri.rfind("data:", 0) == 0 ? std::string() : image.uri;
            t.mime_type = image.mimeType;
        }
        if (src.sampler >= 0 && static_cast<std::size_t>(src.sampler) < model_.samplers.size()) {
            const tinygltf::Sampler& sampler = model_.samplers[static_cast<std::size_t>(src.sampler)];
            t.mag_filter = sampler.magFilter;
            t.min_filter = sampler.minFilter;
            t.wrap_s = sampler.wrapS;
            t.wrap_t = sampler.wrapT;
        }
        scene_.textures.push_back(std::move(t));
    }
    const auto textureRef = [&](const std::string& who, int index, int texcoord, double scale, bool srgb) {
        TextureRef ref;
        if (index < 0) return ref;
        if (static_cast<std::size_t>(index) >= scene_.textures.size()) {
            warnings_.push_back(who + ": texture " + std::to_string(index) +
                                " does not exist; slot left empty");
            return ref;
        }
        if (texcoord < 0 || texcoord > 1) {
            warnings_.push_back(who + ": reads TEXCOORD_" + std::to_string(texcoord) +
                                "; only TEXCOORD_0 and TEXCOORD_1 are passed to shaders");
        }
        ref.texture = index;
        ref.texcoord = texcoord;
        ref.scale = std::isfinite(scale) ? static_cast<float>(scale) : 1.0f;
        // Colour textures hold sRGB-encoded values, data textures linear ones (glTF 2.0, 3.9).
        if (srgb) scene_.textures[static_cast<std::size_t>(index)].srgb = true;
        return ref;
    };
    for (std::size_t i = 0; i < model_.materials.size(); ++i) {
        const tinygltf::Material& src = model_.materials[i];
        const std::string who = "material " + std::to_string(i);
        Material m;
        m.name = src.name.empty() ? "material" + std::to_string(i) : src.name;
        const auto& pbr = src.pbrMetallicRoughness;
        const auto& f = pbr.baseColorFactor;
        const glm::vec4 color = f.size() == 4 ? glm::vec4(static_cast<float>(f[0]), static_cast<float>(f[1]),
                                                          static_cast<float>(f[2]), static_cast<float>(f[3]))
                                              : glm::vec4(std::numeric_limits<float>::quiet_NaN());
        if (std::isfinite(color.r + color.g + color.b + color.a)) {
            m.base_color = color;
        } else {
            warnings_.push_back(who + ": baseColorFactor is not 4 finite numbers; white used");
        }
        const auto unit = [&](double v, float fallback, const char* name) {
            if (std::isfinite(v) && v >= 0.0 && v <= 1.0) return static_cast<float>(v);
            warnings_.push_back(who + ": " + name + " must be in 0..1; " + std::to_string(fallback) +
                                " used");
            return fallback;
        };
        m.metallic = unit(pbr.metallicFactor, 1.0f, "metallicFactor");
        m.roughness = unit(pbr.roughnessFactor, 1.0f, "roughnessFactor");
        if (src.emissiveFactor.size() == 3 && finite(src.emissiveFactor)) {
            m.emissive = glm::vec3(static_cast<float>(src.emissiveFactor[0]),
                                   static_cast<float>(src.emissiveFactor[1]),
                                   static_cast<float>(src.emissiveFactor[2]));
        }
        m.double_sided = src.doubleSided;
        m.alpha_mode = src.alphaMode == "MASK"    ? AlphaMode::Mask
                       : src.alphaMode == "BLEND" ? AlphaMode::Blend
                                                  : AlphaMode::Opaque;
        m.alpha_cutoff = std::isfinite(src.alphaCutoff) ? static_cast<float>(src.alphaCutoff) : 0.5f;
        m.base_color_texture = textureRef(who + " baseColorTexture", pbr.baseColorTexture.index,
                                          pbr.baseColorTexture.texCoord, 1.0, true);
        m.metallic_roughness_texture =
            textureRef(who + " metallicRoughnessTexture", pbr.metallicRoughnessTexture.index,
                       pbr.metallicRoughnessTexture.texCoord, 1.0, false);
        m.normal_texture = textureRef(who + " normalTexture", src.normalTexture.index,
                                      src.normalTexture.texCoord, src.normalTexture.scale, false);
        m.occlusion_texture = textureRef(who + " occlusionTexture", src.occlusionTexture.index,
                                         src.occlusionTexture.texCoord, src.occlusionTexture.strength, false);
        m.emissive_texture = textureRef(who + " emissiveTexture", src.emissiveTexture.index,
                                        src.emissiveTexture.texCoord, 1.0, true);
        scene_.materials.push_back(std::move(m));
    }
}

glm::mat4 Converter::localMatrix(std::size_t node_index) const {
    const glm::mat4 m = localMatrixUnchecked(node_index);
    if (!finiteMatrix(m))
        fail("node " + std::to_string(node_index) + ": its transform is too large for floats");
    return m;
}

glm::mat4 Converter::localMatrixUnchecked(std::size_t node_index) const {
    const tinygltf::Node& node = model_.nodes[node_index];
    const std::string who = "node " + std::to_string(node_index);
    if (!node.matrix.empty()) {
        if (node.matrix.size() != 16 || !finite(node.matrix))
            fail(who + ": matrix must be 16 finite numbers");
        glm::mat4 m(1.0f);
        for (int c = 0; c < 4; ++c) {
            for (int r = 0; r < 4; ++r)
                m[c][r] = static_cast<float>(node.matrix[static_cast<std::size_t>(c * 4 + r)]);
        }
        return m;  // glTF stores column-major, as glm does
    }
    glm::mat4 m(1.0f);
    if (!node.translation.empty()) {
        if (node.translation.size() != 3 || !finite(node.translation)) {
            fail(who + ": translation must be 3 finite numbers");
        }
        m = glm::translate(
            m, glm::vec3(static_cast<float>(node.translation[0]), static_cast<float>(node.translation[1]),
                         static_cast<float>(node.translation[2])));
    }
    if (!node.rotation.empty()) {
        if (node.rotation.size() != 4 || !finite(node.rotation))
            fail(who + ": rotation must be 4 finite numbers");
        // glTF quaternions are (x, y, z, w); glm's constructor takes w first.
        glm::quat q(static_cast<float>(node.rotation[3]), static_cast<float>(node.rotation[0]),
                    static_cast<float>(node.rotation[1]), static_cast<float>(node.rotation[2]));
        const float len = glm::length(q);
        if (!(len > 1e-6f)) fail(who + ": rotation quaternion has zero length");
        m = m * glm::mat4_cast(q / len);
    }
    if (!node.scale.empty()) {
        if (node.scale.size() != 3 || !finite(node.scale)) fail(who + ": scale must be 3 finite numbers");
        m = glm::scale(m, glm::vec3(static_cast<float>(node.scale[0]), static_cast<float>(node.scale[1]),
                                    static_cast<float>(node.scale[2])));
    }
    return m;
}

std::vector<int> Converter::rootNodes() const {
    const int chosen = model_.defaultScene;
    if (chosen < -1 || (chosen >= 0 && static_cast<std::size_t>(chosen) >= model_.scenes.size())) {
        fail("default scene " + std::to_string(chosen) + " does not exist (the file has " +
             std::to_string(model_.scenes.size()) + " scenes)");
    }
    if (chosen >= 0) return model_.scenes[static_cast<std::size_t>(chosen)].nodes;
    if (!model_.scenes.empty()) return model_.scenes[0].nodes;
    // No scenes at all: every node that is nobody's child is a root.
    std::vector<char> is_child(model_.nodes.size(), 0);
    for (const auto& node : model_.nodes) {
        for (int child : node.children) {
            if (child >= 0 && static_cast<std::size_t>(child) < model_.nodes.size()) {
                is_child[static_cast<std::size_t>(child)] = 1;
            }
        }
    }
    std::vector<int> roots;
    for (std::size_t i = 0; i < model_.nodes.size(); ++i) {
        if (!is_child[i]) roots.push_back(static_cast<int>(i));
    }
    return roots;
}

void Converter::walkNodes() {
    // Iterative pre-order walk: a hostile file can nest nodes deeper than the call stack allows.
    std::vector<char> visited(model_.nodes.size(), 0);
    std::vector<std::pair<int, glm::mat4>> stack;
    const std::vector<int> roots = rootNodes();
    for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.emplace_back(*it, glm::mat4(1.0f));
    while (!stack.empty()) {
        const auto [index, parent] = stack.back();
        stack.pop_back();
        if (index < 0 || static_cast<std::size_t>(index) >= model_.nodes.size()) {
            fail("node " + std::to_string(index) + " does not exist (the file has " +
                 std::to_string(model_.nodes.size()) + " nodes)");
        }
        const auto node_index = static_cast<std::size_t>(index);
        if (visited[node_index]) {
            fail("node " + std::to_string(index) + " is reached twice; the node hierarchy must be a tree");
        }
        visited[node_index] = 1;
        const glm::mat4 world = parent * localMatrix(node_index);
        if (!finiteMatrix(world)) {
            fail("node " + std::to_string(index) + ": its world transform overflows to infinity or NaN");
        }
        visitNode(node_index, world);
        const auto& children = model_.nodes[node_index].children;
        for (auto child = children.rbegin(); child != children.rend(); ++child)
            stack.emplace_back(*child, world);
    }
}

// EXT_mesh_gpu_instancing: one local transform per instance (TRS from accessors), applied after
// the node's own. Empty when the node has no instancing.
std::vector<glm::mat4> Converter::instanceTransforms(std::size_t node_index) const {
    const tinygltf::Node& node = model_.nodes[node_index];
    const auto ext = node.extensions.find(kInstancing);
    if (ext == node.extensions.end()) return {};
    const std::string who = "node " + std::to_string(node_index) + " (" + kInstancing + ")";
    if (!ext->second.IsObject() || !ext->second.Has("attributes") ||
        !ext->second.Get("attributes").IsObject())
        fail(who + ": the extension needs an \"attributes\" object");
    const tinygltf::Value& attributes = ext->second.Get("attributes");
    std::size_t count = 0;
    std::vector<float> t, r, s;
    const auto read = [&](const char* name, Use use, std::vector<float>* out) {
        if (!attributes.Has(name)) return;
        const tinygltf::Value& index = attributes.Get(name);
        if (!index.IsNumber()) fail(who + ": " + name + " must be an accessor index");
        const std::size_t n =
            readAccessor(index.GetNumberAsInt(), std::string(name) + " of " + who, use, out);
        if (count != 0 && n != count)
            fail(who + ": " + name + " has " + std::to_string(n) + " instances, not " +
                 std::to_string(count));
        count = n;
    };
    read("TRANSLATION", Use::Translation, &t);
    read("ROTATION", Use::Rotation, &r);
    read("SCALE", Use::Scale, &s);
    if (count == 0) fail(who + ": no TRANSLATION, ROTATION or SCALE accessor");
    if (count > kMaxDrawItems)
        fail(who + ": " + std::to_string(count) + " instances is over the limit of " +
             std::to_string(kMaxDrawItems));
    std::vector<glm::mat4> out(count, glm::mat4(1.0f));
    for (std::size_t i = 0; i < count; ++i) {
        glm::mat4 m(1.0f);
        if (!t.empty()) m = glm::translate(m, glm::vec3(t[3 * i], t[3 * i + 1], t[3 * i + 2]));
        if (!r.empty()) {
            glm::quat q(r[4 * i + 3], r[4 * i], r[4 * i + 1], r[4 * i + 2]);
            const float len = glm::length(q);
            if (len > 1e-6f && std::isfinite(len)) m = m * glm::mat4_cast(q / len);
        }
        if (!s.empty()) m = glm::scale(m, glm::vec3(s[3 * i], s[3 * i + 1], s[3 * i + 2]));
        out[i] = m;
    }
    return out;
}

void Converter::visitNode(std::size_t node_index, const glm::mat4& world) {
    const tinygltf::Node& node = model_.nodes[node_index];
    const std::string who = "node " + std::to_string(node_index);
    if (node.mesh != -1) {
        if (node.mesh < 0 || static_cast<std::size_t>(node.mesh) >= model_.meshes.size()) {
            fail(who + ": mesh " + std::to_string(node.mesh) + " does not exist (the file has " +
                 std::to_string(model_.meshes.size()) + " meshes)");
        }
        const auto mesh_index = static_cast<std::size_t>(node.mesh);
        const auto& prims = model_.meshes[mesh_index].primitives;
        if (node.skin != -1 && warned_.insert("skin node " + std::to_string(node_index)).second) {
            warnings_.push_back(who + ": skin " + std::to_string(node.skin) + " ignored; " +
                                meshLabel(mesh_index) + " is drawn in its bind pose");
        }
        const std::vector<glm::mat4> instances = instanceTransforms(node_index);
        for (std::size_t p = 0; p < prims.size(); ++p) {
            const int mode = prims[p].mode;
            if (mode != -1 && mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
                mode != TINYGLTF_MODE_TRIANGLE_FAN) {
                static const char* const kModeNames[] = {"POINTS", "LINES", "LINE_LOOP", "LINE_STRIP"};
                const std::string name =
                    mode >= 0 && mode <= 3 ? std::string(" (") + kModeNames[mode] + ")" : "";
                if (warned_.insert("mode " + std::to_string(mesh_index) + "/" + std::to_string(p)).second) {
                    warnings_.push_back(meshLabel(mesh_index) + " primitive " + std::to_string(p) +
                                        ": mode " + std::to_string(mode) + name +
                                        " skipped; shaderlab draws only triangles (lists, strips and fans)");
                }
                continue;
            }
            const int material = prims[p].material;
            if (material < -1 ||
                (material >= 0 && static_cast<std::size_t>(material) >= model_.materials.size())) {
                fail(meshLabel(mesh_index) + " primitive " + std::to_string(p) + ": material " +
                     std::to_string(material) + " does not exist (the file has " +
                     std::to_string(model_.materials.size()) + " materials)");
            }
            const int mesh_id = convertPrimitive(mesh_index, p);
            for (std::size_t k = 0; k < std::max<std::size_t>(instances.size(), 1); ++k) {
                if (scene_.draw_items.size() >= kMaxDrawItems) {
                    fail("the scene has more than " + std::to_string(kMaxDrawItems) + " draw items");
                }
                DrawItem item;
                item.node_name = node.name.empty() ? "node" + std::to_string(node_index) : node.name;
                item.mesh = mesh_id;
                item.material = material;
                item.world = instances.empty() ? world : world * instances[k];
                if (!finiteMatrix(item.world))
                    fail(who + ": an instance's transform overflows to infinity or NaN");
                item.mirrored = glm::determinant(glm::mat3(item.world)) < 0.0f;
                scene_.draw_items.push_back(std::move(item));
            }
        }
    }
    if (node.camera != -1) {
        if (node.camera < 0 || static_cast<std::size_t>(node.camera) >= model_.cameras.size()) {
            fail(who + ": camera " + std::to_string(node.camera) + " does not exist (the file has " +
                 std::to_string(model_.cameras.size()) + " cameras)");
        }
        const auto& cam = model_.cameras[static_cast<std::size_t>(node.camera)];
        if (cam.type != "perspective" && cam.type != "orthographic") {
            warnings_.push_back(who + ": camera " + std::to_string(node.camera) + " has unknown type " +
                                inQuotes(cam.type) + "; ignored");
        } else if (camera_node_ < 0) {
            camera_node_ = static_cast<int>(node_index);
            camera_world_ = world;
        }
    }
    addLight(node_index, world);
}

void Converter::addLight(std::size_t node_index, const glm::mat4& world) {
    const tinygltf::Node& node = model_.nodes[node_index];
    const auto ext = node.extensions.find("KHR_lights_punctual");
    if (ext == node.extensions.end()) return;
    const std::string who = "node " + std::to_string(node_index);
    if (!ext->second.IsObject() || !ext->second.Has("light") || !ext->second.Get("light").IsNumber()) {
        fail(who + ": KHR_lights_punctual must be an object with a numeric \"light\"");
    }
    const double index = ext->second.Get("light").GetNumberAsDouble();
    if (!(index >= 0.0) || index >= static_cast<double>(model_.lights.size()) || index != std::floor(index)) {
        std::ostringstream shown;
        shown << index;
        fail(who + ": light " + shown.str() + " does not exist (the file has " +
             std::to_string(model_.lights.size()) + " KHR_lights_punctual lights)");
    }
    const auto light_index = static_cast<std::size_t>(index);
    const tinygltf::Light& src = model_.lights[light_index];
    const std::string lwho = "light " + std::to_string(light_index);
    Light light;
    if (src.type == "directional") {
        light.type = LightType::Directional;
    } else if (src.type == "point") {
        light.type = LightType::Point;
    } else if (src.type == "spot") {
        light.type = LightType::Spot;
    } else {
        fail(lwho + ": unknown type " + inQuotes(src.type));
    }
    if (!src.color.empty()) {
        if (src.color.size() != 3 || !finite(src.color)) fail(lwho + ": color must be 3 finite numbers");
        light.color = glm::vec3(static_cast<float>(src.color[0]), static_cast<float>(src.color[1]),
                                static_cast<float>(src.color[2]));
    }
    if (!std::isfinite(src.intensity) || src.intensity < 0.0)
        fail(lwho + ": intensity must be finite and >= 0");
    if (!std::isfinite(src.range) || src.range < 0.0) fail(lwho + ": range must be finite and >= 0");
    light.intensity = static_cast<float>(src.intensity);
    light.range = static_cast<float>(src.range);
    if (light.type == LightType::Spot) {
        const double inner = src.spot.innerConeAngle, outer = src.spot.outerConeAngle;
        // KHR_lights_punctual: 0 <= innerConeAngle < outerConeAngle <= pi/2.
        if (!(inner >= 0.0) || !(outer > inner) || !(outer <= 1.5707964)) {
            fail(lwho + ": spot cone angles must satisfy 0 <= innerConeAngle < outerConeAngle <= pi/2");
        }
        light.inner_cone = static_cast<float>(inner);
        light.outer_cone = static_cast<float>(outer);
    }
    if (!finiteVec(light.color) || !std::isfinite(light.intensity) || !std::isfinite(light.range)) {
        fail(lwho + ": color, intensity or range is too large for a float");
    }
    light.position = glm::vec3(world * glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    // Lights shine down their local -Z; a scaled node must not change the direction's length.
    const glm::vec3 dir = glm::vec3(world * glm::vec4(0.0f, 0.0f, -1.0f, 0.0f));
    const float len = glm::length(dir);
    light.direction = len > 0.0f && std::isfinite(len) ? dir / len : glm::vec3(0.0f, 0.0f, -1.0f);
    scene_.lights.push_back(light);
}

void Converter::computeBounds() {
    glm::vec3 lo(std::numeric_limits<float>::max());
    glm::vec3 hi(std::numeric_limits<float>::lowest());
    std::size_t work = 0;
    for (const DrawItem& item : scene_.draw_items) {
        work += scene_.meshes[static_cast<std::size_t>(item.mesh)].positions.size();
    }
    if (work <= kExactBoundsBudget) {
        // Tight bounds: every vertex of every item in world space.
        for (const DrawItem& item : scene_.draw_items) {
            for (const glm::vec3& p : scene_.meshes[static_cast<std::size_t>(item.mesh)].positions) {
                const glm::vec3 w = glm::vec3(item.world * glm::vec4(p, 1.0f));
                lo = glm::min(lo, w);
                hi = glm::max(hi, w);
            }
        }
    } else {
        // A big mesh instanced many times: the corners of each mesh's own box, transformed.
        // Looser for rotated items, but linear in the number of items.
        std::vector<std::pair<glm::vec3, glm::vec3>> boxes;
        for (const Mesh& mesh : scene_.meshes) {
            glm::vec3 mlo(std::numeric_limits<float>::max()), mhi(std::numeric_limits<float>::lowest());
            for (const glm::vec3& p : mesh.positions) {
                mlo = glm::min(mlo, p);
                mhi = glm::max(mhi, p);
            }
            boxes.emplace_back(mlo, mhi);
        }
        for (const DrawItem& item : scene_.draw_items) {
            const auto& box = boxes[static_cast<std::size_t>(item.mesh)];
            for (int corner = 0; corner < 8; ++corner) {
                const glm::vec3 p((corner & 1) ? box.second.x : box.first.x,
                                  (corner & 2) ? box.second.y : box.first.y,
                                  (corner & 4) ? box.second.z : box.first.z);
                const glm::vec3 w = glm::vec3(item.world * glm::vec4(p, 1.0f));
                lo = glm::min(lo, w);
                hi = glm::max(hi, w);
            }
        }
    }
    if (scene_.draw_items.empty()) {
        lo = hi = glm::vec3(0.0f);
        warnings_.push_back("the scene has no triangles to draw");
    }
    if (!std::isfinite(lo.x + lo.y + lo.z + hi.x + hi.y + hi.z)) {
        fail("node transforms take the scene's bounds to infinity");
    }
    scene_.bounds_min = lo;
    scene_.bounds_max = hi;
}

void Converter::placeCamera() {
    const glm::vec3 centre = 0.5f * (scene_.bounds_min + scene_.bounds_max);
    float radius = 0.5f * glm::length(scene_.bounds_max - scene_.bounds_min);
    if (!(radius > 1e-6f)) radius = 1.0f;
    Camera& cam = scene_.camera;

    if (camera_node_ < 0) {
        // No camera in the file: look from +Z and a little above at the centre, far enough back
        // that the bounding sphere fits the vertical field of view.
        scene_.has_camera = false;
        cam = Camera{};
        const float half_fov = glm::radians(cam.fov_y_deg) * 0.5f;
        const float distance = radius / std::sin(half_fov) * 1.05f;
        cam.target = centre;
        cam.position = centre + glm::normalize(glm::vec3(0.0f, 0.35f, 1.0f)) * distance;
        cam.up = glm::vec3(0.0f, 1.0f, 0.0f);
        cam.z_near = std::max((distance - radius) * 0.5f, distance * 1e-3f);
        cam.z_far = (distance + radius) * 2.0f;
        // The distance fits the vertical field of view; a portrait target widens the projection
        // so the sphere fits across as well (camera.cpp).
        cam.fit_both_axes = true;
        checkCamera();
        return;
    }

    const auto& node = model_.nodes[static_cast<std::size_t>(camera_node_)];
    const tinygltf::Camera& file_camera = model_.cameras[static_cast<std::size_t>(node.camera)];
    const std::string who = "camera " + std::to_string(node.camera);
    scene_.has_camera = true;
    if (file_camera.type == "orthographic") {
        const auto& o = file_camera.orthographic;
        if (!std::isfinite(o.xmag) || o.xmag == 0.0 || !std::isfinite(o.ymag) || o.ymag == 0.0)
            fail(who + ": xmag and ymag must be finite and not 0");
        if (!std::isfinite(o.znear) || o.znear < 0.0) fail(who + ": znear must be >= 0");
        if (!std::isfinite(o.zfar) || o.zfar <= o.znear) fail(who + ": zfar must be > znear");
        cam.orthographic = true;
        cam.ortho_height = static_cast<float>(2.0 * std::abs(o.ymag));
        cam.file_aspect = static_cast<float>(std::abs(o.xmag / o.ymag));
        // An orthographic near plane may be 0; checkCamera() wants it positive.
        cam.z_near = static_cast<float>(std::max(o.znear, o.zfar * 1e-6));
        cam.z_far = static_cast<float>(o.zfar);
    } else {
        const auto& p = file_camera.perspective;
        if (!std::isfinite(p.yfov) || p.yfov <= 0.0 || p.yfov >= 3.14159)
            fail(who + ": yfov must be in (0, pi)");
        if (!std::isfinite(p.znear) || p.znear <= 0.0) fail(who + ": znear must be > 0");
        if (!std::isfinite(p.zfar) || (p.zfar != 0.0 && p.zfar <= p.znear))
            fail(who + ": zfar must be > znear");
        if (!std::isfinite(p.aspectRatio) || p.aspectRatio < 0.0) fail(who + ": aspectRatio must be > 0");
        cam.fov_y_deg = static_cast<float>(p.yfov * 180.0 / 3.14159265358979323846);
        cam.z_near = static_cast<float>(p.znear);
        cam.file_aspect = static_cast<float>(p.aspectRatio);
    }
    // glTF cameras look down their local -Z with +Y up.
    cam.position = glm::vec3(camera_world_ * glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    glm::vec3 forward = glm::vec3(camera_world_ * glm::vec4(0.0f, 0.0f, -1.0f, 0.0f));
    glm::vec3 up = glm::vec3(camera_world_ * glm::vec4(0.0f, 1.0f, 0.0f, 0.0f));
    if (!(glm::length(forward) > 1e-8f) || !(glm::length(up) > 1e-8f)) {
        fail("node " + std::to_string(camera_node_) + ": the camera's transform is degenerate");
    }
    forward = glm::normalize(forward);
    cam.up = glm::normalize(up);
    // The target only fixes a direction; put it at the scene's depth so orbiting tools have a
    // sensible pivot.
    float distance = glm::length(centre - cam.position);
    if (!(distance > 1e-4f)) distance = 1.0f;
    cam.target = cam.position + forward * distance;
    if (cam.orthographic) {
        // z_far was set above.
    } else if (file_camera.perspective.zfar > 0.0) {
        cam.z_far = static_cast<float>(file_camera.perspective.zfar);
    } else {
        // Infinite projection in the file: a finite far plane well behind the whole scene.
        cam.z_far = std::max(cam.z_near * 1000.0f, 2.0f * (glm::length(centre - cam.position) + radius));
    }
    checkCamera();
}

// Huge but finite coordinates can still overflow the float arithmetic above; a camera with an
// infinite or NaN field would only fail later, in the renderer, with a black image.
void Converter::checkCamera() const {
    const Camera& cam = scene_.camera;
    if (!finiteVec(cam.position) || !finiteVec(cam.target) || !finiteVec(cam.up) ||
        !std::isfinite(cam.fov_y_deg) || !std::isfinite(cam.z_near) || !std::isfinite(cam.z_far) ||
        !std::isfinite(cam.file_aspect) || !(cam.z_near > 0.0f) || !(cam.z_far > cam.z_near) ||
        cam.position == cam.target) {
        fail(std::string(scene_.has_camera ? "the file's camera" : "the default camera framing the scene") +
             " is not finite or not valid (are the scene's coordinates within float range?)");
    }
}

void Converter::run() {
    if (model_.asset.version.rfind("2.", 0) != 0) {
        fail("glTF version " + inQuotes(model_.asset.version) + " is not supported (need 2.x)");
    }
    // checkExtensions() refused what the loader cannot draw before tinygltf ran.
    quantized_ = std::find(model_.extensionsUsed.begin(), model_.extensionsUsed.end(), kQuantization) !=
                 model_.extensionsUsed.end();
    decodeMeshoptViews();
    convertMaterials();
    walkNodes();
    computeBounds();
    placeCamera();
}

}  // namespace

SceneLoadResult loadGltfScene(const std::string& path, Scene* out) {
    const FileText file = readFile(path, kMaxFileBytes);
    if (!file.ok) {
        SceneLoadResult result;
        result.error = file.error.rfind(path, 0) == 0 ? file.error : path + ": " + file.error;
        if (out) *out = Scene{};
        return result;
    }
    return loadGltfSceneFromBytes(file.text, path, out);
}

SceneLoadResult loadGltfSceneFromBytes(const std::string& bytes, const std::string& path, Scene* out) {
    SceneLoadResult result;
    if (out == nullptr) {
        result.error = path + ": no Scene to load into";
        return result;
    }
    *out = Scene{};
    try {
        if (bytes.size() > kMaxFileBytes)
            fail("file is larger than " + std::to_string(kMaxFileBytes >> 20) + " MiB");
        if (bytes.empty()) fail("file is empty");

        FsGuard guard;
        std::error_code ec;
        fs::path folder = fs::absolute(fs::path(path), ec).lexically_normal().parent_path();
        if (ec) fail("cannot resolve the file's folder");
        guard.folder = folder.string();
        guard.prefix = guard.folder;
        if (guard.prefix.empty() || guard.prefix.back() != '/') guard.prefix += '/';

        tinygltf::TinyGLTF gltf;
        gltf.SetFsCallbacks(tinygltf::FsCallbacks{&guardFileExists, &guardExpandFilePath, &guardReadWholeFile,
                                                  &guardWriteWholeFile, &guard});
        ImageBytes images;
        gltf.SetImageLoader(&keepImage, &images);

        tinygltf::Model model;
        std::string err;
        std::string warn;
        bool loaded = false;
        const bool glb_magic = bytes.size() >= 4 && bytes.compare(0, 4, "glTF") == 0;
        const std::string ext = fs::path(path).extension().string();
        std::set<int> fallback_buffers;
        if (glb_magic) {
            std::size_t length = checkGlbLayout(bytes, &result.warnings);
            const std::size_t json_length = readU32(bytes, 12);
            const char* json = bytes.data() + 20;
            checkJson(json, json + json_length);
            const std::string rewritten =
                checkExtensions(json, json + json_length, &result.warnings, &fallback_buffers);
            const std::string glb =
                rewritten.empty() ? std::string() : replaceGlbJson(bytes, length, rewritten);
            if (!glb.empty()) length = glb.size();
            loaded = gltf.LoadBinaryFromMemory(
                &model, &err, &warn,
                reinterpret_cast<const unsigned char*>(glb.empty() ? bytes.data() : glb.data()),
                static_cast<unsigned int>(length), guard.folder);
        } else {
            if (ext == ".glb" || ext == ".GLB")
                fail("not a GLB file: it does not start with the 'glTF' magic");
            checkJson(bytes.data(), bytes.data() + bytes.size());
            const std::string rewritten = checkExtensions(bytes.data(), bytes.data() + bytes.size(),
                                                          &result.warnings, &fallback_buffers);
            const std::string& json = rewritten.empty() ? bytes : rewritten;
            loaded = gltf.LoadASCIIFromString(&model, &err, &warn, json.data(),
                                              static_cast<unsigned int>(json.size()), guard.folder);
        }
        appendLines(warn, "", &result.warnings);
        // Our own refusals first: tinygltf only sees them as "file not found".
        if (!guard.refusal.empty()) fail(guard.refusal);
        if (!loaded) {
            if (!guard.missing.empty()) {
                fail("missing file " + inQuotes(guard.missing) +
                     " (referenced by a buffer URI, looked for in " + guard.folder + ")");
            }
            fail("tinygltf: " + (err.empty() ? std::string("load failed") : joinLines(err)));
        }
        // tinygltf sometimes fills `err` and still succeeds (e.g. a misaligned GLB JSON chunk).
        appendLines(err, "tinygltf: ", &result.warnings);

        Scene scene;
        scene.source_path = path;
        Converter(model, &scene, &result.warnings, fallback_buffers, &images).run();
        *out = std::move(scene);
        result.ok = true;
    } catch (const LoadError& e) {
        result.error = path + ": " + e.message;
    } catch (const std::bad_alloc&) {
        result.error = path + ": out of memory while loading";
    } catch (const std::exception& e) {
        // tinygltf 2.7.0 can throw on some malformed input (e.g. vector::at on a zero-length GLB
        // buffer); that is a bad file, not a crash.
        result.error = path + ": tinygltf: " + e.what();
    }
    if (!result.ok) *out = Scene{};
    return result;
}

}  // namespace shaderlab
