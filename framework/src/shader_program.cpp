// GLSL compile/link with structured logs; see shader_program.h.
#include "shaderlab/shader_program.h"

#include <cctype>
#include <chrono>
#include <cstring>
#include <glm/gtc/type_ptr.hpp>
#include <regex>
#include <sstream>

#include "shaderlab/gl.h"

namespace shaderlab {

namespace {

// Skips blank lines, // comments and /* */ comments at the start of the file to find the
// `#version` directive, which must come before anything else but comments and whitespace.
int findVersionLine(const std::vector<std::string>& lines) {
    bool in_block = false;
    for (std::size_t i = 0; i < lines.size(); ++i) {
        std::string s = lines[i];
        std::size_t p = 0;
        while (p < s.size()) {
            if (in_block) {
                const auto end = s.find("*/", p);
                if (end == std::string::npos) {
                    p = s.size();
                    break;
                }
                in_block = false;
                p = end + 2;
                continue;
            }
            if (s[p] == ' ' || s[p] == '\t' || s[p] == '\r') {
                ++p;
                continue;
            }
            if (s.compare(p, 2, "//") == 0) {
                p = s.size();
                break;
            }
            if (s.compare(p, 2, "/*") == 0) {
                in_block = true;
                p += 2;
                continue;
            }
            if (s[p] == '#') {
                std::size_t q = p + 1;
                while (q < s.size() && (s[q] == ' ' || s[q] == '\t')) ++q;
                if (s.compare(q, 7, "version") == 0) return static_cast<int>(i);
            }
            return -1;  // first real token is not #version
        }
    }
    return -1;
}

std::vector<std::string> splitLines(const std::string& text) {
    std::vector<std::string> lines;
    std::string line;
    std::istringstream in(text);
    while (std::getline(in, line)) lines.push_back(line);
    return lines;
}

// The GLSL type a lab.json value stands for.
unsigned glTypeOf(const UniformValue& v) {
    switch (v.index()) {
        case 0:
            return GL_FLOAT;
        case 1:
            return GL_INT;
        case 2:
            return GL_BOOL;
        case 3:
            return GL_FLOAT_VEC2;
        case 4:
            return GL_FLOAT_VEC3;
        case 5:
            return GL_FLOAT_VEC4;
        case 6:
            return GL_FLOAT_MAT3;
        default:
            return GL_FLOAT_MAT4;
    }
}

const char* glslTypeName(unsigned type) {
    switch (type) {
        case GL_FLOAT:
            return "float";
        case GL_INT:
            return "int";
        case GL_BOOL:
            return "bool";
        case GL_FLOAT_VEC2:
            return "vec2";
        case GL_FLOAT_VEC3:
            return "vec3";
        case GL_FLOAT_VEC4:
            return "vec4";
        case GL_FLOAT_MAT3:
            return "mat3";
        case GL_FLOAT_MAT4:
            return "mat4";
        case GL_SAMPLER_2D:
            return "sampler2D";
        case GL_SAMPLER_CUBE:
            return "samplerCube";
        default:
            return "another type";
    }
}

}  // namespace

std::string defaultPrelude() {
    return "#define SHADERLAB 1\n"
           "#define SL_MAX_LIGHTS 4\n";
}

PreparedSource prepareSource(const std::string& student_text, const std::string& prelude) {
    // A UTF-8 byte-order mark (some Windows editors write one) is not GLSL.
    const bool bom = student_text.compare(0, 3, "\xEF\xBB\xBF") == 0;
    const std::vector<std::string> lines = splitLines(bom ? student_text.substr(3) : student_text);
    const int version_line = findVersionLine(lines);
    PreparedSource out;
    std::string text;
    int next_student_line = 1;
    // GLSL 3.30 (ES 3.00) and later: "#line N" numbers the next line N. Earlier versions number
    // it N + 1 (GLSL 1.50 section 3.3), so the directive must say one less.
    bool old_line_rule = false;
    if (version_line >= 0) {
        const std::string& v = lines[static_cast<std::size_t>(version_line)];
        static const std::regex version_re(R"(#\s*version\s+(\d+)\s*(es)?)");
        std::smatch m;
        if (std::regex_search(v, m, version_re)) {
            const int number = std::stoi(m[1]);
            old_line_rule = m[2].matched ? number < 300 : number < 330;
        }
        for (int i = 0; i <= version_line; ++i) text += lines[static_cast<std::size_t>(i)] + "\n";
        next_student_line = version_line + 2;
    } else {
        text += "#version 330 core\n";
    }
    text += prelude;
    text += "#line " + std::to_string(old_line_rule ? next_student_line - 1 : next_student_line) + " 0\n";
    for (std::size_t i = static_cast<std::size_t>(next_student_line - 1); i < lines.size(); ++i)
        text += lines[i] + "\n";
    out.text = std::move(text);
    out.first_student_line = next_student_line;
    return out;
}

std::vector<Diagnostic> parseInfoLog(const std::string& log, const std::string& file) {
    // Mesa:      0:12(5): error: `x' undeclared
    // NVIDIA:    0(12) : error C1008: undefined variable "x"
    // Others:    ERROR: 0:12: 'x' : undeclared identifier
    static const std::regex mesa(
        R"(^\s*\d+:(\d+)\((\d+)\):\s*(?:preprocessor\s+)?(error|warning)\s*:?\s*(.*)$)", std::regex::icase);
    static const std::regex nvidia(R"(^\s*\d+\((\d+)\)\s*:\s*(error|warning)\s*\w*\s*:?\s*(.*)$)",
                                   std::regex::icase);
    static const std::regex khr(R"(^\s*(ERROR|WARNING)\s*:\s*\d+:(\d+)\s*:?\s*(.*)$)", std::regex::icase);
    std::vector<Diagnostic> out;
    for (const std::string& raw : splitLines(log)) {
        std::string line = raw;
        while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
        if (line.empty()) continue;
        std::smatch m;
        Diagnostic d;
        d.file = file;
        auto lower = [](std::string s) {
            for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
            return s;
        };
        if (std::regex_match(line, m, mesa)) {
            d.line = std::stoi(m[1]);
            d.column = std::stoi(m[2]);
            d.severity = lower(m[3]);
            d.message = m[4];
        } else if (std::regex_match(line, m, nvidia)) {
            d.line = std::stoi(m[1]);
            d.severity = lower(m[2]);
            d.message = m[3];
        } else if (std::regex_match(line, m, khr)) {
            d.severity = lower(m[1]);
            d.line = std::stoi(m[2]);
            d.message = m[3];
        } else {
            // A continuation of the previous message, or a line without a position.
            if (!out.empty() && (raw.rfind(' ', 0) == 0 || raw.rfind('\t', 0) == 0)) {
                out.back().message += "\n" + line;
                continue;
            }
            d.severity = line.find("warning") != std::string::npos ? "warning" : "error";
            d.message = line;
        }
        out.push_back(std::move(d));
    }
    return out;
}

ShaderProgram::~ShaderProgram() { release(); }

ShaderProgram::ShaderProgram(ShaderProgram&& other) noexcept { *this = std::move(other); }

ShaderProgram& ShaderProgram::operator=(ShaderProgram&& other) noexcept {
    if (this != &other) {
        release();
        program_ = other.program_;
        other.program_ = 0;
        compiled_ = other.compiled_;
        linked_ = other.linked_;
        stages_ = std::move(other.stages_);
        link_log_ = std::move(other.link_log_);
        diagnostics_ = std::move(other.diagnostics_);
        uniforms_ = std::move(other.uniforms_);
    }
    return *this;
}

void ShaderProgram::release() {
    if (program_) glDeleteProgram(program_);
    program_ = 0;
}

bool ShaderProgram::build(const std::string& vertex_file, const std::string& vertex_text,
                          const std::string& fragment_file, const std::string& fragment_text) {
    release();
    stages_.clear();
    diagnostics_.clear();
    uniforms_.clear();
    link_log_.clear();
    compiled_ = linked_ = false;

    auto compile = [this](GLenum kind, const std::string& file, const std::string& text) -> GLuint {
        StageLog log;
        log.file = file;
        log.stage = kind == GL_VERTEX_SHADER ? "vertex" : "fragment";
        const PreparedSource src = prepareSource(text, defaultPrelude());
        const auto t0 = std::chrono::steady_clock::now();
        const GLuint shader = glCreateShader(kind);
        const char* ptr = src.text.c_str();
        glShaderSource(shader, 1, &ptr, nullptr);
        glCompileShader(shader);
        GLint ok = GL_FALSE;
        glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
        log.compile_us =
            std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
        GLint len = 0;
        glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &len);
        if (len > 1) {
            std::string buf(static_cast<std::size_t>(len), '\0');
            glGetShaderInfoLog(shader, len, nullptr, buf.data());
            buf.resize(std::strlen(buf.c_str()));
            log.info_log = buf;
        }
        log.compiled = ok == GL_TRUE;
        for (auto& d : parseInfoLog(log.info_log, file)) diagnostics_.push_back(std::move(d));
        stages_.push_back(std::move(log));
        if (ok != GL_TRUE) {
            glDeleteShader(shader);
            return 0;
        }
        return shader;
    };

