// A program's first draw in horizontal strips, the loop guard read after each: an endless loop is
// then stopped after one strip of pixels has run it to the guard's limit, not the whole picture.
//
// Why: the guard (shader_program.h) ends a loop per invocation, so an endless loop costs every
// pixel kLoopGuardLimit iterations of its body. A light loop without its `++i` costs 23,750
// pixels of a lit sphere 46 s on llvmpipe (two cores); a strip of at most kProbePixels pixels
// costs a few seconds at most. The strips give the same picture as one draw: each pixel is drawn in
// exactly one of them, by the same primitives in the same order, and strips are an even number of
// rows high, so no 2x2 quad (and no derivative) is split. Only the first draw of each program is
// cut so (LabRunner::drawFaces): the vertex work it repeats per strip is paid once per program and
// lab. Private to the render library.
#pragma once

#include <functional>

#include "shaderlab/gl/gl.h"
#include "shaderlab/render/shader_program.h"

namespace shaderlab::render_detail {

// Pixels per strip, at most (the strip is at least two rows high).
constexpr int kProbePixels = 2048;

// Whether either stage's text holds a `for`, `while` or `do` (a comment that says one counts too:
// the probe then costs a little for nothing).
bool hasLoop(const ShaderProgram& program);

// Runs `draw` (every draw call of one face of a pass, its target bound and cleared) once per strip
// of a `width` x `height` target, with the scissor test on that strip, until a strip leaves a
// count in the loop guard's storage buffer `loop_guard` (0: no guard; `draw` runs once, whole).
// The scissor test is off again afterwards. Returns false when a loop ran past the guard: the
// strips below that one are not drawn, and the pass's guard check (checkLoopGuard) says so.
bool drawProbingLoops(GLuint loop_guard, int width, int height, const std::function<void()>& draw);

}  // namespace shaderlab::render_detail
