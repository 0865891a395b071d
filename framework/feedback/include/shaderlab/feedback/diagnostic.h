// One message about a student's GLSL: where it is (file, line, column), how bad (error or
// warning), and what it means in plain words. Made by the shader program from the driver's logs
// and by the explanations of glsl_explain.h; carried into reports. No OpenGL here.
#pragma once

#include <string>

namespace shaderlab {

struct Diagnostic {
    std::string file;      // the student's file as named in lab.json, e.g. "phong.frag"
    int line = 0;          // 1-based, in that file; 0 when the driver gave none
    int column = 0;        // 1-based character of `source_line`; 0 when unknown or not trustworthy
    std::string severity;  // "error" or "warning"
    std::string message;   // in plain words: no parser jargon
    // Defaulted so that {file, line, column, severity, message} still initialises the rest.
    std::string explanation{};     // what usually causes it and how to fix it; may be empty
    std::string source_line{};     // line `line` of `file` as written (tabs kept); may be empty
    std::string driver_message{};  // the driver's own words, for instructors; empty for our own
    int follow_on = 0;             // later errors of the stage dropped as probable consequences
};

}  // namespace shaderlab
