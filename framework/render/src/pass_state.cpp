// A pass's GL state (lab.json's render state): depth test and write, culling, polygon mode, line
// and point size, sRGB writes and blending, set in full each time a pass draws into a face of its
// target, so nothing of the pass before carries over; and the pass's clears. Which framebuffer is
// bound, and the per-draw winding and culling of mirrored or double-sided meshes, are the
// caller's (pass_draw.cpp).
#include <glm/gtc/type_ptr.hpp>

#include "lab_runner.h"

namespace shaderlab::render_detail {

namespace {

GLenum glDepthFuncOf(DepthFunc f) {
    switch (f) {
        case DepthFunc::Never:
            return GL_NEVER;
        case DepthFunc::Equal:
            return GL_EQUAL;
        case DepthFunc::LessEqual:
            return GL_LEQUAL;
        case DepthFunc::Greater:
            return GL_GREATER;
        case DepthFunc::NotEqual:
            return GL_NOTEQUAL;
        case DepthFunc::GreaterEqual:
            return GL_GEQUAL;
        case DepthFunc::Always:
            return GL_ALWAYS;
        default:
            return GL_LESS;
    }
}

}  // namespace

void applyState(const RenderState& s, bool srgb_target, bool program_point_size) {
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDisable(GL_SCISSOR_TEST);
    if (s.depth_test) {
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(glDepthFuncOf(s.depth_func));
    } else {
        glDisable(GL_DEPTH_TEST);
    }
    glDepthMask(s.depth_write ? GL_TRUE : GL_FALSE);
    if (s.cull == CullMode::None) {
        glDisable(GL_CULL_FACE);
    } else {
        glEnable(GL_CULL_FACE);
        glCullFace(s.cull == CullMode::Back ? GL_BACK : GL_FRONT);
    }
    glFrontFace(GL_CCW);
    glPolygonMode(GL_FRONT_AND_BACK, s.polygon_mode == PolygonMode::Line    ? GL_LINE
                                     : s.polygon_mode == PolygonMode::Point ? GL_POINT
                                                                            : GL_FILL);
    glLineWidth(s.line_width);
    glPointSize(s.point_size);
    if (program_point_size)
        glEnable(GL_PROGRAM_POINT_SIZE);
    else
        glDisable(GL_PROGRAM_POINT_SIZE);
    if (srgb_target)
        glEnable(GL_FRAMEBUFFER_SRGB);
    else
        glDisable(GL_FRAMEBUFFER_SRGB);
    switch (s.blend) {
        case BlendMode::None:
            glDisable(GL_BLEND);
            break;
        case BlendMode::Alpha:
            glEnable(GL_BLEND);
            glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
            break;
        case BlendMode::Premultiplied:
            glEnable(GL_BLEND);
            glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
            break;
        case BlendMode::Additive:
            glEnable(GL_BLEND);
            glBlendFunc(GL_ONE, GL_ONE);
            break;
    }
}

void clearTarget(const RenderState& s, bool has_depth) {
    for (std::size_t i = 0; i < s.clear_colors.size(); ++i) {
        if (!s.clear_colors[i]) continue;
        glClearBufferfv(GL_COLOR, static_cast<GLint>(i), glm::value_ptr(*s.clear_colors[i]));
    }
    if (s.clear_depth && has_depth) {
        glDepthMask(GL_TRUE);  // a disabled depth mask would also mask the clear
        const GLfloat one = 1.0f;
        glClearBufferfv(GL_DEPTH, 0, &one);
        glDepthMask(s.depth_write ? GL_TRUE : GL_FALSE);
    }
}

}  // namespace shaderlab::render_detail
