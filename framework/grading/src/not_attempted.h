// A lab handed in as the starter code, untouched: "not attempted", a status of its own (0 points,
// no render, no hint, no known mistake), so that a folder copied from labs/ and never edited is
// not graded as a failed attempt whose picture happens to look like some known mistake.
// Private to framework/grading/src.
#pragma once

#include <string>

#include "shaderlab/lab/lab_spec.h"

namespace shaderlab::grading_detail {

// Whether the student files of lab `spec` in `<submission_dir>/<spec.id>` are the lab's starter
// files unchanged: at least one of them is there, and every one there has a starter file in the
// lab folder with the same text, line endings, trailing spaces and blank lines at the end aside
// (an editor that saved it again changed nothing), and one of them marks work to do with
// TODO(student), as every lab's starter does (lab-check): a starter complete as given (a test
// lab's) is graded like any work. A file found only by its case counts as the
// file (student_files.h). The lab folder itself is never "not attempted": it is the starter, drawn
// so that the lab's author sees it fail. `message` gets what the report says.
bool untouchedStarter(const LabSpec& spec, const std::string& submission_dir, std::string* message);

}  // namespace shaderlab::grading_detail
