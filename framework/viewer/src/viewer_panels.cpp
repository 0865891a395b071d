// The panels: on the left of the window the controls (the view mode, the debug view of the vertex
// data, viewer_debug.cpp; the scene and camera; the images of the scene and the textures a pass
// reads; the keys), on the right the verdict grading would give this scene and the lab's grade
// (points, every goal and why one is not met, failing scenes and their known-mistake hints, in
// `check`'s words). They read what the other parts worked out; they judge, grade and render
// nothing themselves.
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
    ImGui::SetCursorPosY(std::max(ImGui::GetCursorPosY(), height - kKeysHeight));
    drawKeys();
    ImGui::End();
}

// The column on the right: the verdict grading would give this scene, then the lab's grade with
// every goal, the failing scenes and their known-mistake hints.
void Viewer::drawResults(float x, float width, float height) {
    ImGui::SetNextWindowPos(ImVec2(x, 0));
    ImGui::SetNextWindowSize(ImVec2(width, height));
    ImGui::Begin("results", nullptr,
                 ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoMove |
                     ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoBringToFrontOnFocus);
    drawVerdict(height);
    drawGrade();
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

// The verdict grading would give, or why there is none yet: at most a third of the column.
void Viewer::drawVerdict(float height) {
    ImGui::TextDisabled("THIS SCENE");
    if (!judged_.empty()) {
        bool passed = true;
        for (const Judged& j : judged_) passed = passed && j.verdict.passed;
        ImGui::TextColored(passed ? kGreen : kRed, "scene %s: %s", student_scene_.c_str(),
                           passed ? "PASS" : "FAIL");
        if (!judged_graded_view_) ImGui::TextDisabled("(this turned view is not graded)");
        if (!error_title_.empty()) ImGui::TextDisabled("(of the last good picture, before the error)");
        const float lines = 3.0f * static_cast<float>(judged_.size()) + 1.0f;
        ImGui::BeginChild("verdict",
                          ImVec2(0, std::min(height / 3.0f, lines * ImGui::GetTextLineHeightWithSpacing())),
                          false);
        if (!error_title_.empty()) ImGui::PushStyleVar(ImGuiStyleVar_Alpha, 0.5f);
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
        if (!error_title_.empty()) ImGui::PopStyleVar();
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
}

void Viewer::buildGradeLines() { grade_lines_ = grade_ ? gradeLines(*grade_) : std::vector<PanelLine>(); }

// The lab graded as `check` grades it: the points, then every goal and what is missing, as
// `check` says it.
void Viewer::drawGrade() {
    ImGui::Separator();
    ImGui::TextDisabled("YOUR GRADE (as `check` gives it)");
    if (!grade_) {
        if (grade_error_.empty())
            ImGui::TextDisabled("grade: grading the lab as `check` does");
        else
            ImGui::TextWrapped("%s", grade_error_.c_str());
        return;
    }
    const grader::ReportLab& lab = *grade_;
    const bool passed = lab.status == "passed";
    // While a newer save is graded this grade is the previous save's: said, and dimmed.
    const bool old = grading();
    ImGui::TextColored(old      ? ImVec4(0.6f, 0.6f, 0.6f, 1)
                       : passed ? kGreen
                                : kRed,
                       "lab %s: %.2f / %.2f points", lab.id.c_str(), lab.score, lab.max_score);
    if (old) {
        ImGui::SameLine();
        ImGui::TextDisabled("(previous save; grading)");
    }
    if (!grade_error_.empty()) ImGui::TextWrapped("%s", grade_error_.c_str());
    // The rest of the column; it scrolls.
    ImGui::BeginChild("grade", ImVec2(0, 0), false);
    if (old) ImGui::PushStyleVar(ImGuiStyleVar_Alpha, 0.5f);
    for (const PanelLine& l : grade_lines_) {
        switch (l.kind) {
            case PanelLine::Met:
            case PanelLine::Missed:
                ImGui::TextColored(l.kind == PanelLine::Met ? kGreen : kRed, "%s",
                                   l.kind == PanelLine::Met ? "ok  " : "MISS");
                ImGui::SameLine();
                ImGui::TextWrapped("%s", l.text.c_str());
                break;
            case PanelLine::Why:
            case PanelLine::Judged:
                ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
                ImGui::Indent(28.0f);
                ImGui::TextWrapped("%s", l.text.c_str());
                ImGui::Unindent(28.0f);
                ImGui::PopStyleColor();
                break;
            case PanelLine::FailingScene:
                // Picking a failing scene shows it.
                ImGui::PushStyleColor(ImGuiCol_Text, kRed);
                if (ImGui::Selectable((l.text + "##grade").c_str(), l.scene == sceneName()))
                    for (std::size_t i = 0; i < spec_.scenes.size(); ++i)
                        if (spec_.scenes[i].name == l.scene && static_cast<int>(i) != scene_) {
                            scene_ = static_cast<int>(i);
                            requestStudent(0);
                        }
                ImGui::PopStyleColor();
                break;
            case PanelLine::Hint:
                ImGui::PushStyleColor(ImGuiCol_Text, kHint);
                ImGui::Indent(12.0f);
                ImGui::TextWrapped("%s", l.text.c_str());
                ImGui::Unindent(12.0f);
                ImGui::PopStyleColor();
                break;
            case PanelLine::Note:
                ImGui::TextWrapped("%s", l.text.c_str());
                break;
        }
    }
    if (old) ImGui::PopStyleVar();
    ImGui::EndChild();
}

// For scripts and tests (--panel-text): the grade's lines as drawn, then the scene's verdict.
void Viewer::savePanelText(const std::string& path) const {
    std::string text;
    if (grade_) {
        char head[160];
        std::snprintf(head, sizeof head, "lab %s: %.2f / %.2f points\n", grade_->id.c_str(), grade_->score,
                      grade_->max_score);
        text += head;
    }
    static const char* const kinds[] = {"met", "miss", "why", "judged", "scene", "hint", "note"};
    for (const PanelLine& l : grade_lines_) text += std::string(kinds[l.kind]) + ": " + l.text + "\n";
    for (const Judged& j : judged_)
        text += std::string("verdict: ") + (j.verdict.passed ? "ok " : "FAIL ") + j.label + "\n";
    FILE* f = std::fopen(path.c_str(), "w");
    if (!f || std::fputs(text.c_str(), f) < 0 || std::fclose(f) != 0) {
        std::fprintf(stderr, "view: cannot write %s\n", path.c_str());
        return;
    }
    std::printf("view: saved the panel's text to %s\n", path.c_str());
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
