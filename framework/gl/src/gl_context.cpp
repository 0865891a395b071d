// Headless context backends: OSMesa (Mesa's off-screen library, llvmpipe) and EGL on the
// surfaceless platform (EGL_MESA_platform_surfaceless; also the road to a GPU). Both create a
// core-profile context of the newest version offered, then load GL through glad.
//
// Both libraries are opened with dlopen() when a context is first asked for, not linked: OSMesa
// needs libLLVM, whose relocation alone made every `shaderlab compare` (which never draws) take
// 20 ms to start. A missing library is an ordinary context error naming it.
#include "shaderlab/gl/gl_context.h"

// glad's header must come before any other GL header.
// clang-format off
#include "shaderlab/gl/gl.h"
#include <EGL/egl.h>
#include <EGL/eglext.h>
// clang-format on

#include <dlfcn.h>
#include <link.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <vector>

#include "osmesa_api.h"
#include "shaderlab/base/sanitizer.h"
#include "shaderlab/base/timings.h"

namespace shaderlab {

namespace {

// Resolves `name` from `lib` into `*fn`; false (and `missing` names it) when absent.
template <typename Fn>
bool resolve(void* lib, const char* name, Fn* fn, std::string* missing) {
    *fn = reinterpret_cast<Fn>(dlsym(lib, name));
    if (!*fn && missing->empty()) *missing = name;
    return *fn != nullptr;
}

// The OSMesa entry points this file uses, from libOSMesa opened on first use.
struct OSMesaApi {
    osmesa::CreateContextAttribsFn CreateContextAttribs = nullptr;
    osmesa::CreateContextExtFn CreateContextExt = nullptr;
    osmesa::MakeCurrentFn MakeCurrent = nullptr;
    osmesa::DestroyContextFn DestroyContext = nullptr;
    osmesa::GetProcAddressFn GetProcAddress = nullptr;
    std::string error;  // why the library is unusable; empty when it loaded

    static const OSMesaApi& get() {
        static const OSMesaApi api = load();
        return api;
    }

  private:
    static OSMesaApi load() {
        OSMesaApi a;
        // SHADERLAB_OSMESA_LIBRARY names another library file (a Mesa built with OSMesa elsewhere).
        const char* chosen = std::getenv("SHADERLAB_OSMESA_LIBRARY");
        const std::string name = chosen && *chosen ? chosen : "libOSMesa.so.8";
        void* lib = dlopen(name.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!lib && !(chosen && *chosen)) lib = dlopen("libOSMesa.so", RTLD_NOW | RTLD_LOCAL);
        if (!lib) {
            const char* why = dlerror();
            a.error =
                "osmesa: cannot open " + name + " (" + (why ? why : "not found") +
                "); is libosmesa6 installed? (an address-space limit too small to map it also stops it)";
            return a;
        }
        std::string missing;
        resolve(lib, "OSMesaCreateContextAttribs", &a.CreateContextAttribs, &missing);
        resolve(lib, "OSMesaCreateContextExt", &a.CreateContextExt, &missing);
        resolve(lib, "OSMesaMakeCurrent", &a.MakeCurrent, &missing);
        resolve(lib, "OSMesaDestroyContext", &a.DestroyContext, &missing);
        resolve(lib, "OSMesaGetProcAddress", &a.GetProcAddress, &missing);
        if (!missing.empty()) a.error = "osmesa: " + name + " lacks " + missing;
        return a;
    }
};

// The EGL entry points this file uses, from libEGL opened on first use.
struct EglApi {
    decltype(&::eglQueryString) QueryString = nullptr;
    decltype(&::eglGetProcAddress) GetProcAddress = nullptr;
    decltype(&::eglInitialize) Initialize = nullptr;
    decltype(&::eglTerminate) Terminate = nullptr;
    decltype(&::eglBindAPI) BindAPI = nullptr;
    decltype(&::eglChooseConfig) ChooseConfig = nullptr;
    decltype(&::eglCreateContext) CreateContext = nullptr;
    decltype(&::eglDestroyContext) DestroyContext = nullptr;
    decltype(&::eglMakeCurrent) MakeCurrent = nullptr;
    decltype(&::eglGetError) GetError = nullptr;
    std::string error;

    static const EglApi& get() {
        static const EglApi api = load();
        return api;
    }

