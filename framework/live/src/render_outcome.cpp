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

RenderFailure describeFailure(const LabSpec& spec, const IsolatedRender& r) {
    RenderFailure f;
    switch (r.status) {
        case IsolatedStatus::CompileError:
            f.title = "Your shader does not compile";
            break;
        case IsolatedStatus::LinkError:
            f.title = "Your shaders do not link";
            break;
        case IsolatedStatus::Timeout:
            f.title = "Timed out: " + timeoutCulprit(spec, r);
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
    if (f.text.empty() || r.status == IsolatedStatus::Timeout) f.text = r.message + "\n" + f.text;
    return f;
}

}  // namespace shaderlab::viewer
