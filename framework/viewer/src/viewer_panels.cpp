// The panel of controls on the left of the window: the view mode, the scene and camera, the
// images of the scene and the textures a pass reads, the verdict grading would give, and the
// keys. It reads what the other parts worked out; it judges and renders nothing itself.
#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "viewer_window.h"

namespace fs = std::filesystem;

namespace shaderlab::viewer::detail {

namespace {

// Room at the bottom of the controls for the list of keys.
constexpr float kKeysHeight = 172.0f;

}  // namespace

void Viewer::drawControls(float width, float height) {
    ImGui::SetNextWindowPos(ImVec2(0, 0));
    ImGui::SetNextWindowSize(ImVec2(width, height));
    ImGui::Begin("controls", nullptr,
                 ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoMove |
                     ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoBringToFrontOnFocus);
    ImGui::TextWrapped("%s", spec_.title.c_str());
    ImGui::TextDisabled("%s", (fs::path(opt_.submission_root) / spec_.id).string().c_str());
    ImGui::Separator();

    int mode = static_cast<int>(mode_);
    ImGui::RadioButton("student [1]", &mode, 0);
    ImGui::SameLine();
    ImGui::RadioButton("reference [2]", &mode, 1);
    ImGui::RadioButton("diff [3]", &mode, 2);
    ImGui::SameLine();
    ImGui::RadioButton("split [4]", &mode, 3);
    mode_ = static_cast<ViewMode>(mode);
    if (mode_ == ViewMode::Split) ImGui::SliderFloat("split", &split_, 0.0f, 1.0f, "%.2f");

    ImGui::Separator();
    if (ImGui::BeginCombo("scene", sceneName().c_str())) {
        for (std::size_t i = 0; i < spec_.scenes.size(); ++i)
            if (ImGui::Selectable(spec_.scenes[i].name.c_str(), static_cast<int>(i) == scene_)) {
                scene_ = static_cast<int>(i);
                requestStudent(0);
            }
        ImGui::EndCombo();
    }
    if (orbit_.any()) {
        ImGui::TextColored(ImVec4(1, 0.8f, 0.3f, 1), "turned view: yaw %.0f pitch %.0f zoom %.2f",
                           orbit_.yaw_deg, orbit_.pitch_deg, orbit_.zoom);
        if (ImGui::Button("back to the graded view [R]")) {
            orbit_ = CameraOrbit();
            requestStudent(0);
        }
    } else {
        ImGui::TextDisabled("graded view (drag to orbit, wheel to zoom)");
    }

    // Passes and the textures they read.
    const std::vector<PassImage>* mine = studentPasses();
    if (mine) drawImageList(*mine);

    drawVerdict(height);
    drawKeys();
    ImGui::End();
}

// The images of the scene (pass outputs, the graded ones starred) and the textures the
// selected pass reads; picking one shows it.
void Viewer::drawImageList(const std::vector<PassImage>& mine) {
    ImGui::Separator();
    ImGui::Text("images of this scene [up/down]");
    ImGui::BeginChild("passes", ImVec2(0, std::min(150.0f, 20.0f * static_cast<float>(mine.size()) + 8.0f)),
                      true);
    for (const PassImage& p : mine) {
        const std::string label = (p.graded ? "* " : "  ") + p.pass + " -> " + p.target + "." + p.attachment;
        const bool shown = shown_.student_pass == &p && input_ < 0;
        if (shown && scroll_to_shown_) {
            ImGui::SetScrollHereY();
            scroll_to_shown_ = false;
        }
        if (ImGui::Selectable(label.c_str(), shown)) {
            selected_ = imageKey(p);
            input_ = -1;
            dirty_ = true;
        }
    }
    ImGui::EndChild();
    const PassSpec* pass = nullptr;
    for (const PassImage& p : mine)
        if (imageKey(p) == selected_) pass = spec_.findPass(p.pass);
    if (!pass && shown_.pass) pass = shown_.pass;
    if (pass && !pass->inputs.empty()) {
        ImGui::Text("textures pass '%s' reads [Tab]", pass->name.c_str());
        for (std::size_t i = 0; i < pass->inputs.size(); ++i) {
            const PassInput& in = pass->inputs[i];
            std::string from = in.source == InputSource::Target ? in.target
                               : in.source == InputSource::File ? in.file
                               : in.source == InputSource::Cube ? "cube map"
                                                                : "generated " + in.generated.pattern;
            const std::string label = "  " + in.sampler + " <- " + from + "##in" + std::to_string(i);
            if (ImGui::Selectable(label.c_str(), input_ == static_cast<int>(i))) {
                if (selected_.empty() && shown_.student_pass) selected_ = imageKey(*shown_.student_pass);
                input_ = input_ == static_cast<int>(i) ? -1 : static_cast<int>(i);
                dirty_ = true;
            }
        }
    }
    ImGui::TextDisabled("* graded image");
}

// The verdict grading would give, or why there is none yet.
void Viewer::drawVerdict(float height) {
    ImGui::Separator();
    if (!judged_.empty()) {
        bool passed = true;
        for (const Judged& j : judged_) passed = passed && j.verdict.passed;
        ImGui::TextColored(passed ? ImVec4(0.3f, 0.9f, 0.3f, 1) : ImVec4(1, 0.35f, 0.3f, 1), "scene %s: %s",
                           student_scene_.c_str(), passed ? "PASS" : "FAIL");
        if (!judged_graded_view_) ImGui::TextDisabled("(this turned view is not graded)");
        ImGui::BeginChild("verdict", ImVec2(0, -kKeysHeight), false);
        for (const Judged& j : judged_) {
            const grader::MetricSet& m = j.verdict.covered;
            ImGui::TextColored(j.verdict.passed ? ImVec4(0.3f, 0.9f, 0.3f, 1) : ImVec4(1, 0.35f, 0.3f, 1),
                               "%s", j.verdict.passed ? "ok  " : "FAIL");
            ImGui::SameLine();
            ImGui::Text("%s", j.label.c_str());
            char ssim[16] = "n/a";
            if (m.ssim_defined) std::snprintf(ssim, sizeof ssim, "%.3f", m.ssim);
            ImGui::TextDisabled("  PSNR %s  SSIM %s  FLIP %.3f", formatPsnr(m.psnr_db).c_str(), ssim,
                                m.flip_mean);
            ImGui::TextDisabled("  mismatch %.2f%%", 100.0 * m.mismatch_fraction);
            if (j.verdict.nan_count) ImGui::Text("  %zu NaN pixels", j.verdict.nan_count);
            for (const std::string& r : j.verdict.reasons) ImGui::TextWrapped("  %s", r.c_str());
        }
        ImGui::EndChild();
    } else if (!opt_.reference_root.empty() && !reference_error_.empty()) {
        ImGui::TextWrapped("%s", reference_error_.c_str());
    } else if (opt_.reference_root.empty() && orbit_.any()) {
        ImGui::TextWrapped(
            "no reference for a turned view: the stored golden images show the graded view only");
    } else if (opt_.reference_root.empty() && golden_errors_.count(sceneName())) {
        ImGui::TextWrapped("%s", golden_errors_[sceneName()].c_str());
    } else {
        ImGui::TextDisabled("verdict: waiting for both pictures");
    }
    if (judged_.empty()) ImGui::SetCursorPosY(std::max(ImGui::GetCursorPosY(), height - kKeysHeight));
}

// Which reference the verdict uses, and the keys.
void Viewer::drawKeys() {
    ImGui::Separator();
    ImGui::TextDisabled("reference: %s",
                        opt_.reference_root.empty() ? "stored golden images" : "reference solution");
    ImGui::TextDisabled("keys");
    ImGui::TextDisabled("1 2 3 4   student, reference, diff, split");
    ImGui::TextDisabled("[ ]       move the split");
    ImGui::TextDisabled("left/right scene    up/down image");
    ImGui::TextDisabled("Tab       textures the pass reads");
    ImGui::TextDisabled("drag/wheel orbit, zoom   R reset");
    ImGui::TextDisabled("S screenshot   F5 render again   Q quit");
}

}  // namespace shaderlab::viewer::detail
