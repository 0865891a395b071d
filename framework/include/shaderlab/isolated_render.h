// Runs renderLab() for untrusted shaders in a child process with a wall-clock limit and an
// address-space limit, so a shader that loops forever, crashes the driver or eats memory costs
// one lab's result, never the grader. The child creates its own GL context (the parent never
// holds one, so fork() copies no driver threads) and hands back images through files in a
// private temporary folder. POSIX only.
#pragma once

#include <string>

#include "shaderlab/gl_context.h"
#include "shaderlab/renderer.h"

namespace shaderlab {

enum class IsolatedStatus { Ok, Missing, CompileError, LinkError, RenderError, Timeout, Crashed };
const char* isolatedStatusName(IsolatedStatus status);

struct IsolationLimits {
    double timeout_s = 60.0;                          // wall clock for the whole lab
    std::size_t memory_bytes = std::size_t(6) << 30;  // RLIMIT_AS of the child (llvmpipe reserves a lot)
};

struct IsolatedRender {
    IsolatedStatus status = IsolatedStatus::Ok;
    std::string message;
    LabRender render;        // scenes and diagnostics as the child produced them
    std::string renderer;    // GL_RENDERER and GL_VERSION the child saw
    std::string last_event;  // the last thing the child reported doing (RenderOptions::progress)
    double wall_ms = 0.0;
};

// `options.progress`, when set, is called in this process with each event the child reports.
IsolatedRender renderLabIsolated(const LabSpec& spec, const std::string& shader_dir, Backend backend,
                                 const IsolationLimits& limits, const RenderOptions& options = {});

}  // namespace shaderlab
