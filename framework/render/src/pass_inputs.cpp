// The textures a pass samples (lab_runner.h): each sampler its program declares on a unit of its
// own, fed from a target (colour or depth, the front copy when ping-ponged), an input texture made
// on first use (input_textures.h), or nothing; and the sampler objects that filter and wrap them.
// Material textures are material_textures.h's, bound per draw.
#include "gl_types.h"
#include "lab_runner.h"
#include "shaderlab/base/json_messages.h"

namespace shaderlab::render_detail {

namespace {

constexpr int kMaxTextureUnits = 16;

GLint glFilterMin(TextureFilter f) {
    return f == TextureFilter::Nearest  ? GL_NEAREST
           : f == TextureFilter::Mipmap ? GL_LINEAR_MIPMAP_LINEAR
                                        : GL_LINEAR;
}

GLint glWrap(TextureWrap w) {
    switch (w) {
        case TextureWrap::Repeat:
            return GL_REPEAT;
        case TextureWrap::MirroredRepeat:
            return GL_MIRRORED_REPEAT;
        default:
            return GL_CLAMP_TO_EDGE;
    }
}

}  // namespace

GLuint LabRunner::sampler(TextureFilter filter, TextureWrap wrap, bool shadow) {
    const auto key = std::make_tuple(static_cast<int>(filter), static_cast<int>(wrap), shadow);
    auto it = samplers_.find(key);
    if (it != samplers_.end()) return it->second;
    GLuint s = 0;
    glGenSamplers(1, &s);
    glSamplerParameteri(s, GL_TEXTURE_MIN_FILTER, glFilterMin(filter));
    glSamplerParameteri(s, GL_TEXTURE_MAG_FILTER, filter == TextureFilter::Nearest ? GL_NEAREST : GL_LINEAR);
    for (GLenum p : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
        glSamplerParameteri(s, p, glWrap(wrap));
    if (shadow) {
        glSamplerParameteri(s, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
        glSamplerParameteri(s, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    }
    samplers_[key] = s;
    return s;
}

// Every sampler the program declares gets its own unit, so samplers of different types never
// share one (a GL_INVALID_OPERATION at draw time). The lab's inputs are bound by the sampler type
// the program declares; a sampler the lab does not feed reads an empty unit (black).
// The stand-in's texture, made on first use in this scene like the target it replaces: the same
// internal format, size and faces, mipmapped when the target is. Rows go back to GL's order
// (readBack's in reverse: 2D images were flipped to top row first, cube faces were not).
GLuint LabRunner::standInTexture(const StandIn& stand_in, const TargetGl& target) {
    const auto found = stand_in_textures_.find(&stand_in);
    if (found != stand_in_textures_.end()) return found->second;
    const grader::Image& img = stand_in.image;
    const int w = target.spec->width, h = target.spec->height, faces = target.faces();
    if (img.width != w * faces || img.height != h || img.channels < 1) return 0;
    const GLenum tex_target = target.textureTarget();
    GLuint tex = 0;
    glGenTextures(1, &tex);
    glActiveTexture(GL_TEXTURE0 + kScratchTextureUnit);
    glBindTexture(tex_target, tex);
    std::vector<float> face(static_cast<std::size_t>(w) * h * 4);
    for (int f = 0; f < faces; ++f) {
        for (int y = 0; y < h; ++y) {
            const int src_y = target.cube() ? y : h - 1 - y;
            for (int x = 0; x < w; ++x)
                for (int c = 0; c < 4; ++c)
                    face[(static_cast<std::size_t>(y) * w + x) * 4 + c] =
                        c < img.channels ? img.at(f * w + x, src_y, c) : 1.0f;
        }
        const GLenum image =
            target.cube() ? GL_TEXTURE_CUBE_MAP_POSITIVE_X + static_cast<GLenum>(f) : GL_TEXTURE_2D;
        glTexImage2D(image, 0, static_cast<GLint>(targetInternalFormat(target.spec->format)), w, h, 0,
                     GL_RGBA, GL_FLOAT, face.data());
    }
    if (target.mipmapped) glGenerateMipmap(tex_target);
    glBindTexture(tex_target, 0);
    glActiveTexture(GL_TEXTURE0);
    stand_in_textures_[&stand_in] = tex;
    return tex;
}

void LabRunner::dropStandIns() {
    for (auto& [stand_in, tex] : stand_in_textures_) glDeleteTextures(1, &tex);
    stand_in_textures_.clear();
}

bool LabRunner::bindInputs(std::size_t pass_index, const ShaderProgram& prog, const std::string& scene) {
    const PassSpec& pass = spec_.passes[pass_index];
    for (const auto& [unit, target] : bound_units_) {
        glActiveTexture(GL_TEXTURE0 + unit);
        glBindTexture(target, 0);
        glBindSampler(unit, 0);
    }
    bound_units_.clear();
    const std::string& file = pass.program.fragment;
    GLuint unit = 0;
    std::set<std::string> fed;
    const auto fedByLab = [&](const std::string& name) {
        return std::any_of(pass.inputs.begin(), pass.inputs.end(),
                           [&](const PassInput& in) { return in.sampler == name; });
    };
    for (const UniformSlot& slot : prog.uniforms()) {
        if (glTypeInfo(slot.type).kind != ScalarKind::Sampler) continue;
        // Material textures have units of their own (material_textures.h), unless the lab feeds
        // the name itself.
        if (isMaterialSampler(slot.name) && !fedByLab(slot.name)) continue;
        if (slot.size > 1)
            return failAt(RenderStatus::LinkError,
                          "the program declares `" + std::string(glslTypeName(slot.type)) + " " + slot.name +
                              "[" + std::to_string(slot.size) +
                              "]`: arrays of samplers are not supported; declare one per input");
        if (static_cast<int>(unit) >= kMaxTextureUnits)
            return failAt(RenderStatus::LinkError, "the program declares more than 16 samplers");
        const PassInput* in = nullptr;
        for (const PassInput& candidate : pass.inputs)
            if (candidate.sampler == slot.name) in = &candidate;
        const GLenum tex_target = samplerTextureTarget(slot.type);
        const std::string declared = "`" + std::string(glslTypeName(slot.type)) + " " + slot.name + "`";
        glUniform1i(slot.location, static_cast<GLint>(unit));
        if (!in) {
            warnOnce(file, "sampler " + slot.name + " gets no texture from the lab (" + pass.path +
                               ".inputs has none by that name); it reads black");
            ++unit;
            continue;
        }
        fed.insert(in->sampler);
        if (tex_target == 0)
            return failAt(RenderStatus::LinkError,
                          in->path + ": the program declares " + declared +
                              "; inputs feed sampler1D, sampler2D, sampler3D, samplerCube "
                              "and sampler2DShadow");
        GLuint texture = 0;
        TextureFilter filter = in->filter.value_or(TextureFilter::Linear);
        TextureWrap wrap = in->wrap.value_or(TextureWrap::ClampToEdge);
        if (in->source == InputSource::Target) {
            TargetGl& t = *targets_.at(in->target);
            filter = in->filter.value_or(t.spec->filter);
            wrap = in->wrap.value_or(t.spec->wrap);
            const bool depth = in->attachment == "depth";
            if (depth) {
                if (tex_target != GL_TEXTURE_2D)
                    return failAt(RenderStatus::LinkError, in->path +
                                                               ": a depth texture is read with sampler2D or "
                                                               "sampler2DShadow; the program declares " +
                                                               declared);
                texture = t.depth_texture;
            } else {
                if (isShadowSampler(slot.type))
                    return failAt(RenderStatus::LinkError,
                                  in->path + ": the program declares " + declared +
                                      ", which compares depths: feed it a depth attachment (\"" + in->target +
                                      ".depth\")");
                if (tex_target != t.textureTarget())
                    return failAt(RenderStatus::LinkError, in->path + ": target '" + in->target + "' is " +
                                                               (t.cube() ? "a cube map (declare samplerCube)"
                                                                         : "2D (declare sampler2D)") +
                                                               "; the program declares " + declared);
                const auto at =
                    std::find(t.spec->attachments.begin(), t.spec->attachments.end(), in->attachment);
                const std::size_t index =
                    in->attachment.empty() ? 0 : static_cast<std::size_t>(at - t.spec->attachments.begin());
                texture = t.color[t.front][index];
                if (pass.isolate && !options_.stand_ins.empty()) {
                    const StandInSource source = standInSource(spec_, pass_index, *in);
                    for (const StandIn& s : options_.stand_ins)
                        if (source.pass && s.scene == scene && s.pass == source.pass->name &&
                            s.attachment == source.attachment)
                            if (const GLuint stand_in = standInTexture(s, t)) texture = stand_in;
                }
            }
        } else {
            const bool mipmaps = filter == TextureFilter::Mipmap;
            const std::string key = in->path + '\n' + std::to_string(slot.type) + (mipmaps ? "m" : "");
            auto it = input_textures_.find(key);
            if (it == input_textures_.end()) {
                InputTexture tex;
                const std::string problem = createInputTexture(spec_, *in, slot.type, mipmaps, &tex);
                if (!problem.empty()) return failAt(RenderStatus::LinkError, in->path + ": " + problem);
                it = input_textures_.emplace(key, tex).first;
            }
            texture = it->second.id;
        }
        glActiveTexture(GL_TEXTURE0 + unit);
        glBindTexture(tex_target, texture);
        glBindSampler(unit, sampler(filter, wrap, isShadowSampler(slot.type)));
        bound_units_.emplace_back(unit, tex_target);
        ++unit;
    }
    glActiveTexture(GL_TEXTURE0);
    material_textures_.beginPass(prog, fed, [&](const std::string& message) { warnOnce(file, message); });
    for (const PassInput& in : pass.inputs) {
        if (fed.count(in.sampler)) continue;
        const std::string text = prog.preparedText(0) + prog.preparedText(1);
        if (!mentionsIdentifier(text, in.sampler))
            warnOnce(file, in.path + ": the lab gives a texture to " + in.sampler + ", which neither " +
                               pass.program.vertex + " nor " + file + " declares" +
                               didYouMean(in.sampler, declaredUniformNames(text)));
    }
    return true;
}

}  // namespace shaderlab::render_detail
