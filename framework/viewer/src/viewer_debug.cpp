// The debug view of the scene's vertex data in the window: which view is on (the panel's combo and
// the V key), the render server asked for it on the scene and camera on screen
// (RenderRequest::debug_view: the framework's own program, in the same child process as a lab's
// render), the picture in place of the lab's, the view named above it, the values under the mouse
// decoded, and what the view could not show (a mesh without tangents) in the panel and on the
// terminal. Nothing here draws the view itself.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "shaderlab/render/debug_view.h"
#include "viewer_window.h"

namespace shaderlab::viewer::detail {

namespace {

const ImVec4 kDebugColor(1.0f, 0.85f, 0.35f, 1.0f);

}  // namespace

void Viewer::setDebug(DebugView view) {
    if (view == debug_) return;
    debug_ = view;
    if (view == DebugView::Off) {
        std::printf("view: the lab's picture\n");
    } else {
        std::printf("view: debug view %s: %s\n", debugViewName(view), debugViewInfo(view)->label);
        requestDebug();
    }
    std::fflush(stdout);
}

// The view on screen for the scene and camera on screen, unless it is drawn already.
void Viewer::requestDebug() {
    if (debug_ == DebugView::Off) return;
    if (debug_render_ && debug_render_view_ == debug_ && debug_render_scene_ == sceneName() &&
        debug_render_orbit_ == orbit_)
        return;
    Job job;
    job.kind = kDebug;
    job.request.scene = sceneName();
    job.request.orbit = orbit_;
    job.request.timeout_s = std::max(opt_.timeout_s, 10.0);
    job.request.debug_view = debug_;
    queue_->submit(std::move(job));
}

// Keeps a good picture (and says what it could not show, once each); a failure is kept as text.
void Viewer::onDebug(const Finished& f) {
    const IsolatedRender& r = f.result;
    const DebugView view = f.job.request.debug_view;
    const bool drawn = r.status == IsolatedStatus::Ok && r.render.scenes.size() == 1 &&
                       r.render.scenes[0].passes.size() == 1;
    if (!drawn) {
        debug_error_ =
            r.status == IsolatedStatus::Ok && !r.render.scenes.empty() && !r.render.scenes[0].error.empty()
                ? "the scene did not load: " + r.render.scenes[0].error
                : std::string("not drawn (") + isolatedStatusName(r.status) + "): " + r.message;
        std::printf("view: debug view %s of scene %s: %s\n", debugViewName(view), f.job.request.scene.c_str(),
                    debug_error_.c_str());
        std::fflush(stdout);
        return;
    }
    debug_error_.clear();
    debug_render_ = std::make_shared<const IsolatedRender>(r);
    debug_render_view_ = view;
    debug_render_scene_ = f.job.request.scene;
    debug_render_orbit_ = f.job.request.orbit;
    tex_debug_.upload(debug_render_->render.scenes[0].passes[0].color);
    debug_notes_.clear();
    std::printf("view: debug view %s of scene %s drawn in %.0f ms\n", debugViewName(view),
                debug_render_scene_.c_str(), r.wall_ms);
    for (const Diagnostic& d : r.render.diagnostics) {
        if (d.severity != "note") continue;
        debug_notes_.push_back(d.message);
        std::printf("view: debug view: %s\n", d.message.c_str());
    }
    std::fflush(stdout);
}

// For scripts: the debug view asked for is on screen, or could not be drawn.
bool Viewer::debugSettled() const {
    if (debug_ == DebugView::Off) return true;
    if (!debug_error_.empty()) return true;
    return debug_render_ && debug_render_view_ == debug_ && debug_render_scene_ == sceneName() &&
           debug_render_orbit_ == orbit_;
}

// The image to show: the last one drawn of this view and scene (of another camera while the new
// one is drawn, as the lab's picture keeps the last good one); null when there is none.
const PassImage* Viewer::debugImage() const {
    if (!debug_render_ || debug_render_view_ != debug_ || debug_render_scene_ != sceneName()) return nullptr;
    return &debug_render_->render.scenes[0].passes[0];
}

// The combo in the panel: the lab's picture, or one of the views.
void Viewer::drawDebugControls() {
    ImGui::Separator();
    const DebugViewInfo* info = debugViewInfo(debug_);
    const std::string current = info ? info->name : "off: the lab's picture";
    if (ImGui::BeginCombo("vertex data [V]", current.c_str())) {
        if (ImGui::Selectable("off: the lab's picture", debug_ == DebugView::Off)) setDebug(DebugView::Off);
        for (const DebugViewInfo& v : debugViews())
            if (ImGui::Selectable(v.name, debug_ == v.view)) setDebug(v.view);
        ImGui::EndCombo();
    }
    if (!info) return;
    ImGui::TextDisabled("a debug view of the scene, not graded");
    if (!debug_error_.empty()) ImGui::TextColored(ImVec4(1, 0.35f, 0.3f, 1), "%s", debug_error_.c_str());
    if (!debugImage()) return;
    ImGui::PushStyleColor(ImGuiCol_Text, kDebugColor);
    for (const std::string& note : debug_notes_) ImGui::TextWrapped("%s", note.c_str());
    ImGui::PopStyleColor();
}

// Above the picture: which view it is, and what its colours mean.
void Viewer::drawDebugLabel() {
    const DebugViewInfo* info = debugViewInfo(debug_);
    ImGui::PushStyleColor(ImGuiCol_Text, kDebugColor);
    ImGui::TextWrapped("vertex data: %s - %s", info->name, info->label);
    ImGui::PopStyleColor();
}

void Viewer::drawDebugImage(float area_w, float area_h) {
    if (!debugImage()) {
        drawMissing(debug_error_.empty() ? std::string("drawing the ") + debugViewName(debug_) + " view..."
                                         : debug_error_,
                    area_w, area_h);
        return;
    }
    placeImage(tex_debug_, area_w, area_h);
}

// The colour under the mouse and what it stands for (describeDebugPixel).
void Viewer::drawDebugInspector(int x, int y) {
    const PassImage* img = debugImage();
    if (!img || x < 0 || y < 0 || x >= img->color.width || y >= img->color.height) {
        ImGui::TextDisabled("point at the picture to read its vertex data");
        return;
    }
    const float r = img->color.at(x, y, 0), g = img->color.at(x, y, 1), b = img->color.at(x, y, 2);
    const bool covered =
        img->coverage.empty() || img->coverage[static_cast<std::size_t>(y) * img->color.width + x] != 0;
    ImGui::Text("pixel %d, %d   colour %.4f %.4f %.4f", x, y, r, g, b);
    ImGui::Text("%s", describeDebugPixel(debug_, r, g, b, covered).c_str());
}

}  // namespace shaderlab::viewer::detail
