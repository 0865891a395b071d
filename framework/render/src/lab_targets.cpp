// The lab runner's targets (lab_runner.h): their textures, depth and framebuffers, sized and
// formatted as lab.json declares; the copy that lets a pass read the target it draws into
// (ping-pong); blanking them before each scene; and reading their attachments back into images.
// Which state a pass draws with is pass_state.cpp's.
#include <algorithm>
#include <cstdio>
#include <glm/gtc/type_ptr.hpp>

#include "lab_runner.h"
#include "shaderlab/base/timings.h"

namespace shaderlab::render_detail {

GLenum targetInternalFormat(TargetFormat f) {
    switch (f) {
        case TargetFormat::RGBA8:
            return GL_RGBA8;
        case TargetFormat::SRGB8:
            return GL_SRGB8_ALPHA8;
        case TargetFormat::RGBA16F:
            return GL_RGBA16F;
        default:
            return GL_RGBA32F;
    }
}

namespace {

bool createTarget(TargetGl* t, std::string* error) {
    const TargetSpec& s = *t->spec;
    glActiveTexture(GL_TEXTURE0 + kScratchTextureUnit);
    const GLenum format = targetInternalFormat(s.format);
    const GLenum tex_target = t->textureTarget();
    for (int b = 0; b < t->buffers; ++b) {
        t->color[b].resize(s.attachments.size());
        glGenTextures(static_cast<GLsizei>(s.attachments.size()), t->color[b].data());
        for (GLuint tex : t->color[b]) {
            glBindTexture(tex_target, tex);
            for (int f = 0; f < t->faces(); ++f) {
                const GLenum image =
                    t->cube() ? GL_TEXTURE_CUBE_MAP_POSITIVE_X + static_cast<GLenum>(f) : GL_TEXTURE_2D;
                glTexImage2D(image, 0, static_cast<GLint>(format), s.width, s.height, 0, GL_RGBA, GL_FLOAT,
                             nullptr);
            }
            if (t->mipmapped) glGenerateMipmap(tex_target);
        }
    }
    if (t->depth == DepthMode::Texture) {
        glGenTextures(1, &t->depth_texture);
        glBindTexture(GL_TEXTURE_2D, t->depth_texture);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT32F, s.width, s.height, 0, GL_DEPTH_COMPONENT,
                     GL_FLOAT, nullptr);
    } else if (t->depth == DepthMode::Buffer) {
        glGenRenderbuffers(1, &t->depth_renderbuffer);
        glBindRenderbuffer(GL_RENDERBUFFER, t->depth_renderbuffer);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, s.width, s.height);
    }
    glBindTexture(tex_target, 0);
    glActiveTexture(GL_TEXTURE0);
    std::vector<GLenum> draw_buffers;
    for (std::size_t i = 0; i < s.attachments.size(); ++i)
        draw_buffers.push_back(GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i));
    for (int b = 0; b < t->buffers; ++b) {
        for (int f = 0; f < t->faces(); ++f) {
            GLuint fbo = 0;
            glGenFramebuffers(1, &fbo);
            t->fbos[{b, f}] = fbo;
            glBindFramebuffer(GL_FRAMEBUFFER, fbo);
            const GLenum image =
                t->cube() ? GL_TEXTURE_CUBE_MAP_POSITIVE_X + static_cast<GLenum>(f) : GL_TEXTURE_2D;
            for (std::size_t i = 0; i < s.attachments.size(); ++i)
                glFramebufferTexture2D(GL_FRAMEBUFFER, draw_buffers[i], image, t->color[b][i], 0);
            if (t->depth_texture)
                glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, t->depth_texture,
                                       0);
            if (t->depth_renderbuffer)
                glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER,
                                          t->depth_renderbuffer);
            glDrawBuffers(static_cast<GLsizei>(draw_buffers.size()), draw_buffers.data());
            const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
            if (status != GL_FRAMEBUFFER_COMPLETE) {
                char buf[32];
                std::snprintf(buf, sizeof buf, "0x%04X", status);
                *error = "target '" + s.name + "' is incomplete on this driver (status " + buf + ")";
                return false;
            }
        }
    }
    return true;
}

