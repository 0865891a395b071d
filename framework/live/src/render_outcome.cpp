#include "shaderlab/live/render_outcome.h"

#include <sstream>

#include "grader/reports/report.h"
#include "shaderlab/grading/grading.h"

namespace shaderlab::viewer {

std::string timeoutCulprit(const LabSpec& spec, const IsolatedRender& r) {
    std::istringstream in(r.last_event);
    std::string kind, a, b;
    in >> kind >> a >> b;
    if (kind == "compile") return a + " / " + b;
    if (kind == "pass") {
        if (const PassSpec* p = spec.findPass(b))
            return p->program.fragment + " (pass '" + b + "', with " + p->program.vertex + ")";
        return "pass '" + b + "'";
    }
    return "your shaders";
}

// Where the loop guard stopped a render: "phong.frag:29 (pass 'shade')", from the error it left.
std::string loopCulprit(const LabSpec& spec, const IsolatedRender& r) {
    for (const Diagnostic& d : r.render.diagnostics) {
        if (d.severity != "error" || d.message.rfind("endless loop", 0) != 0) continue;
        std::string where = d.file + (d.line > 0 ? ":" + std::to_string(d.line) : "");
        const std::size_t at = d.message.find("in pass '");
        if (at != std::string::npos)
            where += " (" + d.message.substr(at + 3, d.message.find('\'', at + 9) - at - 2) + ")";
        return where;
    }
    return timeoutCulprit(spec, r);
}

RenderFailure describeFailure(const LabSpec& spec, const IsolatedRender& r) {
    RenderFailure f;
    const bool loop = r.status == IsolatedStatus::Timeout && r.limit == "loop";
    switch (r.status) {
        case IsolatedStatus::CompileError:
            f.title = "Your shader does not compile";
            break;
        case IsolatedStatus::LinkError:
            f.title = "Your shaders do not link";
            break;
        case IsolatedStatus::Timeout:
            f.title =
                loop ? "Endless loop: " + loopCulprit(spec, r) : "Timed out: " + timeoutCulprit(spec, r);
            break;
        case IsolatedStatus::Missing:
            f.title = "A file is missing";
            break;
        default:
            f.title = "The render failed (" + std::string(isolatedStatusName(r.status)) + ")";
    }
    const bool build_error =
        r.status == IsolatedStatus::CompileError || r.status == IsolatedStatus::LinkError;
    for (const Diagnostic& d : r.render.diagnostics)
        if (d.severity == "error" || build_error)
            f.text += grader::formatDiagnostic(toReportDiagnostic(d)) + "\n";
    // The loop guard's error says it all; a time-out says which clock ran out.
    if (f.text.empty() || (r.status == IsolatedStatus::Timeout && !loop)) f.text = r.message + "\n" + f.text;
    return f;
}

}  // namespace shaderlab::viewer
