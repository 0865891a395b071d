// Diagnostics as the text a person reads, one layout for the terminal and every report writer;
// see report.h. No colour and no wrapping: callers add what their medium needs.
#include "grader/reports/report.h"

namespace grader {

std::string formatDiagnostic(const ReportDiagnostic& d, const std::string& prefix,
                             const std::string& indent) {
    std::string s = indent + prefix + d.file;
    if (d.line > 0) s += ":" + std::to_string(d.line);
    s += ": " + d.severity + ": " + d.message;
    const std::string number = d.line > 0 ? std::to_string(d.line) : "";
    const std::string gutter = indent + " " + std::string(number.size(), ' ') + " ";
    if (!d.source_line.empty()) {
        s += "\n" + indent + " " + number + " | " + d.source_line;
        if (d.column > 0 && static_cast<std::size_t>(d.column) <= d.source_line.size() + 1) {
            // Tabs copied so the caret lines up whatever the tab width; one space per character.
            std::string pad;
            for (std::size_t i = 0; i + 1 < static_cast<std::size_t>(d.column); ++i) {
                const unsigned char c = static_cast<unsigned char>(d.source_line[i]);
                if ((c & 0xC0) == 0x80) continue;
                pad += c == '\t' ? '\t' : ' ';
            }
            s += "\n" + gutter + "| " + pad + "^";
        }
    }
    std::string note = d.explanation;
    if (d.follow_on > 0)
        note += std::string(note.empty() ? "" : " ") + "(" + std::to_string(d.follow_on) + " more " +
                (d.follow_on == 1 ? "error" : "errors") + " after this one, probably caused by it)";
    if (!note.empty()) s += "\n" + gutter + "= " + note;
    return s;
}

}  // namespace grader