// Reads one attachment ("depth" included) of the front set into a top-row-first image; a cube
// target's faces side by side.
grader::Image readAttachment(const TargetGl& t, const std::string& attachment) {
    const TargetSpec& s = *t.spec;
    const int w = s.width, h = s.height, faces = t.faces();
    grader::Image img(w * faces, h, 4);
    std::vector<float> buf(static_cast<std::size_t>(w) * h * 4);
    const bool depth = attachment == "depth";
    const auto at = std::find(s.attachments.begin(), s.attachments.end(), attachment);
    const GLenum read_buffer = GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(at - s.attachments.begin());
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    for (int f = 0; f < faces; ++f) {
        glBindFramebuffer(GL_READ_FRAMEBUFFER, t.fbos.at({t.front, f}));
        if (depth) {
            std::vector<float> d(static_cast<std::size_t>(w) * h);
            glReadPixels(0, 0, w, h, GL_DEPTH_COMPONENT, GL_FLOAT, d.data());
            for (std::size_t i = 0; i < d.size(); ++i) {
                buf[i * 4 + 0] = buf[i * 4 + 1] = buf[i * 4 + 2] = d[i];
                buf[i * 4 + 3] = 1.0f;
            }
        } else {
            glReadBuffer(read_buffer);
            glReadPixels(0, 0, w, h, GL_RGBA, GL_FLOAT, buf.data());
        }
        // GL's first row is the bottom one. Cube faces keep GL's row order, as face images are
        // stored (their first row is t = 0).
        for (int y = 0; y < h; ++y) {
            const int src_y = t.cube() ? y : h - 1 - y;
            std::copy_n(buf.data() + static_cast<std::size_t>(src_y) * w * 4, static_cast<std::size_t>(w) * 4,
                        img.pixels.data() +
                            (static_cast<std::size_t>(y) * w * faces + static_cast<std::size_t>(f) * w) * 4);
        }
    }
    return img;
}

std::vector<std::uint8_t> readCoverage(const TargetGl& t) {
    const TargetSpec& s = *t.spec;
    const std::size_t n = static_cast<std::size_t>(s.width) * t.faces() * s.height;
    std::vector<std::uint8_t> coverage(n, 1);
    if (t.fullscreen_drawn || t.depth == DepthMode::None || t.cube()) return coverage;
    const int w = s.width, h = s.height;
    std::vector<float> depth(static_cast<std::size_t>(w) * h);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, t.fbos.at({t.front, 0}));
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, w, h, GL_DEPTH_COMPONENT, GL_FLOAT, depth.data());
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            coverage[static_cast<std::size_t>(y) * w + x] =
                depth[static_cast<std::size_t>(h - 1 - y) * w + x] < 1.0f;
    return coverage;
}

}  // namespace

bool LabRunner::createTargets() {
    std::set<std::string> self_read, mipmapped;
    for (const PassSpec& pass : spec_.passes) {
        for (const PassInput& in : pass.inputs) {
            if (in.source != InputSource::Target) continue;
            if (in.target == pass.target && in.attachment != "depth") self_read.insert(in.target);
            const TargetSpec* t = spec_.findTarget(in.target);
            if (in.filter.value_or(t ? t->filter : TextureFilter::Linear) == TextureFilter::Mipmap)
                mipmapped.insert(in.target);
        }
    }
    // A depth buffer (not a depth texture, which later passes read) is allocated only when a
    // pass drawing into the target tests or writes depth, or grades it: a target that only
    // full-screen passes draw (post-processing, unless its lab.json says "depth": "none") would
    // otherwise be cleared and carried for nothing.
    std::set<std::string> depth_used;
    for (const PassSpec& pass : spec_.passes) {
        const bool grades_depth =
            std::find(pass.graded.begin(), pass.graded.end(), "depth") != pass.graded.end();
        if (pass.state.depth_test || pass.state.depth_write || grades_depth) depth_used.insert(pass.target);
    }
    for (const TargetSpec& spec : spec_.targets) {
        auto t = std::make_unique<TargetGl>();
        t->spec = &spec;
        t->depth =
            spec.depth == DepthMode::Buffer && !depth_used.count(spec.name) ? DepthMode::None : spec.depth;
        t->buffers = self_read.count(spec.name) ? 2 : 1;
        t->mipmapped = mipmapped.count(spec.name) > 0;
        std::string err;
        if (!createTarget(t.get(), &err)) return fail(RenderStatus::RenderError, err);
        targets_[spec.name] = std::move(t);
    }
    fullscreen_ = fullscreenTriangle();
    glGenVertexArrays(1, &empty_vao_);
    return true;
}

