// Runs renderLab() for untrusted shaders in a child process with wall-clock limits and a memory
// limit, so a shader that loops forever, crashes the driver or eats memory costs one lab's
// result, never the grader. The child creates its own GL context (the parent never holds one,
// so fork() copies no driver threads), runs in its own process group, dies with the parent
// (PR_SET_PDEATHSIG) and hands back images through an anonymous memory file (memfd): nothing
// is written to disk, so nothing is left behind when either process is killed. Linux only.
//
// Every string the child hands back (driver logs, messages, file names) is escaped and capped
// (grader/untrusted_text.h) and at most kMaxDiagnostics diagnostics are kept.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "shaderlab/gl/gl_context.h"
#include "shaderlab/render/renderer.h"

namespace shaderlab {

enum class IsolatedStatus { Ok, Missing, CompileError, LinkError, RenderError, Timeout, Crashed };
const char* isolatedStatusName(IsolatedStatus status);

// The limits of one lab's render (docs/grading.md, "Limits"). The two clocks are separate: a
// shader that takes long to compile (a 20,000-entry constant array) is not a shader that loops
// forever, and the message says which limit ran out.
struct IsolationLimits {
    // Wall clock for drawing: from the first scene to the last image read back.
    double timeout_s = 60.0;
    // Wall clock for everything before: creating the context, reading the files, compiling and
    // linking every program.
    double compile_timeout_s = 30.0;
    // Resident memory of the child, watched by the parent (killed above it). The child's address
    // space is capped too, at this plus kAddressSpaceHeadroom: llvmpipe reserves far more address
    // space than it touches.
    std::size_t memory_bytes = std::size_t(2) << 30;
};
constexpr std::size_t kAddressSpaceHeadroom = std::size_t(4) << 30;
constexpr std::size_t kMaxDiagnostics = 50;

struct IsolatedRender {
    IsolatedStatus status = IsolatedStatus::Ok;
    std::string message;
    LabRender render;        // scenes and diagnostics as the child produced them
    std::string renderer;    // GL_RENDERER and GL_VERSION the child saw
    std::string last_event;  // the last thing the child reported doing (RenderOptions::progress)
    // Which limit stopped the child: "compile_timeout", "draw_timeout", "memory", or "loop" (the
    // loop guard of shader_program.h stopped a loop: status Timeout); empty if none.
    std::string limit;
    double wall_ms = 0.0;
    double compile_ms = 0.0;         // of wall_ms, spent before the first scene
    std::size_t peak_rss_bytes = 0;  // the child's largest resident size the parent saw
};

// A diagnostic as a JSON object, the form it takes between a render child and its parent (here
// and in the viewer's render server).
nlohmann::json diagnosticToJson(const Diagnostic& d);

// `options.progress`, when set, is called in this process with each event the child reports.
// `while_rendering`, when set, is called in this process once the child exists, before its end is
// awaited: work that needs no render (reading the goldens) starts there, on a thread of its own
// if it should overlap the render; no thread may be left running that could fork or that holds a
// lock the next fork's child needs, so join it before the next render.
IsolatedRender renderLabIsolated(const LabSpec& spec, const std::string& shader_dir, Backend backend,
                                 const IsolationLimits& limits, const RenderOptions& options = {},
                                 const std::function<void()>& while_rendering = {});

// One lab of an IsolatedRenderQueue: the lab (which must outlive the queue), the folder of its
// shaders and its options (`progress` is called in this process).
struct IsolatedLabJob {
    const LabSpec* spec = nullptr;
    std::string shader_dir;
    RenderOptions options;
};

// Several labs rendered by one child, one after another: one process start, one GL context and
// one driver start for all of them instead of one each. The child hands each lab back as it
// finishes it and goes on with the next, so the caller judges a lab while the next one is drawn.
//
// Each lab keeps the limits and the verdicts of a lone renderLabIsolated(). Its compile clock
// starts when the child is done with the lab before it, its draw clock at its first scene; a lab
// stopped by a clock is charged with it and the labs after it go to a fresh child. A lab during
// which the child crashes, exits or outgrows the memory limit is charged only if it was the
// child's first; otherwise it is rendered again in a fresh child (what killed the child may be
// what an earlier lab left behind), so its progress events may be told twice. The clocks and the
// memory are watched while next() waits: work done between two calls delays the stop of a
// runaway lab by as long (the address-space limit, IsolationLimits::memory_bytes plus
// kAddressSpaceHeadroom, holds meanwhile), and a lab that finished meanwhile past a clock, by the
// child's own clock, is charged as if it had been stopped there.
class IsolatedRenderQueue {
  public:
    IsolatedRenderQueue(std::vector<IsolatedLabJob> jobs, Backend backend, const IsolationLimits& limits);
    ~IsolatedRenderQueue();  // stops and reaps a child still drawing
    IsolatedRenderQueue(const IsolatedRenderQueue&) = delete;
    IsolatedRenderQueue& operator=(const IsolatedRenderQueue&) = delete;

    // Starts the child for the labs not handed back yet, unless one runs; next() does it when
    // needed. It forks: no other thread of this process may be running.
    void start();

    // The render of the next lab, in the order of the jobs (a RenderError once all are handed
    // back). `while_rendering` as for renderLabIsolated(), except that with more than one lab a
    // lab may be rendered again in a fresh child after it: it must not leave a thread running.
    IsolatedRender next(const std::function<void()>& while_rendering = {});

    std::size_t handedBack() const;       // how many labs next() has returned
    std::size_t childrenStarted() const;  // how many child processes it has started

  private:
    struct State;
    std::unique_ptr<State> state_;
};

}  // namespace shaderlab
