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
//
// This file reads the file, checks its GLB layout, JSON and extensions, guards tinygltf's access
// to other files, and runs the Converter (gltf_converter.h), whose stages are defined in
// gltf_accessors.cpp, gltf_primitives.cpp, gltf_materials.cpp and gltf_nodes.cpp.
// Buffers are read as little-endian, which is what glTF stores and what the hosts we run on are.
#include "shaderlab/scene/gltf_loader.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <map>
#include <new>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "gltf_converter.h"
#include "shaderlab/base/paths.h"

namespace fs = std::filesystem;

namespace shaderlab {

// The caps, the error type and the Converter are shared with the loader's other files.
using namespace gltf_detail;

namespace {

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

// tinygltf 2.8 and later ask for a file's size before reading it: the same approved paths only.
bool guardFileSize(std::size_t* size, std::string* err, const std::string& path, void* user) {
    auto* guard = static_cast<FsGuard*>(user);
    const auto it = guard->approved.find(path);
    std::error_code ec;
    const auto bytes = it == guard->approved.end() ? 0 : fs::file_size(it->second, ec);
    if (it == guard->approved.end() || ec) {
        if (err) *err = it == guard->approved.end() ? "not a file inside the scene's folder" : ec.message();
        return false;
    }
    *size = static_cast<std::size_t>(bytes);
    return true;
}

// The guard's callbacks, whichever FsCallbacks the installed tinygltf has: up to 2.7 four
// callbacks and user_data; from 2.8 also GetFileSizeInBytes, and SetFsCallbacks then refuses (and
// keeps tinygltf's own file system, which reads anywhere) unless every one is set.
template <typename Callbacks>
auto setFileSizeCallback(Callbacks& callbacks, int)
    -> decltype(callbacks.GetFileSizeInBytes = &guardFileSize, void()) {
    callbacks.GetFileSizeInBytes = &guardFileSize;
}
template <typename Callbacks>
void setFileSizeCallback(Callbacks&, long) {}

// Installs the guard; false when tinygltf refused it (it returns whether it did from 2.8 on).
template <typename Loader>
auto installGuard(Loader& gltf, const tinygltf::FsCallbacks& callbacks, int)
    -> decltype(gltf.SetFsCallbacks(callbacks, nullptr), bool()) {
    std::string err;
    return gltf.SetFsCallbacks(callbacks, &err);
}
template <typename Loader>
bool installGuard(Loader& gltf, const tinygltf::FsCallbacks& callbacks, long) {
    gltf.SetFsCallbacks(callbacks);
    return true;
}

// tinygltf's image loader: keeps the encoded bytes of an image (ImageBytes, gltf_converter.h).
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

}  // namespace

namespace gltf_detail {

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

}  // namespace gltf_detail

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
        tinygltf::FsCallbacks callbacks{};
        callbacks.FileExists = &guardFileExists;
        callbacks.ExpandFilePath = &guardExpandFilePath;
        callbacks.ReadWholeFile = &guardReadWholeFile;
        callbacks.WriteWholeFile = &guardWriteWholeFile;
        setFileSizeCallback(callbacks, 0);
        callbacks.user_data = &guard;
        // Fail closed: without the guard tinygltf would read whatever a URI names.
        if (!installGuard(gltf, callbacks, 0))
            fail("the glTF library refused the loader's file-system guard");
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
