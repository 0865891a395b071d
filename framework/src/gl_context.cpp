// Headless context backends: OSMesa (Mesa's off-screen library, llvmpipe) and EGL on the
// surfaceless platform (EGL_MESA_platform_surfaceless; also the road to a GPU). Both create a
// core-profile context of the newest version offered, then load GL through glad.
#include "shaderlab/gl_context.h"

// glad's header must come before any other GL header (osmesa.h pulls in GL/gl.h).
// clang-format off
#include "shaderlab/gl.h"
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/osmesa.h>
// clang-format on

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

namespace shaderlab {

namespace {

constexpr int kMinMajor = 3, kMinMinor = 3;

std::string versionString(int major, int minor) {
    return std::to_string(major) + "." + std::to_string(minor);
}

class OSMesaContextImpl final : public GlContext {
  public:
    ~OSMesaContextImpl() override {
        if (ctx_) OSMesaDestroyContext(ctx_);
    }
    const char* backend() const override { return "osmesa"; }
    bool makeCurrent() override {
        return OSMesaMakeCurrent(ctx_, pixel_, GL_UNSIGNED_BYTE, 1, 1) &&
               gladLoadGL(reinterpret_cast<GLADloadfunc>(&OSMesaGetProcAddress));
    }

    bool create(std::string* error) {
        // Ask for the highest core versions first: OSMesa returns a context of at least the
        // requested version, and fails when it cannot.
        const int wanted[][2] = {{4, 5}, {4, 3}, {4, 1}, {3, 3}};
        for (const auto& v : wanted) {
            const int attribs[] = {OSMESA_FORMAT,
                                   OSMESA_RGBA,
                                   OSMESA_DEPTH_BITS,
                                   24,
                                   OSMESA_STENCIL_BITS,
                                   8,
                                   OSMESA_PROFILE,
                                   OSMESA_CORE_PROFILE,
                                   OSMESA_CONTEXT_MAJOR_VERSION,
                                   v[0],
                                   OSMESA_CONTEXT_MINOR_VERSION,
                                   v[1],
                                   0};
            ctx_ = OSMesaCreateContextAttribs(attribs, nullptr);
            if (ctx_) break;
        }
        if (!ctx_) {
            // Learn which version the library can give, to say so.
            OSMesaContext legacy = OSMesaCreateContextExt(OSMESA_RGBA, 24, 8, 0, nullptr);
            std::string found = "none";
            if (legacy && OSMesaMakeCurrent(legacy, pixel_, GL_UNSIGNED_BYTE, 1, 1)) {
                auto get_string =
                    reinterpret_cast<const GLubyte* (*)(GLenum)>(OSMesaGetProcAddress("glGetString"));
                if (get_string && get_string(GL_VERSION))
                    found = reinterpret_cast<const char*>(get_string(GL_VERSION));
            }
            if (legacy) OSMesaDestroyContext(legacy);
            *error = "osmesa: cannot create an OpenGL " + versionString(kMinMajor, kMinMinor) +
                     " core context; the library offers " + found;
            return false;
        }
        // The 1x1 buffer only satisfies MakeCurrent; every pass renders into an FBO.
        if (!OSMesaMakeCurrent(ctx_, pixel_, GL_UNSIGNED_BYTE, 1, 1)) {
            *error = "osmesa: OSMesaMakeCurrent failed";
            return false;
        }
        return loadGl(reinterpret_cast<GetProcFn>(&OSMesaGetProcAddress), &info_, error);
    }

  private:
    OSMesaContext ctx_ = nullptr;
    unsigned char pixel_[4] = {};
};

class EglContextImpl final : public GlContext {
  public:
    ~EglContextImpl() override {
        if (display_ != EGL_NO_DISPLAY) {
            eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            if (ctx_ != EGL_NO_CONTEXT) eglDestroyContext(display_, ctx_);
            eglTerminate(display_);
        }
    }
    const char* backend() const override { return "egl"; }
    bool makeCurrent() override {
        return eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx_) &&
               gladLoadGL(reinterpret_cast<GLADloadfunc>(&eglGetProcAddress));
    }

    bool create(std::string* error) {
        const char* client_ext = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
        if (!client_ext || !std::strstr(client_ext, "EGL_MESA_platform_surfaceless")) {
            *error = "egl: the EGL library lacks EGL_MESA_platform_surfaceless (client extensions: " +
                     std::string(client_ext ? client_ext : "none") + ")";
            return false;
        }
        auto get_platform_display =
            reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
        if (!get_platform_display) {
            *error = "egl: eglGetPlatformDisplayEXT not available";
            return false;
        }
        display_ = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        EGLint major = 0, minor = 0;
        if (display_ == EGL_NO_DISPLAY || !eglInitialize(display_, &major, &minor)) {
            *error = "egl: cannot initialise the surfaceless display (error 0x" + hex(eglGetError()) + ")";
            return false;
        }
        if (!eglBindAPI(EGL_OPENGL_API)) {
            *error = "egl: the display does not offer desktop OpenGL";
            return false;
        }
        const EGLint config_attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE,
                                         EGL_PBUFFER_BIT, EGL_NONE};
        EGLConfig config = nullptr;
        EGLint count = 0;
        // Surfaceless contexts need no config; when the display lists one we use it anyway so
        // that drivers insisting on a config are served.
        if (!eglChooseConfig(display_, config_attribs, &config, 1, &count) || count == 0) config = nullptr;
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
                eglCreateContext(display_, config ? config : EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, ctx_attribs);
            if (ctx_ != EGL_NO_CONTEXT) break;
        }
        if (ctx_ == EGL_NO_CONTEXT) {
            *error = "egl: cannot create an OpenGL " + versionString(kMinMajor, kMinMinor) +
                     " core context (EGL " + versionString(major, minor) + ", error 0x" + hex(eglGetError()) +
                     ")";
            return false;
        }
        if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx_)) {
            *error = "egl: eglMakeCurrent without a surface failed (error 0x" + hex(eglGetError()) + ")";
            return false;
        }
        return loadGl(reinterpret_cast<GetProcFn>(&eglGetProcAddress), &info_, error);
    }

  private:
    static std::string hex(EGLint v) {
        char buf[16];
        std::snprintf(buf, sizeof buf, "%04x", static_cast<unsigned>(v));
        return buf;
    }
    EGLDisplay display_ = EGL_NO_DISPLAY;
    EGLContext ctx_ = EGL_NO_CONTEXT;
};

}  // namespace

bool parseBackend(const std::string& name, Backend* out) {
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

ContextResult createHeadlessContext(Backend backend) {
    // A cached shader compiles silently: "`v' used uninitialized" or a varying never written
    // would show once and never again. Feedback must not depend on what ran before; the cost
    // is recompiling (about 0.2 s per lab on llvmpipe). Read when the driver loads.
    setenv("MESA_SHADER_CACHE_DISABLE", "true", 0);
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