void LabRunner::copyFrontToBack(TargetGl& t) {
    const int back = 1 - t.front;
    for (int f = 0; f < t.faces(); ++f) {
        glBindFramebuffer(GL_READ_FRAMEBUFFER, t.fbos.at({t.front, f}));
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, t.fbos.at({back, f}));
        for (std::size_t i = 0; i < t.spec->attachments.size(); ++i) {
            const GLenum a = GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i);
            glReadBuffer(a);
            glDrawBuffers(1, &a);
            glBlitFramebuffer(0, 0, t.spec->width, t.spec->height, 0, 0, t.spec->width, t.spec->height,
                              GL_COLOR_BUFFER_BIT, GL_NEAREST);
        }
        std::vector<GLenum> all;
        for (std::size_t i = 0; i < t.spec->attachments.size(); ++i)
            all.push_back(GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i));
        glDrawBuffers(static_cast<GLsizei>(all.size()), all.data());
    }
}

// Every target starts each scene blank, so nothing of the previous scene survives in a pass
// that draws without clearing.
void LabRunner::blankTargets() {
    for (auto& [name, t] : targets_) {
        t->front = 0;
        t->fullscreen_drawn = false;
        for (const auto& [key, fbo] : t->fbos) {
            glBindFramebuffer(GL_FRAMEBUFFER, fbo);
            glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
            glDepthMask(GL_TRUE);
            glDisable(GL_FRAMEBUFFER_SRGB);
            const GLfloat zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
            for (std::size_t i = 0; i < t->spec->attachments.size(); ++i)
                glClearBufferfv(GL_COLOR, static_cast<GLint>(i), zero);
            if (t->depth != DepthMode::None) {
                const GLfloat one = 1.0f;
                glClearBufferfv(GL_DEPTH, 0, &one);
            }
        }
    }
}

// After the last run of a pass: its graded attachments (every attachment, and depth, with
// keep_all_passes) as images of the scene.
void LabRunner::readBack(const PassRun& run) {
    const PassSpec& pass = run.pass;
    const TargetGl& target = run.target;
    const TargetSpec& tspec = *target.spec;
    const SceneContext& ctx = run.ctx;
    std::vector<std::string> read = pass.graded;
    if (options_.keep_all_passes) {
        read = tspec.attachments;
        if (target.depth != DepthMode::None && !target.cube()) read.push_back("depth");
    }
    if (read.empty()) return;
    ScopedTiming timing("readback", spec_.id, ctx.spec->name);
    const std::vector<std::uint8_t> coverage = readCoverage(target);
    for (const std::string& attachment : read) {
        PassImage img;
        img.pass = pass.name;
        img.target = tspec.name;
        img.attachment = attachment;
        img.graded = std::find(pass.graded.begin(), pass.graded.end(), attachment) != pass.graded.end();
        img.color = readAttachment(target, attachment);
        img.coverage = coverage;
        ctx.out->passes.push_back(std::move(img));
    }
}

}  // namespace shaderlab::render_detail
