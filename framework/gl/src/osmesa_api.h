// The few OSMesa declarations the OSMesa backend needs, written out so that building shaderlab
// needs no OSMesa header: Mesa removed OSMesa in 25.1, and Mesa 25.0's GL/osmesa.h no longer
// compiles after glad's header (it expects GLAPI and APIENTRY, which only GL/gl.h defines). The
// library itself is opened with dlopen() when an OSMesa context is asked for (gl_context.cpp), so
// a system without it builds and runs on EGL. Values and signatures are those of Mesa's
// include/GL/osmesa.h (OSMesa 11.2, unchanged since Mesa 10.x); on Linux GLAPIENTRY is empty.
#pragma once

#include "shaderlab/gl/gl.h"

namespace shaderlab::osmesa {

using Context = struct osmesa_context*;  // OSMesaContext
using Proc = void (*)();                 // OSMESAproc

using CreateContextAttribsFn = Context (*)(const int* attrib_list, Context share_list);
using CreateContextExtFn = Context (*)(GLenum format, GLint depth_bits, GLint stencil_bits, GLint accum_bits,
                                       Context share_list);
using MakeCurrentFn = GLboolean (*)(Context ctx, void* buffer, GLenum type, GLsizei width, GLsizei height);
using DestroyContextFn = void (*)(Context ctx);
using GetProcAddressFn = Proc (*)(const char* name);

constexpr int kRgba = GL_RGBA;  // OSMESA_RGBA
constexpr int kFormat = 0x22;   // OSMESA_FORMAT
constexpr int kDepthBits = 0x30;
constexpr int kStencilBits = 0x31;
constexpr int kProfile = 0x33;
constexpr int kCoreProfile = 0x34;
constexpr int kContextMajorVersion = 0x36;
constexpr int kContextMinorVersion = 0x37;

}  // namespace shaderlab::osmesa
