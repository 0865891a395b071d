// Loads a glTF 2.0 file (.gltf or .glb) into a shaderlab::Scene.
//
// tinygltf parses the JSON and decodes buffers; everything that indexes into those buffers is
// done here, and every index, offset, length and stride is checked before a byte is read, so a
// malformed or hostile file ends as an error "<path>: <problem>", never as a crash or an
// out-of-bounds read. The file itself is read here (not by tinygltf) so that the GLB chunk layout
// can be checked first, and tinygltf reaches external files only through callbacks that refuse
// anything outside the scene's folder.
//
// What it does: the default scene (or scene 0, or every root node), node transforms composed
// (matrix or TRS), triangle-list primitives with POSITION / NORMAL / TEXCOORD_0 and any index
// type, sparse accessors, flat normals when NORMAL is absent, base colour factors, the first
// perspective camera, KHR_lights_punctual lights, world-space bounds.
// What it does not: images and textures (never decoded: an image decoder fed untrusted bytes is
// attack surface the labs do not need), skins, morph targets, animations, points/lines/strips/
// fans (skipped with a warning), orthographic cameras (skipped with a warning), spot cone
// angles (scene.h has no field for them), Draco or quantized meshes.
// Buffers are read as little-endian, which is what glTF stores and what the hosts we run on are.
#include "shaderlab/gltf_loader.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <limits>
#include <map>
#include <new>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "shaderlab/paths.h"

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