  private:
    static EglApi load() {
        EglApi a;
        void* lib = dlopen("libEGL.so.1", RTLD_NOW | RTLD_LOCAL);
        if (!lib) {
            const char* why = dlerror();
            a.error = std::string("egl: cannot open libEGL.so.1 (") + (why ? why : "not found") +
                      "); are libegl1 and libegl-mesa0 installed? (an address-space limit too small to map "
                      "them also stops it)";
            return a;
        }
        std::string missing;
        resolve(lib, "eglQueryString", &a.QueryString, &missing);
        resolve(lib, "eglGetProcAddress", &a.GetProcAddress, &missing);
        resolve(lib, "eglInitialize", &a.Initialize, &missing);
        resolve(lib, "eglTerminate", &a.Terminate, &missing);
        resolve(lib, "eglBindAPI", &a.BindAPI, &missing);
        resolve(lib, "eglChooseConfig", &a.ChooseConfig, &missing);
        resolve(lib, "eglCreateContext", &a.CreateContext, &missing);
        resolve(lib, "eglDestroyContext", &a.DestroyContext, &missing);
        resolve(lib, "eglMakeCurrent", &a.MakeCurrent, &missing);
        resolve(lib, "eglGetError", &a.GetError, &missing);
        if (!missing.empty()) a.error = "egl: libEGL.so.1 lacks " + missing;
        return a;
    }
};

#if SHADERLAB_ASAN
// LeakSanitizer reports at exit, after libEGL_mesa (or GLFW's libGL) has closed the DRI driver
// it loaded (swrast_dri.so) at eglTerminate, glfwTerminate or in a destructor. A leak allocated
// inside that driver then has only "<unknown module>" frames (the driver has no frame pointers,
// so ASan's fast unwinder stops after one frame), and tests/asan/lsan.supp, which suppresses the
// driver's leaks by library name, cannot match it. So every library loaded by now is marked
// RTLD_NODELETE (with RTLD_NOLOAD: only those already there): it stays mapped until exit and LSan
// names it; a leak of ours is still reported. Slow unwinding (ASAN_OPTIONS
// fast_unwind_on_malloc=0) also reaches a named frame, in libEGL_mesa, but slows every malloc;
// suppressing "<unknown module>" would hide our own leaks in any library that was unloaded.
void keepLoadedLibrariesMapped() {
    std::vector<std::string> paths;  // collected first: no dlopen under dl_iterate_phdr's lock
    dl_iterate_phdr(
        [](dl_phdr_info* info, std::size_t, void* out) {
            if (info->dlpi_name && info->dlpi_name[0] == '/')
                static_cast<std::vector<std::string>*>(out)->push_back(info->dlpi_name);
            return 0;
        },
        &paths);
    for (const std::string& path : paths) dlopen(path.c_str(), RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE);
}
#endif

constexpr int kMinMajor = 3, kMinMinor = 3;

std::string versionString(int major, int minor) {
    return std::to_string(major) + "." + std::to_string(minor);
}

class OSMesaContextImpl final : public GlContext {
  public:
    ~OSMesaContextImpl() override {
        if (ctx_) osmesa.DestroyContext(ctx_);
    }
    const char* backend() const override { return "osmesa"; }
    bool makeCurrent() override {
        return osmesa.MakeCurrent(ctx_, pixel_, GL_UNSIGNED_BYTE, 1, 1) &&
               gladLoadGL(reinterpret_cast<GLADloadfunc>(osmesa.GetProcAddress));
    }

