// GLSL compile/link with structured logs; see shader_program.h.
#include "shaderlab/render/shader_program.h"

#include <xxhash.h>

#include <cctype>
#include <chrono>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <set>
#include <sstream>

#include "gl_types.h"
#include "grader/base/atomic_file.h"
#include "shaderlab/feedback/glsl_explain.h"
#include "shaderlab/gl/gl.h"
#include "shaderlab/gl/gl_context.h"

namespace shaderlab {

namespace {

constexpr int kMaxIncludeDepth = 16;
// Driver log lines longer than this are cut before any regex sees them (std::regex recurses per
// character and a student can make the driver echo a huge line).
constexpr std::size_t kMaxLogLine = 2000;
// A driver log is cut after this many bytes, and at most this many of its messages are explained.
constexpr std::size_t kMaxLogBytes = 1u << 20;
constexpr std::size_t kMaxExplained = 40;
// A message and its continuation lines (Mesa's candidate signatures) stop growing past this.
constexpr std::size_t kMaxMessage = 8000;

// Skips blank lines, // comments and /* */ comments at the start of the file to find the
// `#version` directive, which must come before anything else but comments and whitespace.
int findVersionLine(const std::vector<std::string>& lines) {
    bool in_block = false;
    for (std::size_t i = 0; i < lines.size(); ++i) {
        const std::string& s = lines[i];
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

// A decimal number from a log or directive, clamped to int range (a student can write
// "#line 2147483646" or "#version 99999999999").
int clampedInt(const std::string& digits) {
    errno = 0;
    const long long v = std::strtoll(digits.c_str(), nullptr, 10);
    if (errno == ERANGE || v > INT_MAX) return INT_MAX;
    return v < INT_MIN ? INT_MIN : static_cast<int>(v);
}

// The file name of `#include "name"` when `line` is such a directive.
bool includeDirective(const std::string& line, std::string* name) {
    std::size_t p = 0;
    while (p < line.size() && (line[p] == ' ' || line[p] == '\t')) ++p;
    if (p >= line.size() || line[p] != '#') return false;
    ++p;
    while (p < line.size() && (line[p] == ' ' || line[p] == '\t')) ++p;
    if (line.compare(p, 7, "include") != 0) return false;
    p += 7;
    while (p < line.size() && (line[p] == ' ' || line[p] == '\t')) ++p;
    if (p >= line.size() || line[p] != '"') return false;
    const std::size_t close = line.find('"', p + 1);
    if (close == std::string::npos) return false;
    *name = line.substr(p + 1, close - p - 1);
    return true;
}

// A NUL byte in a shader file: the driver would read the source only up to it (C strings), so
// the rest of the file would vanish without a word. Finds the first one, as line and column.
bool findNulByte(const std::string& text, const std::string& file, Diagnostic* d) {
    const std::size_t at = text.find('\0');
    if (at == std::string::npos) return false;
    int line = 1;
    for (std::size_t i = 0; i < at; ++i) line += text[i] == '\n' ? 1 : 0;
    // No column: the line as a report shows it is cut at the NUL.
    *d = {file,
          line,
          0,
          "error",
          "this file holds a NUL byte (byte " + std::to_string(at) + " of the file, line " +
              std::to_string(line) + "): it is not plain text, so it was not compiled",
          "A shader file is plain text. A NUL byte comes from a file saved as UTF-16 (some Windows "
          "editors) or from a binary file in its place: save it again as UTF-8 text."};
    return true;
}

struct Expander {
    const IncludeReader& includes;
    bool old_line_rule;
    PreparedSource& out;
    std::set<std::string> seen;  // resolved paths already included

    std::string lineDirective(int next_line, std::size_t file) const {
        return "#line " + std::to_string(old_line_rule ? next_line - 1 : next_line) + " " +
               std::to_string(file) + "\n";
    }

    // Appends lines[first..] of file `file` (numbered from first_number), expanding includes.
    void append(const std::vector<std::string>& lines, std::size_t first, int first_number, std::size_t file,
                int depth, std::string& text) {
        for (std::size_t i = first; i < lines.size(); ++i) {
            const int number = first_number + static_cast<int>(i - first);
            std::string name;
            if (!includeDirective(lines[i], &name)) {
                text += lines[i] + "\n";
                continue;
            }
            text += "\n";  // the directive's own line, kept so numbering holds
            auto fail = [&](const std::string& problem) {
                out.errors.push_back(
                    {out.files[file], number, 0, "error", "#include \"" + name + "\": " + problem});
            };
            if (!includes) {
                fail("includes are not available here");
                continue;
            }
            if (depth >= kMaxIncludeDepth) {
                fail("includes nest deeper than " + std::to_string(kMaxIncludeDepth) + " levels");
                continue;
            }
            const FileText t = includes(out.files[file], name);
            if (!t.ok) {
                fail(t.error);
                continue;
            }
            if (!seen.insert(t.path).second) continue;  // each file once, like an include guard
            Diagnostic nul;
            if (findNulByte(t.text, name, &nul)) {
                out.errors.push_back(nul);
                out.rejected = true;
                continue;
            }
            const std::size_t index = out.files.size();
            out.files.push_back(name);
            out.texts.push_back(t.text);
            text += lineDirective(1, index);
            append(splitLines(t.text), 0, 1, index, depth + 1, text);
            text += lineDirective(number + 1, file);
        }
    }
};

}  // namespace

std::string defaultPrelude() {
    return "#define SHADERLAB 1\n"
           "#define SL_MAX_LIGHTS 4\n";
}

PreparedSource prepareSource(const std::string& student_text, const std::string& prelude,
                             const std::string& file, const IncludeReader& includes) {
    // A UTF-8 byte-order mark (some Windows editors write one) is not GLSL.
    const bool bom = student_text.compare(0, 3, "\xEF\xBB\xBF") == 0;
    const std::vector<std::string> lines = splitLines(bom ? student_text.substr(3) : student_text);
    const int version_line = findVersionLine(lines);
    PreparedSource out;
    out.files.push_back(file);
    out.texts.push_back(bom ? student_text.substr(3) : student_text);
    Diagnostic nul;
    if (findNulByte(student_text, file, &nul)) {
        out.errors.push_back(nul);
        out.rejected = true;
        return out;
    }
    std::string text;
    int next_student_line = 1;
    // GLSL 3.30 (ES 3.00) and later: "#line N" numbers the next line N. Earlier versions number
    // it N + 1 (GLSL 1.50 section 3.3), so the directive must say one less.
    bool old_line_rule = false;
    if (version_line >= 0) {
        std::string v = lines[static_cast<std::size_t>(version_line)];
        if (v.size() > 200) v.resize(200);
        static const std::regex version_re(R"(#\s*version\s+(\d{1,12})\s*(es)?)");
        std::smatch m;
        if (std::regex_search(v, m, version_re)) {
            const int number = clampedInt(m[1]);
            old_line_rule = m[2].matched ? number < 300 : number < 330;
        }
        for (int i = 0; i <= version_line; ++i) text += lines[static_cast<std::size_t>(i)] + "\n";
        next_student_line = version_line + 2;
    } else {
        text += "#version 330 core\n";
    }
    text += prelude;
    Expander expander{includes, old_line_rule, out, {}};
    text += expander.lineDirective(next_student_line, 0);
    expander.append(lines, static_cast<std::size_t>(next_student_line - 1), next_student_line, 0, 0, text);
    out.text = std::move(text);
    out.first_student_line = next_student_line;
    return out;
}

std::string loopGuardPrelude(int stage) {
    const std::string limit = std::to_string(kLoopGuardLimit);
    const std::string files = std::to_string(kLoopGuardFiles), lines = std::to_string(kLoopGuardLines);
    // One counter per stage, file and line, so that the one atomic the first invocation past the
    // limit adds also says where its loop is: the index is a constant once the call is inlined,
    // and the loop costs what a guard without places cost (a second store in the loop, even one
    // never reached, made llvmpipe's loops half as slow again). The macro takes the place of the
    // call guardLoops() writes: __LINE__ is the loop condition's, numbered as the driver's log
    // numbers it, and shaderlab_loop_file its source string's (guardLoops sets it at every `#line`).
    return "#extension GL_ARB_shader_storage_buffer_object : require\n"
           "layout(std430) buffer ShaderlabLoopGuard { uint shaderlab_loop_overruns[" +
           std::to_string(kLoopGuardWords) +
           "]; };\n"
           "int shaderlab_loop_ticks = 0;\n"
           "bool shaderlab_loop_tick_at(int line, int file) {\n"
           "    shaderlab_loop_ticks += 1;\n"
           "    if (shaderlab_loop_ticks <= " +
           limit +
           ") return true;\n"
           "    if (shaderlab_loop_ticks == " +
           limit + " + 1)\n        atomicAdd(shaderlab_loop_overruns[(" + std::to_string(stage == 0 ? 0 : 1) +
           " * " + files + " + clamp(file, 0, " + files + " - 1)) * " + lines + " + clamp(line, 0, " + lines +
           " - 1)], 1u);\n"
           "    return false;\n"
           "}\n"
           "#define shaderlab_loop_file 0\n"
           "#define shaderlab_loop_tick() shaderlab_loop_tick_at(__LINE__, shaderlab_loop_file)\n";
}

LoopSite ShaderProgram::loopSite(int stage, int file_number, int line) const {
    LoopSite site;
    const int k = stage == 0 ? 0 : 1;
    if (file_number < 0 || line < 1) return site;
    const std::size_t file = static_cast<std::size_t>(file_number);
    if (file >= stage_files_[k].size() || file >= stage_texts_[k].size()) return site;
    const std::vector<std::string> lines = splitLines(stage_texts_[k][file]);
    if (static_cast<std::size_t>(line) > lines.size()) return site;
    site.file = stage_files_[k][file];
    site.line = line;
    site.source_line = lines[static_cast<std::size_t>(line - 1)];
    // The column of the loop's keyword, when the line has exactly one.
    const std::string& text = site.source_line;
    int found = 0;
    for (std::size_t p = 0; p < text.size(); ++p) {
        if (p > 0 && (std::isalnum(static_cast<unsigned char>(text[p - 1])) || text[p - 1] == '_')) continue;
        for (const char* word : {"for", "while"}) {
            const std::size_t n = std::strlen(word);
            if (text.compare(p, n, word) != 0) continue;
            const char after = p + n < text.size() ? text[p + n] : ' ';
            if (std::isalnum(static_cast<unsigned char>(after)) || after == '_') continue;
            site.column = found++ == 0 ? static_cast<int>(p) + 1 : 0;
        }
    }
    if (found > 1) site.column = 0;
    return site;
}

namespace {

bool isIdentifierChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

// Index just past the comment starting at `p` (`p` itself when none starts there).
std::size_t skipComment(const std::string& t, std::size_t p) {
    if (t.compare(p, 2, "//") == 0) {
        const std::size_t end = t.find('\n', p);
        return end == std::string::npos ? t.size() : end;
    }
    if (t.compare(p, 2, "/*") == 0) {
        const std::size_t end = t.find("*/", p + 2);
        return end == std::string::npos ? t.size() : end + 2;
    }
    return p;
}

// From just inside an opening bracket: the index of the `stop` character (or of the closing
// bracket when `stop` is 0) at the same depth, or npos.
std::size_t findAtDepth(const std::string& t, std::size_t p, char stop) {
    int depth = 0;
    while (p < t.size()) {
        const std::size_t after = skipComment(t, p);
        if (after != p) {
            p = after;
            continue;
        }
        const char c = t[p];
        if (c == '(' || c == '[' || c == '{') {
            ++depth;
        } else if (c == ')' || c == ']' || c == '}') {
            if (depth == 0) return stop == 0 && c == ')' ? p : std::string::npos;
            --depth;
        } else if (depth == 0 && stop != 0 && c == stop) {
            return p;
        }
        ++p;
    }
    return std::string::npos;
}

// Mesa's preprocessor gives __FILE__ as 0 inside a macro's expansion whatever `#line` said, so
// the guard's file number comes from a macro of its own, set again before every `#line N F`
// (a directive's own line number is reset by the `#line` after it: numbering is unchanged).
std::string nameLoopFiles(const std::string& text) {
    static const std::regex line_directive(R"(^[ \t]*#[ \t]*line[ \t]+\d+[ \t]+(\d{1,3})[ \t]*$)");
    if (text.find("line") == std::string::npos) return text;
    std::string out;
    out.reserve(text.size() + 1024);
    std::size_t start = 0;
    while (start < text.size()) {
        std::size_t end = text.find('\n', start);
        if (end == std::string::npos) end = text.size();
        const std::string line = text.substr(start, end - start);
        std::smatch m;
        if (line.find("line") != std::string::npos && std::regex_match(line, m, line_directive))
            out += "#undef shaderlab_loop_file\n#define shaderlab_loop_file " + m[1].str() + "\n";
        out.append(text, start, end - start);
        if (end < text.size()) out += '\n';
        start = end + 1;
    }
    return out;
}

}  // namespace

std::string guardLoops(const std::string& prepared) {
    static const std::string tick = "shaderlab_loop_tick()";
    std::string out;
    out.reserve(prepared.size() + 256);
    std::size_t p = 0, copied = 0;
    while (p < prepared.size()) {
        const std::size_t after = skipComment(prepared, p);
        if (after != p) {
            p = after;
            continue;
        }
        if (!isIdentifierChar(prepared[p])) {
            ++p;
            continue;
        }
        std::size_t end = p;
        while (end < prepared.size() && isIdentifierChar(prepared[end])) ++end;
        const std::string word = prepared.substr(p, end - p);
        std::size_t open = end;
        while (open < prepared.size() && std::isspace(static_cast<unsigned char>(prepared[open]))) ++open;
        if ((word != "for" && word != "while") || open >= prepared.size() || prepared[open] != '(') {
            p = end;
            continue;
        }
        std::size_t cond_begin = open + 1, cond_end = std::string::npos;
        if (word == "while") {
            cond_end = findAtDepth(prepared, cond_begin, 0);
        } else {
            const std::size_t first = findAtDepth(prepared, open + 1, ';');
            if (first != std::string::npos) {
                cond_begin = first + 1;
                cond_end = findAtDepth(prepared, cond_begin, ';');
            }
        }
        if (cond_end == std::string::npos) {  // not a loop we understand: the driver will say why
            p = end;
            continue;
        }
        const std::string cond = prepared.substr(cond_begin, cond_end - cond_begin);
        const bool empty = cond.find_first_not_of(" \t\r\n") == std::string::npos;
        out.append(prepared, copied, cond_begin - copied);
        out += empty ? " " + tick + " " : tick + " && (" + cond + ")";
        copied = p = cond_end;
    }
    out.append(prepared, copied, std::string::npos);
    return nameLoopFiles(out);
}

std::vector<Diagnostic> parseInfoLog(const std::string& log, const std::vector<std::string>& files) {
    // Mesa:      0:12(5): error: `x' undeclared
    // NVIDIA:    0(12) : error C1008: undefined variable "x"
    // Others:    ERROR: 0:12: 'x' : undeclared identifier
    static const std::regex mesa(
        R"(^\s*(\d{1,9}):(\d{1,12})\((\d{1,12})\):\s*(?:preprocessor\s+)?(error|warning)\s*:?( *)(.*)$)",
        std::regex::icase);
    static const std::regex nvidia(R"(^\s*(\d{1,9})\((\d{1,12})\)\s*:\s*(error|warning)\s*\w*\s*:?\s*(.*)$)",
                                   std::regex::icase);
    static const std::regex khr(R"(^\s*(ERROR|WARNING)\s*:\s*(\d{1,9}):(\d{1,12})\s*:?\s*(.*)$)",
                                std::regex::icase);
    const std::string fallback = files.empty() ? std::string() : files.front();
    auto fileOf = [&](const std::string& number) {
        const int n = clampedInt(number);
        return n >= 0 && static_cast<std::size_t>(n) < files.size() ? files[static_cast<std::size_t>(n)]
                                                                    : fallback;
    };
    auto lower = [](std::string s) {
        for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        return s;
    };
    std::vector<Diagnostic> out;
    for (const std::string& raw : splitLines(log)) {
        std::string line = raw.size() > kMaxLogLine ? raw.substr(0, kMaxLogLine) + " [...]" : raw;
        while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
        if (line.empty()) continue;
        std::smatch m;
        Diagnostic d;
        d.file = fallback;
        if (std::regex_match(line, m, mesa)) {
            d.file = fileOf(m[1]);
            d.line = clampedInt(m[2]);
            d.column = clampedInt(m[3]);
            d.severity = lower(m[4]);
            d.message = m[6];
            // Mesa lists a call's candidate signatures as indented messages at the call's position.
            const Diagnostic* prev = out.empty() ? nullptr : &out.back();
            if (m[5].length() >= 2 && prev && prev->file == d.file && prev->line == d.line &&
                prev->column == d.column && prev->severity == d.severity) {
                if (out.back().message.size() < kMaxMessage) out.back().message += "\n" + d.message;
                continue;
            }
        } else if (std::regex_match(line, m, nvidia)) {
            d.file = fileOf(m[1]);
            d.line = clampedInt(m[2]);
            d.severity = lower(m[3]);
            d.message = m[4];
        } else if (std::regex_match(line, m, khr)) {
            d.severity = lower(m[1]);
            d.file = fileOf(m[2]);
            d.line = clampedInt(m[3]);
            d.message = m[4];
        } else {
            // A continuation of the previous message, or a line without a position.
            if (!out.empty() && (raw.rfind(' ', 0) == 0 || raw.rfind('\t', 0) == 0)) {
                if (out.back().message.size() < kMaxMessage) out.back().message += "\n" + line;
                continue;
            }
            d.severity = line.find("warning") != std::string::npos ? "warning" : "error";
            d.message = line;
        }
        out.push_back(std::move(d));
    }
    return out;
}

std::vector<Diagnostic> parseInfoLog(const std::string& log, const std::string& file) {
    return parseInfoLog(log, std::vector<std::string>{file});
}

ShaderProgram::~ShaderProgram() { release(); }

ShaderProgram::ShaderProgram(ShaderProgram&& other) noexcept { *this = std::move(other); }

ShaderProgram& ShaderProgram::operator=(ShaderProgram&& other) noexcept {
    if (this != &other) {
        release();
        program_ = other.program_;
        other.program_ = 0;
        loop_guarded_ = other.loop_guarded_;
        compiled_ = other.compiled_;
        linked_ = other.linked_;
        outputs_known_ = other.outputs_known_;
        stages_ = std::move(other.stages_);
        link_log_ = std::move(other.link_log_);
        diagnostics_ = std::move(other.diagnostics_);
        uniform_index_ = std::move(other.uniform_index_);
        uniform_list_ = std::move(other.uniform_list_);
        outputs_ = std::move(other.outputs_);
        for (int k = 0; k < 2; ++k) {
            prepared_[k] = std::move(other.prepared_[k]);
            stage_files_[k] = std::move(other.stage_files_[k]);
            stage_texts_[k] = std::move(other.stage_texts_[k]);
        }
        defaults_ = std::move(other.defaults_);
    }
    return *this;
}

void ShaderProgram::release() {
    if (program_) glDeleteProgram(program_);
    program_ = 0;
}

bool ShaderProgram::build(const std::string& vertex_file, const std::string& vertex_text,
                          const std::string& fragment_file, const std::string& fragment_text) {
    return build(StageSource{vertex_file, vertex_text, {}}, StageSource{fragment_file, fragment_text, {}});
}

// Compiles and links the guarded copy of a program that built; 0 when it does not build.
unsigned ShaderProgram::guardedProgram(const StageSource& vertex, const StageSource& fragment,
                                       const std::vector<std::string>& attachments) const {
    GLuint shaders[2] = {0, 0};
    const StageSource* sources[2] = {&vertex, &fragment};
    bool ok = true;
    for (int k = 0; k < 2 && ok; ++k) {
        const PreparedSource src = prepareSource(sources[k]->text, loopGuardPrelude(k) + defaultPrelude(),
                                                 sources[k]->file, sources[k]->includes);
        const std::string text = guardLoops(src.text);
        shaders[k] = glCreateShader(k == 0 ? GL_VERTEX_SHADER : GL_FRAGMENT_SHADER);
        const char* ptr = text.c_str();
        const GLint length = static_cast<GLint>(text.size());
        glShaderSource(shaders[k], 1, &ptr, &length);
        glCompileShader(shaders[k]);
        GLint compiled = GL_FALSE;
        glGetShaderiv(shaders[k], GL_COMPILE_STATUS, &compiled);
        ok = compiled == GL_TRUE && !src.rejected;
    }
    GLuint program = 0;
    if (ok) {
        program = glCreateProgram();
        for (GLuint sh : shaders) glAttachShader(program, sh);
        glBindAttribLocation(program, 0, "a_position");
        glBindAttribLocation(program, 1, "a_normal");
        glBindAttribLocation(program, 2, "a_texcoord");
        for (std::size_t i = 0; i < attachments.size(); ++i) {
            glBindFragDataLocation(program, static_cast<GLuint>(i), ("o_" + attachments[i]).c_str());
            glBindFragDataLocation(program, static_cast<GLuint>(i), attachments[i].c_str());
        }
        glLinkProgram(program);
        for (GLuint sh : shaders) glDetachShader(program, sh);
        GLint linked = GL_FALSE;
        glGetProgramiv(program, GL_LINK_STATUS, &linked);
        const GLuint block = linked == GL_TRUE ? glGetProgramResourceIndex(program, GL_SHADER_STORAGE_BLOCK,
                                                                           "ShaderlabLoopGuard")
                                               : GL_INVALID_INDEX;
        if (block == GL_INVALID_INDEX) {
            glDeleteProgram(program);
            program = 0;
        } else {
            glShaderStorageBlockBinding(program, block, kLoopGuardBinding);
        }
    }
    for (GLuint sh : shaders)
        if (sh) glDeleteShader(sh);
    return program;
}

namespace {

// One stage of ShaderProgram::build(), compiled, with its log parsed; build() explains it.
struct CompiledStage {
    GLuint shader = 0;  // 0: it did not compile (and the shader is deleted)
    StageLog log;
    std::string prepared;  // the text the driver compiled
    StageText text;
    std::vector<Diagnostic> parsed, include_errors;
    std::size_t dropped = 0;  // messages of `parsed` left out, unexplained
};

// With Mesa's shader cache on (gl_context.h: useShaderCache), a stage Mesa compiled before is not
// compiled again and leaves no log. The log of its first compile is kept beside the cache, named
// by the text compiled, the stage and the driver: the path for `text`, or empty when the cache
// is off.
std::string keptLogPath(GLenum kind, const std::string& text) {
    const std::string dir = shaderCacheDir();
    if (dir.empty()) return {};
    XXH3_state_t* state = XXH3_createState();
    XXH3_128bits_reset(state);
    for (GLenum name : {GLenum(GL_RENDERER), GLenum(GL_VERSION)}) {
        const char* s = reinterpret_cast<const char*>(glGetString(name));
        const std::string v = s ? s : "";
        XXH3_128bits_update(state, v.c_str(), v.size() + 1);
    }
    XXH3_128bits_update(state, &kind, sizeof kind);
    XXH3_128bits_update(state, text.data(), text.size());
    const XXH128_hash_t h = XXH3_128bits_digest(state);
    XXH3_freeState(state);
    char name[40];
    std::snprintf(name, sizeof name, "%016llx%016llx.log", static_cast<unsigned long long>(h.high64),
                  static_cast<unsigned long long>(h.low64));
    return dir + "/shaderlab-logs/" + name;
}

// The log kept for a stage, or the one it just gave kept (once; written whole or not at all).
void keepOrRecallLog(const std::string& path, bool compiled, std::string* info_log) {
    std::error_code ec;
    if (!info_log->empty()) {
        if (std::filesystem::exists(path, ec)) return;
        std::filesystem::create_directories(std::filesystem::path(path).parent_path(), ec);
        std::string error;  // a log that cannot be kept costs the next run its warnings, no more
        grader::writeFileAtomically(path, *info_log, &error);
    } else if (compiled) {
        std::ifstream in(path, std::ios::binary);
        if (!in) return;
        std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        if (text.size() <= kMaxLogBytes) *info_log = text;
    }
}

CompiledStage compileStage(GLenum kind, const StageSource& source) {
    CompiledStage c;
    StageLog& log = c.log;
    log.file = source.file;
    log.stage = kind == GL_VERTEX_SHADER ? "vertex" : "fragment";
    const PreparedSource src = prepareSource(source.text, defaultPrelude(), source.file, source.includes);
    c.prepared = src.text;
    c.text = StageText{log.stage, src.files, src.texts};
    const auto t0 = std::chrono::steady_clock::now();
    const GLuint shader = glCreateShader(kind);
    GLint ok = GL_FALSE;
    if (!src.rejected) {
        const char* ptr = src.text.c_str();
        const GLint length = static_cast<GLint>(src.text.size());
        glShaderSource(shader, 1, &ptr, &length);
        glCompileShader(shader);
        glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    }
    log.compile_us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
    GLint len = 0;
    if (!src.rejected) glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &len);
    if (len > 1) {
        std::string buf(static_cast<std::size_t>(len), '\0');
        glGetShaderInfoLog(shader, len, nullptr, buf.data());
        buf.resize(std::strlen(buf.c_str()));
        // A student can make the driver write megabytes (thousands of errors): the log is cut.
        if (buf.size() > kMaxLogBytes) {
            const std::size_t cut = buf.rfind('\n', kMaxLogBytes);
            buf.resize(cut == std::string::npos ? kMaxLogBytes : cut + 1);
        }
        log.info_log = buf;
    }
    if (!src.rejected) {
        const std::string kept = keptLogPath(kind, src.text);
        if (!kept.empty()) keepOrRecallLog(kept, ok == GL_TRUE, &log.info_log);
    }
    c.include_errors = src.errors;
    log.compiled = ok == GL_TRUE && src.errors.empty();
    c.parsed = parseInfoLog(log.info_log, src.files);
    // Explaining costs time per message (a closest-name search over the file): a flood is cut
    // before, and a note says how much was left out.
    if (c.parsed.size() > kMaxExplained) {
        c.dropped = c.parsed.size() - kMaxExplained;
        c.parsed.resize(kMaxExplained);
    }
    if (!log.compiled) {
        glDeleteShader(shader);
        return c;
    }
    c.shader = shader;
    return c;
}

// The program's active uniforms by name; one in a uniform block is left out (not set by name).
void queryUniforms(GLuint program, std::map<std::string, std::size_t>* index,
                   std::vector<UniformSlot>* list) {
    GLint count = 0;
    glGetProgramiv(program, GL_ACTIVE_UNIFORMS, &count);
    for (GLint i = 0; i < count; ++i) {
        char name[256];
        GLsizei name_len = 0;
        GLint size = 0;
        GLenum type = 0;
        glGetActiveUniform(program, static_cast<GLuint>(i), sizeof name, &name_len, &size, &type, name);
        std::string n(name, static_cast<std::size_t>(name_len));
        UniformSlot slot;
        slot.location = glGetUniformLocation(program, n.c_str());
        slot.type = type;
        slot.size = size;
        if (n.size() > 3 && n.compare(n.size() - 3, 3, "[0]") == 0) n.resize(n.size() - 3);
        slot.name = n;
        if (slot.location < 0) continue;  // in a uniform block: not set by name
        (*index)[n] = list->size();
        list->push_back(slot);
    }
}

// The program's active fragment outputs, gl_* ones left out (needs OpenGL 4.3).
void queryOutputs(GLuint program, std::vector<FragmentOutput>* out) {
    GLint outputs = 0;
    glGetProgramInterfaceiv(program, GL_PROGRAM_OUTPUT, GL_ACTIVE_RESOURCES, &outputs);
    for (GLint i = 0; i < outputs; ++i) {
        char name[256];
        GLsizei name_len = 0;
        glGetProgramResourceName(program, GL_PROGRAM_OUTPUT, static_cast<GLuint>(i), sizeof name, &name_len,
                                 name);
        const GLenum prop = GL_LOCATION;
        GLint location = -1;
        glGetProgramResourceiv(program, GL_PROGRAM_OUTPUT, static_cast<GLuint>(i), 1, &prop, 1, nullptr,
                               &location);
        std::string n(name, static_cast<std::size_t>(name_len));
        if (n.rfind("gl_", 0) == 0) continue;
        if (n.size() > 3 && n.compare(n.size() - 3, 3, "[0]") == 0) n.resize(n.size() - 3);
        out->push_back({n, location});
    }
}

}  // namespace

bool ShaderProgram::build(const StageSource& vertex, const StageSource& fragment,
                          const std::vector<std::string>& attachments, bool guard_loops) {
    release();
    loop_guarded_ = false;
    stages_.clear();
    diagnostics_.clear();
    uniform_index_.clear();
    uniform_list_.clear();
    outputs_.clear();
    defaults_.clear();
    link_log_.clear();
    compiled_ = linked_ = outputs_known_ = false;

    // Each stage's log is explained once both are compiled: a hint may name the other stage.
    CompiledStage stage[2];
    stage[0] = compileStage(GL_VERTEX_SHADER, vertex);
    stage[1] = compileStage(GL_FRAGMENT_SHADER, fragment);
    for (int k = 0; k < 2; ++k) {
        prepared_[k] = stage[k].prepared;
        stage_files_[k] = stage[k].text.files;
        stage_texts_[k] = stage[k].text.texts;
        stages_.push_back(stage[k].log);
    }
    const GLuint vs = stage[0].shader;
    const GLuint fs = stage[1].shader;
    for (int k = 0; k < 2; ++k) {
        for (const Diagnostic& d : stage[k].include_errors) diagnostics_.push_back(d);
        for (Diagnostic& d : explainCompileLog(stage[k].parsed, stage[k].text, &stage[1 - k].text))
            diagnostics_.push_back(std::move(d));
        if (stage[k].dropped > 0)
            diagnostics_.push_back({stage[k].text.files.empty() ? std::string() : stage[k].text.files.front(),
                                    0, 0, "note",
                                    "the compiler reported " + std::to_string(stage[k].dropped) +
                                        " more messages for this file; they are left out (fix the first "
                                        "ones and compile again)"});
        // Our own warnings only for a stage that compiled: its errors come first.
        if (stages_[static_cast<std::size_t>(k)].compiled)
            for (Diagnostic& d : scanStage(stage[k].text)) diagnostics_.push_back(std::move(d));
    }
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
    for (std::size_t i = 0; i < attachments.size(); ++i) {
        glBindFragDataLocation(program_, static_cast<GLuint>(i), ("o_" + attachments[i]).c_str());
        glBindFragDataLocation(program_, static_cast<GLuint>(i), attachments[i].c_str());
    }
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
        // The driver gives no position: each problem is placed at the declaration it is about.
        for (Diagnostic& d : explainLinkLog(link_log_, stage[0].text, stage[1].text))
            diagnostics_.push_back(std::move(d));
    }
    linked_ = ok == GL_TRUE;
    if (!linked_) return false;
    // Drawn with the guarded copy; every query below is of the program that draws.
    if (guard_loops && GLAD_GL_VERSION_4_3) {
        if (const GLuint guarded = guardedProgram(vertex, fragment, attachments)) {
            glDeleteProgram(program_);
            program_ = guarded;
            loop_guarded_ = true;
        }
    }

