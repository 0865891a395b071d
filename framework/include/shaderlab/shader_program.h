// Compiles and links the student's GLSL, keeping compile and link logs as structured data.
// The framework injects a small prelude after the student's `#version` line (or a default
// `#version 330 core` when there is none) followed by a `#line` directive, so the driver's line
// numbers are the student's own; diagnostics carry the student's file name, not the driver's
// source-string number. This file does not decide what a failure is worth: the grader does.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "shaderlab/lab_spec.h"

namespace shaderlab {

struct Diagnostic {
    std::string file;      // the student's file as named in lab.json, e.g. "phong.frag"
    int line = 0;          // 1-based, in the student's file; 0 when the driver gave none
    int column = 0;        // 0 when unknown
    std::string severity;  // "error" or "warning"
    std::string message;
};

// GLSL text as handed to the driver, and where the student's first line landed.
struct PreparedSource {
    std::string text;
    int first_student_line = 1;
};

// Inserts the prelude after the `#version` directive (keeping the student's version) and a
// `#line` so that line numbers in the driver's log match the student's file.
PreparedSource prepareSource(const std::string& student_text, const std::string& prelude);

// Parses a driver info log (Mesa "0:12(5): error: ...", NVIDIA "0(12) : error C1008: ...",
// "ERROR: 0:12: ...") into diagnostics attributed to `file`. Lines it cannot parse become
// diagnostics with line 0 so nothing the driver said is lost.
std::vector<Diagnostic> parseInfoLog(const std::string& log, const std::string& file);

struct StageLog {
    std::string file;
    std::string stage;  // "vertex" | "fragment"
    bool compiled = false;
    std::string info_log;
    double compile_us = 0.0;
};

struct UniformSlot {
    int location = -1;
    unsigned type = 0;  // GL type enum
    int size = 1;       // array length
};

class ShaderProgram {
  public:
    ShaderProgram() = default;
    ~ShaderProgram();
    ShaderProgram(const ShaderProgram&) = delete;
    ShaderProgram& operator=(const ShaderProgram&) = delete;
    ShaderProgram(ShaderProgram&& other) noexcept;
    ShaderProgram& operator=(ShaderProgram&& other) noexcept;

    // Builds from two prepared sources. Returns false on a compile or link error; logs and
    // diagnostics are filled either way (warnings too).
    bool build(const std::string& vertex_file, const std::string& vertex_text,
               const std::string& fragment_file, const std::string& fragment_text);

    bool compiled() const { return compiled_; }
    bool linked() const { return linked_; }
    unsigned id() const { return program_; }
    const std::vector<StageLog>& stages() const { return stages_; }
    const std::string& linkLog() const { return link_log_; }
    const std::vector<Diagnostic>& diagnostics() const { return diagnostics_; }

    // Active uniforms by name, without the "[0]" GL adds to arrays.
    const UniformSlot* uniform(const std::string& name) const;
    // Sets a lab.json value; returns a message when the shader declares another type.
    std::string set(const std::string& name, const UniformValue& value) const;

  private:
    void release();
    unsigned program_ = 0;
    bool compiled_ = false, linked_ = false;
    std::vector<StageLog> stages_;
    std::string link_log_;
    std::vector<Diagnostic> diagnostics_;
    std::map<std::string, UniformSlot> uniforms_;
};

// The default prelude: defines a submission may test for.
std::string defaultPrelude();

}  // namespace shaderlab