    bool create(std::string* error) {
        if (!osmesa.error.empty()) {
            *error = osmesa.error;
            return false;
        }
        // Ask for the highest core versions first: OSMesa returns a context of at least the
        // requested version, and fails when it cannot.
        const int wanted[][2] = {{4, 5}, {4, 3}, {4, 1}, {3, 3}};
        for (const auto& v : wanted) {
            const int attribs[] = {osmesa::kFormat,
                                   osmesa::kRgba,
                                   osmesa::kDepthBits,
                                   24,
                                   osmesa::kStencilBits,
                                   8,
                                   osmesa::kProfile,
                                   osmesa::kCoreProfile,
                                   osmesa::kContextMajorVersion,
                                   v[0],
                                   osmesa::kContextMinorVersion,
                                   v[1],
                                   0};
            ctx_ = osmesa.CreateContextAttribs(attribs, nullptr);
            if (ctx_) break;
        }
        if (!ctx_) {
            // Learn which version the library can give, to say so.
            osmesa::Context legacy = osmesa.CreateContextExt(osmesa::kRgba, 24, 8, 0, nullptr);
            std::string found = "none";
            if (legacy && osmesa.MakeCurrent(legacy, pixel_, GL_UNSIGNED_BYTE, 1, 1)) {
                auto get_string =
                    reinterpret_cast<const GLubyte* (*)(GLenum)>(osmesa.GetProcAddress("glGetString"));
                if (get_string && get_string(GL_VERSION))
                    found = reinterpret_cast<const char*>(get_string(GL_VERSION));
            }
            if (legacy) osmesa.DestroyContext(legacy);
            *error = "osmesa: cannot create an OpenGL " + versionString(kMinMajor, kMinMinor) +
                     " core context; the library offers " + found;
            return false;
        }
        // The 1x1 buffer only satisfies MakeCurrent; every pass renders into an FBO.
        if (!osmesa.MakeCurrent(ctx_, pixel_, GL_UNSIGNED_BYTE, 1, 1)) {
            *error = "osmesa: OSMesaMakeCurrent failed";
            return false;
        }
        return loadGl(reinterpret_cast<GetProcFn>(osmesa.GetProcAddress), &info_, error);
    }

  private:
    const OSMesaApi& osmesa = OSMesaApi::get();
    osmesa::Context ctx_ = nullptr;
    unsigned char pixel_[4] = {};
};

class EglContextImpl final : public GlContext {
  public:
    ~EglContextImpl() override {
        if (display_ != EGL_NO_DISPLAY) {
            egl.MakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            if (ctx_ != EGL_NO_CONTEXT) egl.DestroyContext(display_, ctx_);
            egl.Terminate(display_);
        }
    }
    const char* backend() const override { return "egl"; }
    bool makeCurrent() override {
        return egl.MakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx_) &&
               gladLoadGL(reinterpret_cast<GLADloadfunc>(egl.GetProcAddress));
    }

    bool create(std::string* error) {
        if (!egl.error.empty()) {
            *error = egl.error;
            return false;
        }
        const char* client_ext = egl.QueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
        if (!client_ext || !std::strstr(client_ext, "EGL_MESA_platform_surfaceless")) {
            *error = "egl: the EGL library lacks EGL_MESA_platform_surfaceless (client extensions: " +
                     std::string(client_ext ? client_ext : "none") + ")";
            return false;
        }
        auto get_platform_display =
            reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(egl.GetProcAddress("eglGetPlatformDisplayEXT"));
        if (!get_platform_display) {
            *error = "egl: eglGetPlatformDisplayEXT not available";
            return false;
        }
        display_ = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        EGLint major = 0, minor = 0;
        if (display_ == EGL_NO_DISPLAY || !egl.Initialize(display_, &major, &minor)) {
            *error = "egl: cannot initialise the surfaceless display (error 0x" + hex(egl.GetError()) + ")";
            return false;
        }
        if (!egl.BindAPI(EGL_OPENGL_API)) {
            *error = "egl: the display does not offer desktop OpenGL";
            return false;
        }
        const EGLint config_attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE,
                                         EGL_PBUFFER_BIT, EGL_NONE};
        EGLConfig config = nullptr;
        EGLint count = 0;
        // Surfaceless contexts need no config; when the display lists one we use it anyway so
        // that drivers insisting on a config are served.
        if (!egl.ChooseConfig(display_, config_attribs, &config, 1, &count) || count == 0) config = nullptr;
        const int wanted[][2] = {{4, 5}, {4, 3}, {4, 1}, {3, 3}};
        for (const auto& v : wanted) {
            const EGLint ctx_attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                          v[0],
                                          EGL_CONTEXT_MINOR_VERSION,
                                          v[1],
                                          EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                          EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                          EGL_NONE};
            ctx_ =
                egl.CreateContext(display_, config ? config : EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, ctx_attribs);
            if (ctx_ != EGL_NO_CONTEXT) break;
        }
        if (ctx_ == EGL_NO_CONTEXT) {
            *error = "egl: cannot create an OpenGL " + versionString(kMinMajor, kMinMinor) +
                     " core context (EGL " + versionString(major, minor) + ", error 0x" +
                     hex(egl.GetError()) + ")";
            return false;
        }
        if (!egl.MakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx_)) {
            *error = "egl: eglMakeCurrent without a surface failed (error 0x" + hex(egl.GetError()) + ")";
            return false;
        }
        return loadGl(reinterpret_cast<GetProcFn>(egl.GetProcAddress), &info_, error);
    }

  private:
    static std::string hex(EGLint v) {
        char buf[16];
        std::snprintf(buf, sizeof buf, "%04x", static_cast<unsigned>(v));
        return buf;
    }
    const EglApi& egl = EglApi::get();
    EGLDisplay display_ = EGL_NO_DISPLAY;
    EGLContext ctx_ = EGL_NO_CONTEXT;
};

}  // namespace

