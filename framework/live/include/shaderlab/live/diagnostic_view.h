// A compile or link message as the window, the page and their terminals show it: the diagnostic,
// a few lines of the student's file around its line, and where to open that line in an editor.
// The lines are read from the student's lab folder when the message is shown, and kept only when
// the file still holds, at that line, the text the message quotes (a file saved again since is
// shown by the next render, not mixed into this one). Only regular files inside the lab folder
// are read (a symlink that leaves it is not followed), at most 1 MiB. No GL, no HTTP here.
#pragma once

#include <string>
#include <vector>

#include "shaderlab/feedback/diagnostic.h"

namespace shaderlab::viewer {

struct SourceLine {
    int number = 0;  // 1-based
    std::string text;
};

struct DiagnosticView {
    Diagnostic diagnostic;
    std::vector<SourceLine> context;  // lines around diagnostic.line, that line included; may be empty
    std::string path;                 // the file, absolute, when it is one of the lab folder's
};

// `around` lines before and after the diagnostic's line, as far as the file has them.
DiagnosticView viewDiagnostic(const Diagnostic& d, const std::string& lab_folder, int around = 2);

// As grader::formatDiagnostic writes it (file:line: severity: message, the line, the caret, the
// explanation), with the lines around it under their numbers:
//    27 |     vec3 l = normalize(u_light_dir);
//    28 |     vec3 n = normalize(v_world_normal)
//       |                                       ^
//    29 |     float d = max(dot(n, l), 0.0);
//       = explanation
std::string formatWithContext(const DiagnosticView& v);

// The line a terminal prints to open the place: `$EDITOR +29 /path/phong.frag` (vi when EDITOR is
// unset; the path quoted for a POSIX shell when it needs it); empty without a file.
std::string editorCommand(const DiagnosticView& v);

// A link that opens the place in VS Code: vscode://file/PATH:LINE:COLUMN (percent-encoded);
// empty without a file.
std::string editorLink(const DiagnosticView& v);

}  // namespace shaderlab::viewer
