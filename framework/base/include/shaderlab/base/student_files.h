// A student's file read as the student knows it: found without regard to case when the name the
// lab asks for is not there (a student on Windows or macOS never sees that `Phong.frag` is not
// `phong.frag`; the grader on Linux does), and every problem said with the name the student uses,
// never the folder the submission was unpacked into.
//
// It reads through resolveInside() (paths.h), so a file found by its case still has to lie inside
// the root. It does not decide what a lab's student files are (lab.json does).
#pragma once

#include <cstddef>
#include <string>

#include "shaderlab/base/paths.h"

namespace shaderlab {

// The path below `root` that matches `relative` but for the case of its letters (ASCII), each
// part matched against the entries of its folder, when exactly one such path exists and it is not
// `relative` itself; "" otherwise (no such entry, or several that differ only in case).
std::string findIgnoringCase(const std::string& root, const std::string& relative);

// "found Phong.frag; the lab expects phong.frag": what the report says of a file found by its case.
std::string caseNote(const std::string& found, const std::string& expected);
// Whether a message is such a note (a report's warning), for summaries that list them.
bool isCaseNote(const std::string& message);

// Reads `relative` inside `root` as readFileInside() does. When it is not there, the one file that
// differs from it only in case is read instead and `case_note` (optional) gets caseNote(). Errors
// name the file as `shown` (what the student calls it, e.g. "phong.frag"), not by its absolute
// path, and a file that resolves outside is said to leave "the submission", not where that is; a
// missing file's error lists, briefly, what its folder holds.
FileText readStudentFile(const std::string& root, const std::string& relative, const std::string& shown,
                         std::size_t max_bytes, std::string* case_note = nullptr);

}  // namespace shaderlab