bool parseBackend(const std::string& name, Backend* out, std::string* note) {
    if (name == "auto") {
        // Opening libOSMesa here, in the process that forks the render children, costs them
        // nothing: they inherit it mapped instead of opening it themselves.
        const std::string& why = OSMesaApi::get().error;
        *out = why.empty() ? Backend::OSMesa : Backend::Egl;
        if (note) *note = why.empty() ? "" : why + "; rendering with EGL (surfaceless) instead";
        return true;
    }
    if (note) note->clear();
    if (name == "osmesa") {
        *out = Backend::OSMesa;
        return true;
    }
    if (name == "egl") {
        *out = Backend::Egl;
        return true;
    }
    return false;
}

const char* backendName(Backend backend) { return backend == Backend::OSMesa ? "osmesa" : "egl"; }

bool loadGl(GetProcFn get_proc, GlInfo* info, std::string* error) {
#if SHADERLAB_ASAN
    // Every context (headless or the viewer's window) is current by now: its driver is loaded.
    keepLoadedLibrariesMapped();
#endif
    // gladLoadGL parses GL_VERSION itself and returns it; 0 means not even glGetString works.
    const int version = gladLoadGL(reinterpret_cast<GLADloadfunc>(get_proc));
    if (!version || !glad_glGetString) {
        *error = "cannot load OpenGL entry points (no usable glGetString)";
        return false;
    }
    auto str = [](GLenum e) {
        const GLubyte* s = glGetString(e);
        return s ? std::string(reinterpret_cast<const char*>(s)) : std::string();
    };
    info->vendor = str(GL_VENDOR);
    info->renderer = str(GL_RENDERER);
    info->version = str(GL_VERSION);
    info->major = GLAD_VERSION_MAJOR(version);
    info->minor = GLAD_VERSION_MINOR(version);
    if (info->major < kMinMajor || (info->major == kMinMajor && info->minor < kMinMinor)) {
        *error = "OpenGL " + versionString(kMinMajor, kMinMinor) + " core is required, found " +
                 info->version + " (" + info->renderer + ")";
        return false;
    }
    return true;
}

void useShaderCache(const std::string& dir) {
    // Mesa makes only the last folder of the path, and turns its cache off for good when it
    // cannot: the whole path is made here.
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    setenv("MESA_SHADER_CACHE_DIR", dir.c_str(), 1);
    setenv("MESA_SHADER_CACHE_DISABLE", "false", 1);
    // Each edit of a student's file adds an entry; Mesa drops the oldest beyond this size.
    setenv("MESA_SHADER_CACHE_MAX_SIZE", "256M", 0);
}

std::string shaderCacheDir() {
    const char* off = std::getenv("MESA_SHADER_CACHE_DISABLE");
    const char* dir = std::getenv("MESA_SHADER_CACHE_DIR");
    if (!off || std::strcmp(off, "false") != 0 || !dir || !*dir) return {};
    return dir;
}

ContextResult createHeadlessContext(Backend backend) {
    // A cached shader compiles silently: "`v' used uninitialized" or a varying never written
    // would show once and never again. Feedback must not depend on what ran before; the cost
    // is recompiling (about 0.2 s per lab on llvmpipe). Read when the driver loads.
    setenv("MESA_SHADER_CACHE_DISABLE", "true", 0);
    ScopedTiming timing("context", "", backendName(backend));
    ContextResult result;
    if (backend == Backend::OSMesa) {
        auto ctx = std::make_unique<OSMesaContextImpl>();
        if (ctx->create(&result.error)) result.context = std::move(ctx);
    } else {
        auto ctx = std::make_unique<EglContextImpl>();
        if (ctx->create(&result.error)) result.context = std::move(ctx);
    }
    return result;
}

}  // namespace shaderlab
