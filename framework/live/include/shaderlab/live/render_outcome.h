// What a student is told when a render gives no picture: a title naming the kind of failure (and,
// for a timeout, the scene, pass and shader that ran out of time) and the diagnostics as text.
// The window, the browser workbench and `watch` say the same words.
#pragma once

#include <string>

#include "shaderlab/lab/lab_spec.h"
#include "shaderlab/render/isolated_render.h"

namespace shaderlab::viewer {

struct RenderFailure {
    std::string title;  // "Your shader does not compile", "Timed out: phong.frag (pass 'shade', ...)"
    std::string text;   // each error diagnostic formatted as the report formats it, one per line
};

// The shader that was running when a render timed out, from IsolatedRender::last_event:
// "phong.frag (pass 'shade', with phong.vert)", "a.vert / a.frag" while compiling, else "your shaders".
std::string timeoutCulprit(const LabSpec& spec, const IsolatedRender& r);

// For a render whose status is not Ok.
RenderFailure describeFailure(const LabSpec& spec, const IsolatedRender& r);

}  // namespace shaderlab::viewer
