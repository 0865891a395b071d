// The lines of the window's grade panel, from the lab's grade as `check` gives it: every goal,
// met or missed, why one is missed (the checks where it fails, or the goals it waits on by
// number), how it was judged, each failing scene with its message and known-mistake hint. Kept
// apart from the drawing (viewer_panels.cpp) so that its words are tested without a window.
// Private to the viewer.
#pragma once

#include <string>
#include <vector>

#include "grader/reports/report.h"

namespace shaderlab::viewer::detail {

// One line of the grade panel, as drawn and as --panel-text writes it.
struct PanelLine {
    enum Kind { Met, Missed, Why, Judged, FailingScene, Hint, Note } kind = Note;
    std::string text;
    std::string scene;  // FailingScene: picking it shows this scene
};

std::vector<PanelLine> gradeLines(const grader::ReportLab& lab);

}  // namespace shaderlab::viewer::detail
