// lab.json values into uniforms by declared type; see uniform_values.h.
#include "uniform_values.h"

#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "gl_types.h"
#include "shaderlab/base/json_messages.h"
#include "shaderlab/gl/gl.h"

namespace shaderlab {

namespace {

using json = nlohmann::json;

struct Leaf {
    const UniformSlot* slot;
    int element;  // array element, 0 for non-arrays
    json value;
    std::string path;
};

std::string declared(const UniformSlot& s) {
    std::string d = std::string("the shader declares `") + glslTypeName(s.type) + " " + s.name;
    if (s.size > 1) d += "[" + std::to_string(s.size) + "]";
    return d + "`";
}

bool isIntegral(const json& v) { return v.is_number_integer() || v.is_number_unsigned(); }

// What one element of `info`'s type looks like in lab.json, for messages.
std::string shapeWords(const GlTypeInfo& info, unsigned type) {
    const char* scalar = info.kind == ScalarKind::Float  ? "number"
                         : info.kind == ScalarKind::Bool ? "true/false"
                         : info.kind == ScalarKind::Uint ? "non-negative integer"
                                                         : "integer";
    if (info.components == 1) return std::string("a ") + scalar;
    if (info.columns > 1)
        return std::to_string(info.components) + " numbers (column-major) or " +
               std::to_string(info.columns) + " columns of " + std::to_string(info.rows);
    (void)type;
    return std::to_string(info.components) + " " + scalar + (info.kind == ScalarKind::Bool ? " values" : "s");
}

// Reads one element of type `slot->type` from `v` into 32-bit words. Returns "" or a problem.
std::string parseElement(const UniformSlot& slot, const json& v, const PassCameraLookup& cameras,
                         std::vector<std::uint32_t>* words) {
    const GlTypeInfo info = glTypeInfo(slot.type);
    words->assign(static_cast<std::size_t>(info.components), 0u);
    auto putFloat = [&](std::size_t i, float f) { std::memcpy(&(*words)[i], &f, sizeof f); };
    if (v.is_string()) {
        // "@pass.what": the schema guarantees the form.
        const std::string s = v.get<std::string>();
        const std::size_t dot = s.rfind('.');
        const std::string pass = s.substr(1, dot - 1), what = s.substr(dot + 1);
        const PassCameraValues* cam = cameras ? cameras(pass) : nullptr;
        if (!cam) return "no pass is called \"" + pass + "\"";
        const bool matrix = what != "camera_position";
        if (matrix ? slot.type != GL_FLOAT_MAT4 : slot.type != GL_FLOAT_VEC3)
            return quoteJson(s) + " is a " + (matrix ? "mat4" : "vec3") + ", but " + declared(slot);
        const float* src = what == "view"              ? &cam->view[0][0]
                           : what == "projection"      ? &cam->projection[0][0]
                           : what == "camera_position" ? &cam->position[0]
                                                       : nullptr;
        glm::mat4 vp;
        if (what == "view_projection") {
            vp = cam->projection * cam->view;
            src = &vp[0][0];
        }
        for (int i = 0; i < info.components; ++i) putFloat(static_cast<std::size_t>(i), src[i]);
        return {};
    }
    // Flatten matrices given as columns.
    json flat = v;
    if (info.columns > 1 && v.is_array() && v.size() == static_cast<std::size_t>(info.columns) &&
        v[0].is_array()) {
        flat = json::array();
        for (const json& col : v) {
            if (!col.is_array() || col.size() != static_cast<std::size_t>(info.rows)) {
                flat = v;
                break;
            }
            for (const json& x : col) flat.push_back(x);
        }
    }
    const bool scalar = info.components == 1;
    if (scalar ? flat.is_array()
               : (!flat.is_array() || flat.size() != static_cast<std::size_t>(info.components)))
        return "expected " + shapeWords(info, slot.type) + ", got " + describeJson(v) + ": " + declared(slot);
    for (int i = 0; i < info.components; ++i) {
        const json& x = scalar ? flat : flat[static_cast<std::size_t>(i)];
        const std::size_t at = static_cast<std::size_t>(i);
        switch (info.kind) {
            case ScalarKind::Float:
                if (!x.is_number())
                    return "expected " + shapeWords(info, slot.type) + ", got " + describeJson(v) + ": " +
                           declared(slot);
                putFloat(at, x.get<float>());
                break;
            case ScalarKind::Bool:
                if (!x.is_boolean())
                    return "expected " + shapeWords(info, slot.type) + ", got " + describeJson(v) + ": " +
                           declared(slot);
                (*words)[at] = x.get<bool>() ? 1u : 0u;
                break;
            case ScalarKind::Int: {
                if (!isIntegral(x))
                    return "expected " + shapeWords(info, slot.type) + ", got " + describeJson(v) + ": " +
                           declared(slot);
                const double d = x.get<double>();
                if (d < std::numeric_limits<std::int32_t>::min() ||
                    d > std::numeric_limits<std::int32_t>::max())
                    return x.dump() + " does not fit a 32-bit int: " + declared(slot);
                const std::int32_t n = x.get<std::int32_t>();
                std::memcpy(&(*words)[at], &n, sizeof n);
                break;
            }
            case ScalarKind::Uint:
                if (!isIntegral(x) || x.get<double>() < 0 || x.get<double>() > 4294967295.0)
                    return "expected " + shapeWords(info, slot.type) + ", got " + describeJson(v) + ": " +
                           declared(slot);
                (*words)[at] = x.get<std::uint32_t>();
                break;
            default:
                return std::string("uniforms of type ") + glslTypeName(slot.type) +
                       " cannot be set from lab.json";
        }
    }
    return {};
}

void upload(GLint location, unsigned type, const std::vector<std::uint32_t>& words) {
    const auto* f = reinterpret_cast<const GLfloat*>(words.data());
    const auto* i = reinterpret_cast<const GLint*>(words.data());
    const auto* u = reinterpret_cast<const GLuint*>(words.data());
    switch (type) {
        case GL_FLOAT_MAT2:
            return glUniformMatrix2fv(location, 1, GL_FALSE, f);
        case GL_FLOAT_MAT3:
            return glUniformMatrix3fv(location, 1, GL_FALSE, f);
        case GL_FLOAT_MAT4:
            return glUniformMatrix4fv(location, 1, GL_FALSE, f);
        case GL_FLOAT_MAT2x3:
            return glUniformMatrix2x3fv(location, 1, GL_FALSE, f);
        case GL_FLOAT_MAT2x4:
            return glUniformMatrix2x4fv(location, 1, GL_FALSE, f);
        case GL_FLOAT_MAT3x2:
            return glUniformMatrix3x2fv(location, 1, GL_FALSE, f);
        case GL_FLOAT_MAT3x4:
            return glUniformMatrix3x4fv(location, 1, GL_FALSE, f);
        case GL_FLOAT_MAT4x2:
            return glUniformMatrix4x2fv(location, 1, GL_FALSE, f);
        case GL_FLOAT_MAT4x3:
            return glUniformMatrix4x3fv(location, 1, GL_FALSE, f);
        default:
            break;
    }
    const GlTypeInfo info = glTypeInfo(type);
    const int n = info.components;
    if (info.kind == ScalarKind::Float) {
        if (n == 1) glUniform1fv(location, 1, f);
        if (n == 2) glUniform2fv(location, 1, f);
        if (n == 3) glUniform3fv(location, 1, f);
        if (n == 4) glUniform4fv(location, 1, f);
    } else if (info.kind == ScalarKind::Uint) {
        if (n == 1) glUniform1uiv(location, 1, u);
        if (n == 2) glUniform2uiv(location, 1, u);
        if (n == 3) glUniform3uiv(location, 1, u);
        if (n == 4) glUniform4uiv(location, 1, u);
    } else {
        if (n == 1) glUniform1iv(location, 1, i);
        if (n == 2) glUniform2iv(location, 1, i);
        if (n == 3) glUniform3iv(location, 1, i);
        if (n == 4) glUniform4iv(location, 1, i);
    }
}

bool hasMemberOrElement(const ShaderProgram& program, const std::string& prefix) {
    for (const UniformSlot& s : program.uniforms())
        if (s.name.compare(0, prefix.size(), prefix) == 0) return true;
    return false;
}

// Splits a value into leaves, one per (uniform, element), by what the program declares.
// Returns "" or a problem; *found is false when nothing of that name is active.
std::string flatten(const ShaderProgram& program, const std::string& name, const json& value,
                    const std::string& path, std::vector<Leaf>* leaves, bool* found) {
    if (const UniformSlot* slot = program.uniform(name)) {
        const GlTypeInfo info = glTypeInfo(slot->type);
        if (info.kind == ScalarKind::Sampler)
            return path + ": " + declared(*slot) + ", a sampler: give it a texture in the pass's \"inputs\"";
        if (slot->size == 1) {
            leaves->push_back({slot, 0, value, path});
            return {};
        }
        if (!value.is_array())
            return path + ": expected an array of up to " + std::to_string(slot->size) + " elements, got " +
                   describeJson(value) + ": " + declared(*slot);
        // An array of vectors or matrices may also be written flat.
        const std::size_t per = static_cast<std::size_t>(info.components);
        const bool flat = per > 1 && !value.empty() && value[0].is_number();
        const std::size_t elements = flat ? value.size() / per : value.size();
        if ((flat && value.size() % per != 0) || elements > static_cast<std::size_t>(slot->size))
            return path + ": has " + std::to_string(value.size()) +
                   " values, more than (or not a multiple of) what " + declared(*slot) + " holds";
        for (std::size_t e = 0; e < elements; ++e) {
            json element = value[e];
            if (flat) {
                element = json::array();
                for (std::size_t k = 0; k < per; ++k) element.push_back(value[e * per + k]);
            }
            leaves->push_back({slot, static_cast<int>(e), element, joinIndex(path, e)});
        }
        return {};
    }
    if (value.is_object() && hasMemberOrElement(program, name + ".")) {
        for (const auto& item : value.items()) {
            bool member_found = true;
            const std::string problem = flatten(program, name + "." + item.key(), item.value(),
                                                joinKey(path, item.key()), leaves, &member_found);
            if (!problem.empty()) return problem;
            if (!member_found)
                return joinKey(path, item.key()) + ": the shader's struct has no active member " +
                       quoteJson(item.key());
        }
        return {};
    }
    if (value.is_array() && hasMemberOrElement(program, name + "[")) {
        for (std::size_t e = 0; e < value.size(); ++e) {
            bool element_found = true;
            const std::string element = name + "[" + std::to_string(e) + "]";
            const std::string problem =
                flatten(program, element, value[e], joinIndex(path, e), leaves, &element_found);
            if (!problem.empty()) return problem;
            if (!element_found && !hasMemberOrElement(program, element))
                return joinIndex(path, e) + ": the shader's array " + name + " has no element " +
                       std::to_string(e);
        }
        return {};
    }
    *found = false;
    return {};
}

bool identifierChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

}  // namespace

UniformApplyResult applyUniform(const ShaderProgram& program, const UniformSetting& setting,
                                const PassCameraLookup& cameras) {
    UniformApplyResult r;
    std::vector<Leaf> leaves;
    r.error = flatten(program, setting.name, setting.value, setting.path, &leaves, &r.declared);
    if (!r.error.empty() || !r.declared) return r;
    std::vector<std::vector<std::uint32_t>> words(leaves.size());
    for (std::size_t i = 0; i < leaves.size(); ++i) {
        const std::string problem = parseElement(*leaves[i].slot, leaves[i].value, cameras, &words[i]);
        if (!problem.empty()) {
            r.error = leaves[i].path + ": " + problem;
            return r;
        }
    }
    for (std::size_t i = 0; i < leaves.size(); ++i) {
        const Leaf& leaf = leaves[i];
        GLint location = leaf.slot->location;
        if (leaf.element > 0) {
            const std::string element = leaf.slot->name + "[" + std::to_string(leaf.element) + "]";
            location = glGetUniformLocation(program.id(), element.c_str());
        }
        if (location >= 0) upload(location, leaf.slot->type, words[i]);
    }
    return r;
}

bool mentionsIdentifier(const std::string& text, const std::string& name) {
    for (std::size_t at = text.find(name); at != std::string::npos; at = text.find(name, at + 1)) {
        const bool start = at == 0 || !identifierChar(text[at - 1]);
        const bool end = at + name.size() >= text.size() || !identifierChar(text[at + name.size()]);
        if (start && end) return true;
    }
    return false;
}

std::vector<std::string> declaredUniformNames(const std::string& text) {
    // "uniform <type> <name>" (qualifiers such as precision or layout before it are skipped).
    std::vector<std::string> names;
    for (std::size_t at = text.find("uniform"); at != std::string::npos; at = text.find("uniform", at + 7)) {
        if ((at > 0 && identifierChar(text[at - 1])) ||
            (at + 7 < text.size() && identifierChar(text[at + 7])))
            continue;
        std::size_t p = at + 7;
        std::vector<std::string> words;
        while (p < text.size() && words.size() < 4) {
            while (p < text.size() && std::isspace(static_cast<unsigned char>(text[p]))) ++p;
            std::size_t q = p;
            while (q < text.size() && identifierChar(text[q])) ++q;
            if (q == p) break;
            words.push_back(text.substr(p, q - p));
            p = q;
        }
        if (words.size() >= 2) names.push_back(words.back());
    }
    return names;
}

}  // namespace shaderlab
