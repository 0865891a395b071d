// The panel of controls on the left of the window: the view mode, the debug view of the vertex
// data (viewer_debug.cpp), the scene and camera, the
// images of the scene and the textures a pass reads, the lab's grade (points, goals not met,
// failing scenes and their known-mistake hints, in `check`'s words), the verdict grading would
// give this scene, and the keys. It reads what the other parts worked out; it judges, grades and
// renders nothing itself.
#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "grader/base/untrusted_text.h"
#include "grader/reports/report.h"
#include "viewer_window.h"

namespace fs = std::filesystem;

namespace shaderlab::viewer::detail {

namespace {

// Room at the bottom of the controls for the list of keys.
constexpr float kKeysHeight = 190.0f;
// At most this much of the panel for the goals and scenes the grade misses (it scrolls).
constexpr float kGradeHeight = 190.0f;

const ImVec4 kGreen(0.3f, 0.9f, 0.3f, 1), kRed(1, 0.35f, 0.3f, 1), kHint(1, 0.8f, 0.3f, 1);

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
    // A mode of the lab's picture, picked, shows the lab's picture again.
    bool picked = ImGui::RadioButton("student [1]", &mode, 0);
    ImGui::SameLine();
    picked |= ImGui::RadioButton("reference [2]", &mode, 1);
    picked |= ImGui::RadioButton("diff [3]", &mode, 2);
    ImGui::SameLine();
    picked |= ImGui::RadioButton("split [4]", &mode, 3);
    if (picked) setDebug(DebugView::Off);
    mode_ = static_cast<ViewMode>(mode);
    if (mode_ == ViewMode::Split) ImGui::SliderFloat("split", &split_, 0.0f, 1.0f, "%.2f");
    drawDebugControls();

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

    drawGrade();
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
        ImGui::TextColored(passed ? kGreen : kRed, "scene %s: %s", student_scene_.c_str(),
                           passed ? "PASS" : "FAIL");
        if (!judged_graded_view_) ImGui::TextDisabled("(this turned view is not graded)");
        ImGui::BeginChild("verdict", ImVec2(0, -kKeysHeight), false);
        for (const Judged& j : judged_) {
            const grader::MetricSet& m = j.verdict.covered;
            ImGui::TextColored(j.verdict.passed ? kGreen : kRed, "%s", j.verdict.passed ? "ok  " : "FAIL");
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

// The lab graded as `check` grades it: the points, then what is missing, as `check` says it.
void Viewer::drawGrade() {
    ImGui::Separator();
    if (!grade_) {
        if (grade_error_.empty())
            ImGui::TextDisabled("grade: grading the lab as `check` does");
        else
            ImGui::TextWrapped("%s", grade_error_.c_str());
        return;
    }
    const grader::ReportLab& lab = *grade_;
    const bool passed = lab.status == "passed";
    ImGui::TextColored(passed ? kGreen : kRed, "lab %s: %.2f / %.2f points", lab.id.c_str(), lab.score,
                       lab.max_score);
    if (grading()) {
        ImGui::SameLine();
        ImGui::TextDisabled("(grading again)");
    }
    if (!grade_error_.empty()) ImGui::TextWrapped("%s", grade_error_.c_str());
    if (passed) return;
    // Half of what is left above the keys, so that the scene's verdict below keeps the rest.
    const float room = ImGui::GetContentRegionAvail().y - kKeysHeight;
    ImGui::BeginChild("grade", ImVec2(0, std::clamp(room * 0.5f, 60.0f, kGradeHeight)), false);
    if (lab.goals.empty())
        ImGui::TextWrapped("%s: %s", lab.status.c_str(), grader::printableText(lab.message).c_str());
    for (const grader::ReportGoal& g : lab.goals) {
        if (g.met) continue;
        ImGui::TextColored(kRed, "MISS");
        ImGui::SameLine();
        ImGui::TextWrapped("goal %s (%.2f)", g.title.c_str(), g.points);
        if (!g.not_met_because.empty()) {
            ImGui::TextWrapped("  not met because %s %s not met",
                               grader::goalsNamed(lab, g.not_met_because).c_str(),
                               g.not_met_because.size() > 1 ? "are" : "is");
        } else {
            std::string where;
            for (const std::string& f : g.failing) where += (where.empty() ? "" : ", ") + f;
            ImGui::TextWrapped("  not met in %s", where.c_str());
        }
    }
    for (const grader::ReportScene& sc : lab.scenes) {
        if (sc.status == "passed") continue;
        // Picking a failing scene shows it.
        if (ImGui::Selectable(("FAIL scene " + sc.name + "##grade").c_str(), sc.name == sceneName()))
            for (std::size_t i = 0; i < spec_.scenes.size(); ++i)
                if (spec_.scenes[i].name == sc.name && static_cast<int>(i) != scene_) {
                    scene_ = static_cast<int>(i);
                    requestStudent(0);
                }
        if (!sc.message.empty()) ImGui::TextWrapped("  %s", sc.message.c_str());
        if (!sc.hint.mistake.empty()) {
            ImGui::PushStyleColor(ImGuiCol_Text, kHint);
            ImGui::TextWrapped("  This looks like a known mistake: %s",
                               grader::printableText(sc.hint.about).c_str());
            ImGui::PopStyleColor();
        }
    }
    ImGui::EndChild();
}

// Which reference the verdict uses, and the keys.
void Viewer::drawKeys() {
    ImGui::Separator();
    ImGui::TextDisabled("reference: %s",
                        opt_.reference_root.empty() ? "stored golden images" : "reference solution");
    ImGui::TextDisabled("keys");
    ImGui::TextDisabled("1 2 3 4   student, reference, diff, split");
    ImGui::TextDisabled("V         vertex data: normals, tangents, ...");
    ImGui::TextDisabled("[ ]       move the split");
    ImGui::TextDisabled("left/right scene    up/down image");
    ImGui::TextDisabled("Tab       textures the pass reads");
    ImGui::TextDisabled("drag/wheel orbit, zoom   R reset");
    ImGui::TextDisabled("S screenshot   F5 render again   Q quit");
}

}  // namespace shaderlab::viewer::detail