    queryUniforms(program_, &uniform_index_, &uniform_list_);
    if (GLAD_GL_VERSION_4_3) {
        outputs_known_ = true;
        queryOutputs(program_, &outputs_);
    }
    snapshotDefaults();
    return true;
}

void ShaderProgram::snapshotDefaults() {
    for (const UniformSlot& s : uniform_list_) {
        const GlTypeInfo info = glTypeInfo(s.type);
        if (info.kind == ScalarKind::Sampler || info.kind == ScalarKind::Other ||
            info.kind == ScalarKind::Double)
            continue;
        for (int e = 0; e < s.size; ++e) {
            const std::string element = s.size > 1 ? s.name + "[" + std::to_string(e) + "]" : s.name;
            const GLint location = e == 0 ? s.location : glGetUniformLocation(program_, element.c_str());
            if (location < 0) continue;
            Default d{location, s.type, 1,
                      std::vector<std::uint32_t>(static_cast<std::size_t>(info.components))};
            if (info.kind == ScalarKind::Float)
                glGetUniformfv(program_, location, reinterpret_cast<GLfloat*>(d.bits.data()));
            else if (info.kind == ScalarKind::Uint)
                glGetUniformuiv(program_, location, reinterpret_cast<GLuint*>(d.bits.data()));
            else
                glGetUniformiv(program_, location, reinterpret_cast<GLint*>(d.bits.data()));
            defaults_.push_back(std::move(d));
        }
    }
}

void ShaderProgram::restoreDefaults() const {
    glUseProgram(program_);
    for (const Default& d : defaults_) {
        const GlTypeInfo info = glTypeInfo(d.type);
        const auto* f = reinterpret_cast<const GLfloat*>(d.bits.data());
        const auto* i = reinterpret_cast<const GLint*>(d.bits.data());
        const auto* u = reinterpret_cast<const GLuint*>(d.bits.data());
        switch (d.type) {
            case GL_FLOAT_MAT2:
                glUniformMatrix2fv(d.location, 1, GL_FALSE, f);
                continue;
            case GL_FLOAT_MAT3:
                glUniformMatrix3fv(d.location, 1, GL_FALSE, f);
                continue;
            case GL_FLOAT_MAT4:
                glUniformMatrix4fv(d.location, 1, GL_FALSE, f);
                continue;
            case GL_FLOAT_MAT2x3:
                glUniformMatrix2x3fv(d.location, 1, GL_FALSE, f);
                continue;
            case GL_FLOAT_MAT2x4:
                glUniformMatrix2x4fv(d.location, 1, GL_FALSE, f);
                continue;
            case GL_FLOAT_MAT3x2:
                glUniformMatrix3x2fv(d.location, 1, GL_FALSE, f);
                continue;
            case GL_FLOAT_MAT3x4:
                glUniformMatrix3x4fv(d.location, 1, GL_FALSE, f);
                continue;
            case GL_FLOAT_MAT4x2:
                glUniformMatrix4x2fv(d.location, 1, GL_FALSE, f);
                continue;
            case GL_FLOAT_MAT4x3:
                glUniformMatrix4x3fv(d.location, 1, GL_FALSE, f);
                continue;
            default:
                break;
        }
        const int n = info.components;
        if (info.kind == ScalarKind::Float) {
            if (n == 1) glUniform1fv(d.location, 1, f);
            if (n == 2) glUniform2fv(d.location, 1, f);
            if (n == 3) glUniform3fv(d.location, 1, f);
            if (n == 4) glUniform4fv(d.location, 1, f);
        } else if (info.kind == ScalarKind::Uint) {
            if (n == 1) glUniform1uiv(d.location, 1, u);
            if (n == 2) glUniform2uiv(d.location, 1, u);
            if (n == 3) glUniform3uiv(d.location, 1, u);
            if (n == 4) glUniform4uiv(d.location, 1, u);
        } else {
            if (n == 1) glUniform1iv(d.location, 1, i);
            if (n == 2) glUniform2iv(d.location, 1, i);
            if (n == 3) glUniform3iv(d.location, 1, i);
            if (n == 4) glUniform4iv(d.location, 1, i);
        }
    }
}

const UniformSlot* ShaderProgram::uniform(const std::string& name) const {
    const auto it = uniform_index_.find(name);
    return it == uniform_index_.end() ? nullptr : &uniform_list_[it->second];
}

}  // namespace shaderlab