// Images are never decoded (see the top of the file); accepting them unread keeps tinygltf from
// running its image decoder on untrusted bytes.
bool skipImage(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int,
               void*) {
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

// What an accessor is used for decides which layouts are accepted (glTF 2.0 spec, 3.7.2.1).
enum class Use { Vec3Float, Texcoord, Indices };

bool layoutAllowed(Use use, int type, int component_type, bool normalized) {
    switch (use) {
        case Use::Vec3Float:
            return type == TINYGLTF_TYPE_VEC3 && component_type == TINYGLTF_COMPONENT_TYPE_FLOAT;
        case Use::Texcoord:
            return type == TINYGLTF_TYPE_VEC2 &&
                   (component_type == TINYGLTF_COMPONENT_TYPE_FLOAT ||
                    (normalized && (component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                    component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT)));
        case Use::Indices:
            return type == TINYGLTF_TYPE_SCALAR && !normalized &&
                   (component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                    component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ||
                    component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
    }
    return false;
}

const char* layoutExpected(Use use) {
    switch (use) {
        case Use::Vec3Float:
            return "VEC3 of FLOAT";
        case Use::Texcoord:
            return "VEC2 of FLOAT, or of normalized UNSIGNED_BYTE / UNSIGNED_SHORT";
        case Use::Indices:
            return "SCALAR of UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT";
    }
    return "";
}

int componentCount(Use use) { return use == Use::Vec3Float ? 3 : use == Use::Texcoord ? 2 : 1; }

struct Bytes {
    const unsigned char* data = nullptr;
    std::size_t size = 0;
};

class Converter {
  public:
    Converter(const tinygltf::Model& model, Scene* scene, std::vector<std::string>* warnings)
        : model_(model), scene_(*scene), warnings_(*warnings) {}

    void run();

  private:
    // Validates bufferView `index` and the buffer it lies in; `who` names the referrer.
    Bytes bufferView(int index, const std::string& who) const {
        if (index < 0 || static_cast<std::size_t>(index) >= model_.bufferViews.size()) {
            fail(who + ": bufferView " + std::to_string(index) + " does not exist (the file has " +
                 std::to_string(model_.bufferViews.size()) + ")");
        }
        const tinygltf::BufferView& view = model_.bufferViews[static_cast<std::size_t>(index)];
        const std::string name = "bufferView " + std::to_string(index);
        if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model_.buffers.size()) {
            fail(name + ": buffer " + std::to_string(view.buffer) + " does not exist (the file has " +
                 std::to_string(model_.buffers.size()) + ")");
        }
        const auto& data = model_.buffers[static_cast<std::size_t>(view.buffer)].data;
        if (view.byteLength > data.size() || view.byteOffset > data.size() - view.byteLength) {
            fail(name + ": bytes " + byteRange(view.byteOffset, view.byteLength) + " lie outside buffer " +
                 std::to_string(view.buffer) + " which has " + std::to_string(data.size()) + " bytes");
        }
        return Bytes{data.data() + view.byteOffset, view.byteLength};
    }

    // Decodes accessor `index` into `out` (count * components values) after checking that every
    // element it names lies inside its bufferView. `role` reads like "POSITION of mesh 'torus'".
    template <typename T>
    std::size_t readAccessor(int index, const std::string& role, Use use, std::vector<T>* out) const {
        if (index < 0 || static_cast<std::size_t>(index) >= model_.accessors.size()) {
            fail("accessor " + std::to_string(index) + " (" + role + ") does not exist (the file has " +
                 std::to_string(model_.accessors.size()) + ")");
        }
        const tinygltf::Accessor& acc = model_.accessors[static_cast<std::size_t>(index)];
        const std::string who = "accessor " + std::to_string(index) + " (" + role + ")";
        if (!layoutAllowed(use, acc.type, acc.componentType, acc.normalized)) {
            fail(who + ": is " + typeName(acc.type) + " of " + (acc.normalized ? "normalized " : "") +
                 componentTypeName(acc.componentType) + ", expected " + layoutExpected(use));
        }
        const std::size_t limit = use == Use::Indices ? kMaxIndices : kMaxVertices;
        if (acc.count == 0) fail(who + ": count is 0");
        if (acc.count > limit) {
            fail(who + ": count " + std::to_string(acc.count) + " is over the limit of " +
                 std::to_string(limit));
        }
        const std::size_t components = static_cast<std::size_t>(componentCount(use));
        const std::size_t comp_size = componentSize(acc.componentType);
        const std::size_t element = comp_size * components;
        out->assign(acc.count * components, T{});

        if (acc.bufferView == -1 && acc.count > kMaxUnbackedCount) {
            fail(who + ": count " + std::to_string(acc.count) +
                 " without a bufferView is over the limit of " + std::to_string(kMaxUnbackedCount));
        }
        if (acc.bufferView != -1) {
            const Bytes view = bufferView(acc.bufferView, who);
            const std::size_t declared =
                model_.bufferViews[static_cast<std::size_t>(acc.bufferView)].byteStride;
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

    int convertPrimitive(std::size_t mesh_index, std::size_t prim_index);
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

    const auto attribute = [&](const char* name) {
        const auto it = prim.attributes.find(name);
        return it == prim.attributes.end() ? -1 : it->second;
    };
    if (prim.attributes.count("POSITION") == 0) fail(where + " has no POSITION attribute");

    std::vector<float> values;
    const std::size_t vertex_count =
        readAccessor(attribute("POSITION"), std::string("POSITION of ") + label, Use::Vec3Float, &values);
    if (!std::all_of(values.begin(), values.end(), [](float v) { return std::isfinite(v); })) {
        fail(where + ": POSITION contains non-finite values");
    }
    mesh.positions.resize(vertex_count);
    for (std::size_t i = 0; i < vertex_count; ++i) {
        mesh.positions[i] = glm::vec3(values[3 * i], values[3 * i + 1], values[3 * i + 2]);
    }

    const int normal_accessor = attribute("NORMAL");
    if (prim.attributes.count("NORMAL") != 0) {
        const std::size_t n =
            readAccessor(normal_accessor, std::string("NORMAL of ") + label, Use::Vec3Float, &values);
        if (n != vertex_count) {
            fail(where + ": NORMAL has " + std::to_string(n) + " elements but POSITION has " +
                 std::to_string(vertex_count));
        }
        mesh.normals.resize(n);
        for (std::size_t i = 0; i < n; ++i) {
            const glm::vec3 v(values[3 * i], values[3 * i + 1], values[3 * i + 2]);
            const float len = glm::length(v);
            // The spec requires unit normals; exporters are sloppy, and a shader that forgets to
            // normalize should not be graded on someone else's rounding.
            mesh.normals[i] = len > 0.0f && std::isfinite(len) ? v / len : glm::vec3(0.0f, 0.0f, 1.0f);
        }
    }

    if (prim.attributes.count("TEXCOORD_0") != 0) {
        const std::size_t n = readAccessor(attribute("TEXCOORD_0"), std::string("TEXCOORD_0 of ") + label,
                                           Use::Texcoord, &values);
        if (n != vertex_count) {
            fail(where + ": TEXCOORD_0 has " + std::to_string(n) + " elements but POSITION has " +
                 std::to_string(vertex_count));
        }
        mesh.texcoords.resize(n);
        for (std::size_t i = 0; i < n; ++i) {
            // glTF puts (0, 0) at an image's top-left, OpenGL texture coordinates at the row
            // uploaded first, which the framework makes the image's bottom row: t = 1 - v keeps
            // an image upright on a mesh as in a fullscreen pass.
            const glm::vec2 uv(values[2 * i], 1.0f - values[2 * i + 1]);
            mesh.texcoords[i] = std::isfinite(uv.x) && std::isfinite(uv.y) ? uv : glm::vec2(0.0f);
        }
        mesh.had_texcoords = true;
    } else {
        mesh.texcoords.assign(vertex_count, glm::vec2(0.0f));
    }

    if (prim.indices != -1) {
        readAccessor(prim.indices, std::string("indices of ") + label, Use::Indices, &mesh.indices);
        for (std::size_t i = 0; i < mesh.indices.size(); ++i) {
            if (mesh.indices[i] >= vertex_count) {
                fail("accessor " + std::to_string(prim.indices) + " (indices of " + label + "): index " +
                     std::to_string(mesh.indices[i]) + " at position " + std::to_string(i) +
                     " is out of range: the primitive has " + std::to_string(vertex_count) + " vertices");
            }
        }
    } else {
        mesh.indices.resize(vertex_count);
        for (std::size_t i = 0; i < vertex_count; ++i) mesh.indices[i] = static_cast<std::uint32_t>(i);
    }
    if (mesh.indices.size() % 3 != 0) {
        fail(where + ": " + std::to_string(mesh.indices.size()) +
             " indices is not a whole number of triangles");
    }

    if (mesh.normals.empty()) {
        // Flat normals need one vertex per triangle corner: un-share every vertex.
        const std::size_t corners = mesh.indices.size();
        if (corners > kMaxVertices) fail(where + ": too many triangles to generate flat normals");
        std::vector<glm::vec3> positions(corners);
        std::vector<glm::vec3> normals(corners);
        std::vector<glm::vec2> texcoords(corners);
        for (std::size_t t = 0; t < corners; t += 3) {
            for (std::size_t k = 0; k < 3; ++k) {
                positions[t + k] = mesh.positions[mesh.indices[t + k]];
                texcoords[t + k] = mesh.texcoords[mesh.indices[t + k]];
            }
            const glm::vec3 n = faceNormal(positions[t], positions[t + 1], positions[t + 2]);
            normals[t] = normals[t + 1] = normals[t + 2] = n;
        }
        mesh.positions = std::move(positions);
        mesh.normals = std::move(normals);
        mesh.texcoords = std::move(texcoords);
        for (std::size_t i = 0; i < corners; ++i) mesh.indices[i] = static_cast<std::uint32_t>(i);
        mesh.had_normals = false;
        warnings_.push_back("normals generated flat for " + where);
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

void Converter::convertMaterials() {
    for (std::size_t i = 0; i < model_.materials.size(); ++i) {
        const tinygltf::Material& src = model_.materials[i];
        Material m;
        m.name = src.name.empty() ? "material" + std::to_string(i) : src.name;
        const auto& f = src.pbrMetallicRoughness.baseColorFactor;
        const glm::vec4 color = f.size() == 4 ? glm::vec4(static_cast<float>(f[0]), static_cast<float>(f[1]),
                                                          static_cast<float>(f[2]), static_cast<float>(f[3]))
                                              : glm::vec4(std::numeric_limits<float>::quiet_NaN());
        if (std::isfinite(color.r + color.g + color.b + color.a)) {
            m.base_color = color;
        } else {
            warnings_.push_back("material " + std::to_string(i) +
                                ": baseColorFactor is not 4 finite numbers; white used");
        }
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
        for (std::size_t p = 0; p < prims.size(); ++p) {
            const int mode = prims[p].mode;
            if (mode != -1 && mode != TINYGLTF_MODE_TRIANGLES) {
                warnings_.push_back(meshLabel(mesh_index) + " primitive " + std::to_string(p) + ": mode " +
                                    std::to_string(mode) +
                                    " skipped; only triangle lists (mode 4) are drawn");
                continue;
            }
            const int material = prims[p].material;
            if (material < -1 ||
                (material >= 0 && static_cast<std::size_t>(material) >= model_.materials.size())) {
                fail(meshLabel(mesh_index) + " primitive " + std::to_string(p) + ": material " +
                     std::to_string(material) + " does not exist (the file has " +
                     std::to_string(model_.materials.size()) + " materials)");
            }
            if (scene_.draw_items.size() >= kMaxDrawItems) {
                fail("the scene has more than " + std::to_string(kMaxDrawItems) + " draw items");
            }
            DrawItem item;
            item.node_name = node.name.empty() ? "node" + std::to_string(node_index) : node.name;
            item.mesh = convertPrimitive(mesh_index, p);
            item.material = material;
            item.world = world;
            scene_.draw_items.push_back(std::move(item));
        }
    }
    if (node.camera != -1) {
        if (node.camera < 0 || static_cast<std::size_t>(node.camera) >= model_.cameras.size()) {
            fail(who + ": camera " + std::to_string(node.camera) + " does not exist (the file has " +
                 std::to_string(model_.cameras.size()) + " cameras)");
        }
        const auto& cam = model_.cameras[static_cast<std::size_t>(node.camera)];
        if (cam.type != "perspective") {
            warnings_.push_back(who + ": camera " + std::to_string(node.camera) + " is " +
                                inQuotes(cam.type) + ", not perspective; ignored");
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
        checkCamera();
        return;
    }

    const auto& node = model_.nodes[static_cast<std::size_t>(camera_node_)];
    const auto& p = model_.cameras[static_cast<std::size_t>(node.camera)].perspective;
    const std::string who = "camera " + std::to_string(node.camera);
    if (!std::isfinite(p.yfov) || p.yfov <= 0.0 || p.yfov >= 3.14159) fail(who + ": yfov must be in (0, pi)");
    if (!std::isfinite(p.znear) || p.znear <= 0.0) fail(who + ": znear must be > 0");
    if (!std::isfinite(p.zfar) || (p.zfar != 0.0 && p.zfar <= p.znear)) fail(who + ": zfar must be > znear");
    if (!std::isfinite(p.aspectRatio) || p.aspectRatio < 0.0) fail(who + ": aspectRatio must be > 0");

    scene_.has_camera = true;
    cam.fov_y_deg = static_cast<float>(p.yfov * 180.0 / 3.14159265358979323846);
    cam.z_near = static_cast<float>(p.znear);
    cam.file_aspect = static_cast<float>(p.aspectRatio);
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
    if (p.zfar > 0.0) {
        cam.z_far = static_cast<float>(p.zfar);
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
    for (const std::string& ext : model_.extensionsRequired) {
        // Material extensions only change shading the labs replace anyway; anything that changes
        // geometry (Draco, quantization, ...) would be read wrongly, so it is refused.
        if (ext != "KHR_lights_punctual" && ext.rfind("KHR_materials_", 0) != 0 &&
            ext != "KHR_texture_transform") {
            fail("requires extension " + inQuotes(ext) + ", which shaderlab does not support");
        }
    }
    convertMaterials();
    walkNodes();
    computeBounds();
    placeCamera();
}

}  // namespace

SceneLoadResult loadGltfScene(const std::string& path, Scene* out) {
    SceneLoadResult result;
    if (out == nullptr) {
        result.error = path + ": no Scene to load into";
        return result;
    }
    *out = Scene{};
    try {
        const FileText file = readFile(path, kMaxFileBytes);
        if (!file.ok) fail(file.error.rfind(path, 0) == 0 ? file.error.substr(path.size() + 2) : file.error);
        const std::string& bytes = file.text;
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
        gltf.SetImageLoader(&skipImage, nullptr);

        tinygltf::Model model;
        std::string err;
        std::string warn;
        bool loaded = false;
        const bool glb_magic = bytes.size() >= 4 && bytes.compare(0, 4, "glTF") == 0;
        const std::string ext = fs::path(path).extension().string();
        if (glb_magic) {
            const std::size_t length = checkGlbLayout(bytes, &result.warnings);
            const std::size_t json_length = readU32(bytes, 12);
            checkJson(bytes.data() + 20, bytes.data() + 20 + json_length);
            loaded = gltf.LoadBinaryFromMemory(&model, &err, &warn,
                                               reinterpret_cast<const unsigned char*>(bytes.data()),
                                               static_cast<unsigned int>(length), guard.folder);
        } else {
            if (ext == ".glb" || ext == ".GLB")
                fail("not a GLB file: it does not start with the 'glTF' magic");
            checkJson(bytes.data(), bytes.data() + bytes.size());
            loaded = gltf.LoadASCIIFromString(&model, &err, &warn, bytes.data(),
                                              static_cast<unsigned int>(bytes.size()), guard.folder);
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
        Converter(model, &scene, &result.warnings).run();
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
