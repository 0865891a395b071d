// What the workbench says in words: diagnostics as the page shows them (the lines around each, the
// editor links), the heat map's legend, and the terminal's lines about pictures, failed renders,
// verdicts and grades, in the words `view` and `check` use.
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "grader/metrics/heatmap.h"
#include "shaderlab/grading/grading.h"
#include "workbench_detail.h"

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace shaderlab::serve {

namespace {

std::string fixed(double v, int digits) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", digits, v);
    return buf;
}

// A diagnostic for the terminal: the lines around it, then the command that opens it.
std::string terminalText(const Diagnostic& d, const std::string& folder) {
    const viewer::DiagnosticView v = viewer::viewDiagnostic(d, folder);
    std::string s = viewer::formatWithContext(v);
    const std::string open = viewer::editorCommand(v);
    if (!open.empty()) s += "\n   open it: " + open;
    return s;
}

}  // namespace

json diagnosticJson(const Diagnostic& d, const std::string& lab_folder) {
    const viewer::DiagnosticView v = viewer::viewDiagnostic(d, lab_folder);
    json context = json::array();
    for (const viewer::SourceLine& l : v.context) context.push_back({{"line", l.number}, {"text", l.text}});
    json out = diagnosticToJson(d);
    out.erase("driver_message");  // for instructors: the page shows the words it was explained in
    out["context"] = context;
    out["formatted"] = viewer::formatWithContext(v);
    out["editor_link"] = viewer::editorLink(v);
    out["editor_command"] = viewer::editorCommand(v);
    return out;
}

json diagnosticsJson(const std::vector<Diagnostic>& ds, const std::string& lab_folder, bool errors) {
    json out = json::array();
    for (const Diagnostic& d : ds)
        if ((d.severity == "error") == errors) out.push_back(diagnosticJson(d, lab_folder));
    return out;
}

json heatmapLegendJson() {
    const grader::HeatmapConfig config;
    json stops = json::array();
    for (int i = 0; i <= 16; ++i) {
        float rgb[3];
        grader::colormapLookup(config.colormap, static_cast<float>(i) / 16.0f, rgb);
        stops.push_back(
            {std::lround(rgb[0] * 255.0f), std::lround(rgb[1] * 255.0f), std::lround(rgb[2] * 255.0f)});
    }
    auto colour = [](const float* c) {
        return json::array(
            {std::lround(c[0] * 255.0f), std::lround(c[1] * 255.0f), std::lround(c[2] * 255.0f)});
    };
    return {{"name", "FLIP error"},
            {"min", 0.0},
            {"max", config.max_error},
            {"stops", stops},
            {"outline", colour(config.outline_color)},
            {"nan", colour(config.nan_color)}};
}

std::string Workbench::Impl::labFolder() const {
    return (fs::path(opt.submission_root) / opt.spec.id).string();
}

void Workbench::Impl::sayPicture(const Snapshot& snap, const IsolatedRender& r) {
    std::string line = "scene " + snap.scene + " rendered in " + fixed(r.wall_ms, 0) + " ms";
    if (snap.latency_ms >= 0) line += "; ready " + fixed(snap.latency_ms, 0) + " ms after the save";
    std::string message = line;
    // Warnings are printed when they change, not with every picture.
    std::string warnings;
    for (const Diagnostic& d : r.render.diagnostics)
        if (d.severity == "warning") warnings += terminalText(d, labFolder()) + "\n";
    if (warnings != warnings_said) {
        if (!warnings.empty())
            message += "\n" + warnings.substr(0, warnings.size() - 1);
        else if (!warnings_said.empty())
            message += "\nno more warnings";
        warnings_said = warnings;
    }
    say(message);
}

void Workbench::Impl::sayFailure(const RenderFailureInfo& info, const IsolatedRender& r) {
    std::string message = info.title;
    bool any = false;
    for (const Diagnostic& d : r.render.diagnostics)
        if (d.severity == "error") {
            message += "\n" + terminalText(d, labFolder());
            any = true;
        }
    if (!any && !info.text.empty())
        message += "\n" + info.text.substr(0, info.text.find_last_not_of('\n') + 1);
    say(message);
}

// In the graded view only, as `view` says it: the scene, and the reasons of each failing image.
void Workbench::Impl::sayVerdict(const Snapshot& snap) {
    if (snap.orbit.any() || snap.debug != DebugView::Off) return;
    std::vector<std::shared_ptr<const Judgement>> judged;
    {
        std::lock_guard<std::mutex> lock(snap.m);
        judged = snap.judged;
    }
    bool any = false, passed = true;
    std::string reasons;
    for (std::size_t i = 0; i < judged.size() && i < snap.images.size(); ++i) {
        if (!judged[i] || !snap.images[i].student->graded) continue;
        any = true;
        passed = passed && judged[i]->verdict.passed;
        const PassImage& p = *snap.images[i].student;
        for (const std::string& reason : judged[i]->verdict.reasons)
            reasons += "\n  " + p.pass + "." + p.attachment + ": " + reason;
    }
    if (any) say("scene " + snap.scene + (passed ? " passes" : " FAILS" + reasons));
}

void Workbench::Impl::sayGrade(const grader::ReportLab& lab) const {
    std::string missed;
    for (const grader::ReportGoal& g : lab.goals)
        if (!g.met) missed += (missed.empty() ? "" : ", ") + g.id;
    std::string message = "grade " + fixed(lab.score, 2) + " / " + fixed(lab.max_score, 2) + "; " +
                          (lab.goals.empty() ? lab.status
                           : missed.empty()  ? std::string("every goal met")
                                             : "goals not met: " + missed);
    for (const grader::ReportScene& s : lab.scenes)
        if (s.status != "passed" && !s.hint.mistake.empty())
            message += "\nscene " + s.name + ": This looks like a known mistake: " + s.hint.about;
    say(message);
}

}  // namespace shaderlab::serve
