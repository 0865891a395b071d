// A current OpenGL context, whatever made it. Headless backends (OSMesa, EGL surfaceless) live
// here; a window host (GLFW) implements the same interface in its own glue, so the renderer
// never knows which one it runs on. A context does not own a default framebuffer worth drawing
// to: every pass renders into framebuffer objects.
#pragma once

#include <memory>
#include <string>

namespace shaderlab {

enum class Backend { OSMesa, Egl };

// "osmesa", "egl" or "auto" (what --backend takes). "auto" is OSMesa where libOSMesa can be opened
// and EGL (surfaceless) where it cannot (Mesa 25.1 and later ship no OSMesa); then `note`, when
// given, says why in one line for the user, and is empty otherwise.
bool parseBackend(const std::string& name, Backend* out, std::string* note = nullptr);
const char* backendName(Backend backend);

struct GlInfo {
    int major = 0, minor = 0;
    std::string vendor, renderer, version;
};

class GlContext {
  public:
    virtual ~GlContext() = default;
    virtual const char* backend() const = 0;
    // Makes this context current on the calling thread and points the GL loader at it again
    // (entry points may differ between backends living in one process).
    virtual bool makeCurrent() = 0;
    const GlInfo& info() const { return info_; }

  protected:
    GlInfo info_;
};

struct ContextResult {
    std::unique_ptr<GlContext> context;  // current on this thread when set
    std::string error;
};

// Creates a headless OpenGL core context of at least 3.3, makes it current and loads the GL
// entry points. A context that is too old is an error naming the version found. Turns Mesa's
// on-disk shader cache off for the process (MESA_SHADER_CACHE_DISABLE, unless already set):
// Mesa skips compiling a shader it has cached and then reports none of its warnings.
ContextResult createHeadlessContext(Backend backend);

// Turns Mesa's on-disk shader cache on for this process and the render children it starts, in
// `dir` (a folder of the run's own: never the user's home), before any context exists. llvmpipe
// then keeps the machine code it compiles for a program, so the next run that draws the same
// shader (the lab's own passes in every grade, a student's unchanged file in the next check)
// skips the compile. Mesa also skips the GLSL compile then and reports no warnings: the render
// keeps each stage's log beside the cache (shaderCacheDir(), shader_program.cpp) and reports the
// kept one, so feedback stays the same from run to run.
void useShaderCache(const std::string& dir);

// The folder useShaderCache() chose for this process (inherited by a render child through its
// environment); empty when the cache is off.
std::string shaderCacheDir();

// Loads GL entry points through `get_proc` into the loader and checks the version (>= 3.3
// core); for window hosts, whose toolkit supplies get_proc (glfwGetProcAddress has this shape).
using GlProc = void (*)();
using GetProcFn = GlProc (*)(const char*);
bool loadGl(GetProcFn get_proc, GlInfo* info, std::string* error);

}  // namespace shaderlab