    const GLuint vs = compile(GL_VERTEX_SHADER, vertex_file, vertex_text);
    const GLuint fs = compile(GL_FRAGMENT_SHADER, fragment_file, fragment_text);
    if (!vs || !fs) {
        if (vs) glDeleteShader(vs);
        if (fs) glDeleteShader(fs);
        return false;
    }
    compiled_ = true;
    program_ = glCreateProgram();
    glAttachShader(program_, vs);
    glAttachShader(program_, fs);
    // The attribute contract (docs/student-contract.md) holds even without layout qualifiers.
    glBindAttribLocation(program_, 0, "a_position");
    glBindAttribLocation(program_, 1, "a_normal");
    glBindAttribLocation(program_, 2, "a_texcoord");
    glLinkProgram(program_);
    glDetachShader(program_, vs);
    glDetachShader(program_, fs);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = GL_FALSE;
    glGetProgramiv(program_, GL_LINK_STATUS, &ok);
    GLint len = 0;
    glGetProgramiv(program_, GL_INFO_LOG_LENGTH, &len);
    if (len > 1) {
        std::string buf(static_cast<std::size_t>(len), '\0');
        glGetProgramInfoLog(program_, len, nullptr, buf.data());
        buf.resize(std::strlen(buf.c_str()));
        link_log_ = buf;
        // Link errors concern the pair; attribute them to the fragment shader's file with
        // both names in the message when the driver gives no position.
        for (auto& d : parseInfoLog(link_log_, vertex_file + " + " + fragment_file))
            diagnostics_.push_back(d);
    }
    linked_ = ok == GL_TRUE;
    if (!linked_) return false;

