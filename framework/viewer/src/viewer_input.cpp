// Keys and mouse: the keys the panel lists (view mode, debug view, scene, image, input, split,
// reset, render again, screenshot, quit) and orbit and zoom over the picture. What they change is
// picked up by the main loop; nothing is drawn here.
#include <algorithm>
#include <cmath>
#include <string>

#include "shaderlab/gl/gl.h"
// glad above provides the GL declarations; GLFW must not include its own.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "shaderlab/render/debug_view.h"
#include "viewer_window.h"

// Dear ImGui names keys with ImGuiKey from 1.87 on (1.90, Debian 13's, takes nothing else); 1.86,
// Debian 12's, takes the platform backend's key codes, here GLFW's.
#if IMGUI_VERSION_NUM >= 18700
#define VIEWER_KEY(imgui_name, glfw_code) ImGuiKey_##imgui_name
#else
#define VIEWER_KEY(imgui_name, glfw_code) glfw_code
#endif

namespace shaderlab::viewer::detail {

void Viewer::handleKeys() {
    ImGuiIO& io = ImGui::GetIO();
    if (io.WantTextInput) return;
    // 1 to 4 show the lab's picture in that mode; V steps through the debug views and back.
    const auto pick = [this](ViewMode m) {
        mode_ = m;
        setDebug(DebugView::Off);
    };
    if (ImGui::IsKeyPressed(VIEWER_KEY(1, GLFW_KEY_1))) pick(ViewMode::Student);
    if (ImGui::IsKeyPressed(VIEWER_KEY(2, GLFW_KEY_2))) pick(ViewMode::Reference);
    if (ImGui::IsKeyPressed(VIEWER_KEY(3, GLFW_KEY_3))) pick(ViewMode::Diff);
    if (ImGui::IsKeyPressed(VIEWER_KEY(4, GLFW_KEY_4))) pick(ViewMode::Split);
    if (ImGui::IsKeyPressed(VIEWER_KEY(V, GLFW_KEY_V), false)) {
        const std::vector<DebugViewInfo>& views = debugViews();
        std::size_t next = 0;  // Off -> the first view
        for (std::size_t i = 0; i < views.size(); ++i)
            if (views[i].view == debug_) next = i + 1;
        setDebug(next < views.size() ? views[next].view : DebugView::Off);
    }
    if (ImGui::IsKeyPressed(VIEWER_KEY(RightArrow, GLFW_KEY_RIGHT))) changeScene(1);
    if (ImGui::IsKeyPressed(VIEWER_KEY(LeftArrow, GLFW_KEY_LEFT))) changeScene(-1);
    const std::vector<PassImage>* mine = studentPasses();
    if (mine && !mine->empty() &&
        (ImGui::IsKeyPressed(VIEWER_KEY(DownArrow, GLFW_KEY_DOWN)) ||
         ImGui::IsKeyPressed(VIEWER_KEY(UpArrow, GLFW_KEY_UP)))) {
        int index = -1;
        for (std::size_t i = 0; i < mine->size(); ++i)
            if (shown_.student_pass == &(*mine)[i] && input_ < 0) index = static_cast<int>(i);
        if (index < 0) {
            for (std::size_t i = 0; i < mine->size(); ++i)
                if (imageKey((*mine)[i]) == selected_) index = static_cast<int>(i);
        }
        if (index < 0) index = static_cast<int>(mine->size()) - 1;
        index += ImGui::IsKeyPressed(VIEWER_KEY(DownArrow, GLFW_KEY_DOWN)) ? 1 : -1;
        index = std::clamp(index, 0, static_cast<int>(mine->size()) - 1);
        selected_ = imageKey((*mine)[static_cast<std::size_t>(index)]);
        input_ = -1;
        dirty_ = scroll_to_shown_ = true;
    }
    if (ImGui::IsKeyPressed(VIEWER_KEY(Tab, GLFW_KEY_TAB)) && shown_.student_pass) {
        const PassSpec* pass = nullptr;
        if (mine)
            for (const PassImage& p : *mine)
                if (imageKey(p) == (selected_.empty() ? imageKey(*shown_.student_pass) : selected_))
                    pass = spec_.findPass(p.pass);
        if (pass && !pass->inputs.empty()) {
            if (selected_.empty()) selected_ = imageKey(*shown_.student_pass);
            input_ = input_ + 1 >= static_cast<int>(pass->inputs.size()) ? -1 : input_ + 1;
            dirty_ = true;
        }
    }
    if (ImGui::IsKeyPressed(VIEWER_KEY(R, GLFW_KEY_R)) && orbit_.any()) {
        orbit_ = CameraOrbit();
        requestStudent(0);
    }
    if (ImGui::IsKeyPressed(VIEWER_KEY(LeftBracket, GLFW_KEY_LEFT_BRACKET)))
        split_ = std::max(0.0f, split_ - 0.05f);
    if (ImGui::IsKeyPressed(VIEWER_KEY(RightBracket, GLFW_KEY_RIGHT_BRACKET)))
        split_ = std::min(1.0f, split_ + 0.05f);
    if (ImGui::IsKeyPressed(VIEWER_KEY(F5, GLFW_KEY_F5))) requestStudent(0);
    if (ImGui::IsKeyPressed(VIEWER_KEY(S, GLFW_KEY_S), false)) {
        const std::string stem =
            "shaderlab-" + spec_.id + "-" + sceneName() + "-" + std::to_string(++screenshot_count_);
        saveScreenshots(stem + ".png", stem + "-window.png");
    }
    if (ImGui::IsKeyPressed(VIEWER_KEY(Escape, GLFW_KEY_ESCAPE)) ||
        ImGui::IsKeyPressed(VIEWER_KEY(Q, GLFW_KEY_Q)))
        glfwSetWindowShouldClose(window_, GLFW_TRUE);
}

// Orbit and zoom: drag and wheel over the picture (the item drawn last).
void Viewer::orbitByMouse() {
    ImGuiIO& io = ImGui::GetIO();
    if (ImGui::IsItemHovered() || ImGui::IsItemActive()) {
        bool moved = false;
        if (ImGui::IsItemActive() && ImGui::IsMouseDragging(ImGuiMouseButton_Left) &&
            (io.MouseDelta.x != 0.0f || io.MouseDelta.y != 0.0f)) {
            orbit_.yaw_deg -= io.MouseDelta.x * 0.5f;
            orbit_.pitch_deg = std::clamp(orbit_.pitch_deg + io.MouseDelta.y * 0.5f, -170.0f, 170.0f);
            moved = true;
        }
        if (io.MouseWheel != 0.0f) {
            orbit_.zoom = std::clamp(orbit_.zoom * std::pow(1.1f, io.MouseWheel), 0.2f, 8.0f);
            moved = true;
        }
        if (moved) requestStudent(0);
    }
}

}  // namespace shaderlab::viewer::detail
