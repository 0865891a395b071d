// A program's first draw in strips, stopped at the first strip an endless loop ran in; see
// loop_probe.h.
#include "loop_probe.h"

#include <algorithm>
#include <vector>

#include "uniform_values.h"

namespace shaderlab::render_detail {

bool hasLoop(const ShaderProgram& program) {
    for (int stage : {0, 1})
        for (const char* word : {"for", "while", "do"})
            if (mentionsIdentifier(program.preparedText(stage), word)) return true;
    return false;
}

bool drawProbingLoops(GLuint loop_guard, int width, int height, const std::function<void()>& draw) {
    if (!loop_guard || width <= 0 || height <= 0) {
        draw();
        return true;
    }
    const int rows = std::max(2, (kProbePixels / width) & ~1);
    std::vector<GLuint> counts(kLoopGuardWords, 0);
    glEnable(GL_SCISSOR_TEST);
    bool clean = true;
    for (int y = 0; y < height && clean; y += rows) {
        glScissor(0, y, width, std::min(rows, height - y));
        draw();
        // Reading the counters (one per stage, file and line) waits for the strip to be drawn.
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, loop_guard);
        glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0,
                           static_cast<GLsizeiptr>(counts.size() * sizeof(GLuint)), counts.data());
        clean = std::all_of(counts.begin(), counts.end(), [](GLuint c) { return c == 0; });
    }
    glDisable(GL_SCISSOR_TEST);
    return clean;
}

}  // namespace shaderlab::render_detail