    GLint count = 0;
    glGetProgramiv(program_, GL_ACTIVE_UNIFORMS, &count);
    for (GLint i = 0; i < count; ++i) {
        char name[256];
        GLsizei name_len = 0;
        GLint size = 0;
        GLenum type = 0;
        glGetActiveUniform(program_, static_cast<GLuint>(i), sizeof name, &name_len, &size, &type, name);
        std::string n(name, static_cast<std::size_t>(name_len));
        UniformSlot slot;
        slot.location = glGetUniformLocation(program_, n.c_str());
        slot.type = type;
        slot.size = size;
        if (n.size() > 3 && n.compare(n.size() - 3, 3, "[0]") == 0) n.resize(n.size() - 3);
        if (slot.location >= 0) uniforms_[n] = slot;
    }
    return true;
}

const UniformSlot* ShaderProgram::uniform(const std::string& name) const {
    const auto it = uniforms_.find(name);
    return it == uniforms_.end() ? nullptr : &it->second;
}

std::string ShaderProgram::set(const std::string& name, const UniformValue& value) const {
    const UniformSlot* slot = uniform(name);
    if (!slot) return {};  // not used by this shader: nothing to do
    const unsigned want = glTypeOf(value);
    const bool int_like = slot->type == GL_INT || slot->type == GL_BOOL;
    if (slot->type != want && !(int_like && (want == GL_INT || want == GL_BOOL))) {
        return "uniform " + name + " is declared " + glslTypeName(slot->type) +
               " in the shader but lab.json gives " + glslTypeName(want);
    }
    glUseProgram(program_);
    std::visit(
        [slot](const auto& v) {
            using T = std::decay_t<decltype(v)>;
            if constexpr (std::is_same_v<T, float>)
                glUniform1f(slot->location, v);
            else if constexpr (std::is_same_v<T, int>)
                glUniform1i(slot->location, v);
            else if constexpr (std::is_same_v<T, bool>)
                glUniform1i(slot->location, v ? 1 : 0);
            else if constexpr (std::is_same_v<T, glm::vec2>)
                glUniform2fv(slot->location, 1, glm::value_ptr(v));
            else if constexpr (std::is_same_v<T, glm::vec3>)
                glUniform3fv(slot->location, 1, glm::value_ptr(v));
            else if constexpr (std::is_same_v<T, glm::vec4>)
                glUniform4fv(slot->location, 1, glm::value_ptr(v));
            else if constexpr (std::is_same_v<T, glm::mat3>)
                glUniformMatrix3fv(slot->location, 1, GL_FALSE, glm::value_ptr(v));
            else
                glUniformMatrix4fv(slot->location, 1, GL_FALSE, glm::value_ptr(v));
        },
        value);
    return {};
}

}  // namespace shaderlab
