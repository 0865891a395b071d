#include "viewer_grade_lines.h"

#include <cstdio>

#include "grader/base/untrusted_text.h"

namespace shaderlab::viewer::detail {

std::vector<PanelLine> gradeLines(const grader::ReportLab& lab) {
    std::vector<PanelLine> lines;
    if (lab.goals.empty() && lab.status != "passed") {
        std::string note = lab.status + ": " + grader::printableText(lab.message);
        if (lab.status == "compile_error" || lab.status == "link_error") {
            if (!note.empty() && note.back() != '.') note += '.';
            note += " No goal can be judged until your shaders build.";
        }
        lines.push_back({PanelLine::Note, note, ""});
    }
    for (std::size_t i = 0; i < lab.goals.size(); ++i) {
        const grader::ReportGoal& g = lab.goals[i];
        char points[32];
        std::snprintf(points, sizeof points, "%.2f", g.points);
        lines.push_back({g.met ? PanelLine::Met : PanelLine::Missed,
                         std::to_string(i + 1) + ". " + g.title + " (" + points + ")", ""});
        if (!g.met && !g.not_met_because.empty()) {
            // By number: the goals it rests on are listed above it, title and all.
            std::string refs;
            for (std::size_t k = 0; k < g.not_met_because.size(); ++k)
                for (std::size_t j = 0; j < lab.goals.size(); ++j)
                    if (lab.goals[j].id == g.not_met_because[k])
                        refs += std::string(k == 0                              ? ""
                                            : k + 1 == g.not_met_because.size() ? " and "
                                                                                : ", ") +
                                std::to_string(j + 1);
            lines.push_back({PanelLine::Why,
                             g.not_met_because.size() > 1 ? "waits on goals " + refs + ", not met"
                                                          : "waits on goal " + refs + ", not met",
                             ""});
        } else if (!g.met && !g.failing.empty()) {
            std::string where;
            for (const std::string& f : g.failing) where += (where.empty() ? "" : ", ") + f;
            lines.push_back({PanelLine::Why, "not met in " + where, ""});
        }
        std::string judged;
        if (g.judged == "alone")
            judged =
                g.met && !g.whole_failing.empty()
                    ? "your own work for it is right; it fails in your whole shader because of another part"
                    : "judged on your own work for it";
        const std::string with = g.judged == "alone" ? grader::judgedWithText(g) : std::string();
        if (!with.empty()) judged += ", " + with;
        if (!g.judged_note.empty()) judged += (judged.empty() ? "" : "; ") + g.judged_note;
        if (!judged.empty()) lines.push_back({PanelLine::Judged, judged, ""});
    }
    for (const grader::ReportScene& sc : lab.scenes) {
        if (sc.status == "passed") continue;
        lines.push_back({PanelLine::FailingScene, "FAIL scene " + sc.name, sc.name});
        if (!sc.message.empty()) lines.push_back({PanelLine::Why, grader::printableText(sc.message), ""});
        if (!sc.hint.mistake.empty())
            lines.push_back({PanelLine::Hint,
                             "This looks like a known mistake: " + grader::printableText(sc.hint.about), ""});
    }
    return lines;
}

}  // namespace shaderlab::viewer::detail
