// Step 4 of the lab.json parser, for targets: the targets passes own joined to the top-level
// ones (one declaration per name), their sizes in pixels, what a cube target cannot do, each
// pass's target, and the render state defaults that depend on it (depth test and write, and which
// attachments the first pass drawing into a target clears).
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "lab_spec_steps.h"

namespace shaderlab::lab_spec_detail {

namespace {

constexpr int kMaxPixels = 4096;

}  // namespace

void Validator::collectTargets() {
    std::map<std::string, std::string> where;  // target name -> path
    for (const TargetSpec& t : spec_.targets) where[t.name] = t.path;
    for (std::size_t i = 0; i < spec_.passes.size(); ++i) {
        if (!drafts_[i].own) continue;
        TargetSpec& t = *drafts_[i].own;
        const auto it = where.find(t.name);
        if (it != where.end()) {
            diag_.error(t.path,
                        "declares target " + quoteJson(t.name) + ", which " + it->second +
                            " already declares; to draw into it, write \"target\": " + quoteJson(t.name));
            continue;
        }
        where[t.name] = t.path;
        spec_.targets.push_back(t);
    }
    for (TargetSpec& t : spec_.targets) {
        if (t.width == 0) {
            t.width = static_cast<int>(std::lround(spec_.width * t.scale));
            t.height = static_cast<int>(std::lround(spec_.height * t.scale));
            if (t.width < 1 || t.height < 1 || t.width > kMaxPixels || t.height > kMaxPixels)
                diag_.error(joinKey(t.path, "scale"), "gives a " + std::to_string(t.width) + "x" +
                                                          std::to_string(t.height) +
                                                          " target; each side must be from 1 to 4096 pixels");
        }
        if (t.type == TargetType::Cube && t.width != t.height)
            diag_.error(t.path, "a cube target must be square, got " + std::to_string(t.width) + "x" +
                                    std::to_string(t.height));
        if (t.type == TargetType::Cube && t.depth == DepthMode::Texture)
            diag_.error(joinKey(t.path, "depth"), "a cube target's depth cannot be sampled");
    }
}

void Validator::resolvePassTargets() {
    std::set<std::string> written;
    for (std::size_t i = 0; i < spec_.passes.size(); ++i) {
        PassSpec& p = spec_.passes[i];
        PassDraft& d = drafts_[i];
        p.target = d.own ? d.own->name : d.target_ref;
        const TargetSpec* t = spec_.findTarget(p.target);
        if (!t) {
            std::vector<std::string> names;
            for (const TargetSpec& x : spec_.targets) names.push_back(x.name);
            diag_.error(joinKey(p.path, "target"),
                        "no target is called " + quoteJson(p.target) + didYouMean(p.target, names));
            continue;
        }
        if (t->type == TargetType::Cube && p.draw == DrawKind::Scene)
            diag_.error(joinKey(p.path, "draw"),
                        "a scene draw cannot render into the cube target " + quoteJson(t->name) +
                            "; use \"fullscreen\" or a draw without a mesh (one per face, u_cube_face)");
        const bool first_writer = written.insert(p.target).second;
        resolveState(p, d, *t, first_writer);
    }
}

void Validator::resolveState(PassSpec& p, const PassDraft& d, const TargetSpec& t, bool first_writer) {
    const bool fullscreen = p.draw == DrawKind::Fullscreen;
    const bool has_depth = t.depth != DepthMode::None;
    p.state.depth_test = d.depth_test.value_or(!fullscreen && has_depth);
    p.state.depth_write = d.depth_write.value_or(!fullscreen && has_depth);
    p.state.clear_depth = d.clear_depth.value_or(first_writer && has_depth);
    if (!has_depth) {
        const std::string state = joinKey(p.path, "state");
        if (d.depth_test && *d.depth_test)
            diag_.error(joinKey(state, "depth_test"),
                        "target " + quoteJson(t.name) + " has no depth (\"depth\": \"none\")");
        if (d.depth_write && *d.depth_write)
            diag_.error(joinKey(state, "depth_write"),
                        "target " + quoteJson(t.name) + " has no depth (\"depth\": \"none\")");
    }
    const glm::vec4 black(0.0f, 0.0f, 0.0f, 1.0f);
    p.state.clear_colors.assign(t.attachments.size(),
                                first_writer ? std::optional<glm::vec4>(black) : std::nullopt);
    if (!d.clear_color) return;
    const json& c = *d.clear_color;
    if (c.is_null()) {
        p.state.clear_colors.assign(t.attachments.size(), std::nullopt);
    } else if (c.is_array()) {
        p.state.clear_colors.assign(t.attachments.size(), readVec4(c));
    } else {
        for (const auto& item : c.items()) {
            const auto at = std::find(t.attachments.begin(), t.attachments.end(), item.key());
            if (at == t.attachments.end()) {
                diag_.error(joinKey(joinKey(joinKey(p.path, "state"), "clear_color"), item.key()),
                            "target " + quoteJson(t.name) + " has no attachment " + quoteJson(item.key()) +
                                didYouMean(item.key(), t.attachments));
                continue;
            }
            p.state.clear_colors[static_cast<std::size_t>(at - t.attachments.begin())] =
                item.value().is_null() ? std::nullopt : std::optional<glm::vec4>(readVec4(item.value()));
        }
    }
}

}  // namespace shaderlab::lab_spec_detail
