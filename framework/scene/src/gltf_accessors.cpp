// The glTF loader's reading of binary data: buffer views, accessors (every layout the
// specification and KHR_mesh_quantization allow, interleaved or not, sparse or not), and the two
// compressions, EXT_meshopt_compression (whole views, decoded up front with libmeshoptimizer) and
// KHR_draco_mesh_compression (one primitive's geometry, decoded with libdraco). Every index,
// offset, length and stride is checked against what the Model holds before a byte is read.
// What it does not: decide what an attribute means or how a primitive is drawn
// (gltf_primitives.cpp), or fetch buffers and data URIs; tinygltf does that, through the guarded
// callbacks of gltf_loader.cpp.
// Buffers are read as little-endian, which is what glTF stores and what the hosts we run on are.
#include <draco/compression/decode.h>
#ifndef SHADERLAB_NO_MESHOPT
#include <meshoptimizer.h>
#endif
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "gltf_converter.h"

namespace shaderlab::gltf_detail {

namespace {

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

[[maybe_unused]] std::string extensionString(const tinygltf::Value& object, const char* key,
                                             const std::string& who, const std::string& fallback) {
    if (!object.Has(key)) return fallback;
    const tinygltf::Value& v = object.Get(key);
    if (!v.IsString()) fail(who + ": \"" + key + "\" must be a string");
    return v.Get<std::string>();
}

}  // namespace

// Validates bufferView `index` and the buffer it lies in; `who` names the referrer. A view
// compressed with EXT_meshopt_compression answers with its decoded bytes.
Bytes Converter::bufferView(int index, const std::string& who) const {
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
std::size_t Converter::readAccessor(int index, const std::string& role, Use use, std::vector<T>* out,
                                    std::size_t* components_out) const {
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
        fail(who + ": count " + std::to_string(acc.count) + " is over the limit of " + std::to_string(limit));
    }
    const std::size_t components = typeComponents(acc.type);
    if (components_out) *components_out = components;
    const std::size_t comp_size = componentSize(acc.componentType);
    const std::size_t element = comp_size * components;
    out->assign(acc.count * components, T{});

    if (acc.bufferView == -1 && acc.count > kMaxUnbackedCount) {
        fail(who + ": count " + std::to_string(acc.count) + " without a bufferView is over the limit of " +
             std::to_string(kMaxUnbackedCount));
    }
    if (acc.bufferView != -1) {
        const Bytes view = bufferView(acc.bufferView, who);
        const std::size_t declared = viewStride(acc.bufferView);
        if (declared != 0 && (declared < element || declared > 252 || declared % 4 != 0)) {
            fail(who + ": byteStride " + std::to_string(declared) + " of bufferView " +
                 std::to_string(acc.bufferView) + " is invalid for " + std::to_string(element) +
                 "-byte elements (must be 0, or a multiple of 4 in " + std::to_string(element) + "..252)");
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
std::size_t Converter::viewStride(int index) const {
    const auto it = meshopt_strides_.find(index);
    if (it != meshopt_strides_.end()) return it->second;
    return model_.bufferViews[static_cast<std::size_t>(index)].byteStride;
}

// Overwrites the elements a sparse accessor names (spec 3.6.2.3): indices strictly
// increasing and below count, values tightly packed.
template <typename T>
void Converter::applySparse(const tinygltf::Accessor& acc, const std::string& who, std::size_t components,
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

// The element types the loader reads accessors as: floats for attributes, integers for indices.
template std::size_t Converter::readAccessor<float>(int, const std::string&, Use, std::vector<float>*,
                                                    std::size_t*) const;
template std::size_t Converter::readAccessor<std::uint32_t>(int, const std::string&, Use,
                                                            std::vector<std::uint32_t>*, std::size_t*) const;

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
#ifdef SHADERLAB_NO_MESHOPT
        // The portable build (cmake/Portable.cmake): Debian 11 has no static libmeshoptimizer.
        fail(who +
             ": this shaderlab is the portable build, which cannot decode meshopt-compressed "
             "data; save the scene without EXT_meshopt_compression, or grade it with a shaderlab "
             "built from source");
        (void)e;
        (void)total;
        (void)kMaxDecodedBytes;
#else
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
#endif
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

}  // namespace shaderlab::gltf_detail
