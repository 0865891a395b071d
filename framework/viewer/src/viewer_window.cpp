// The student's window; see viewer.h. One main loop in the style of Dear ImGui's own examples:
// poll the folder, take finished renders, handle keys, lay out the panels, draw, swap. Every
// picture comes from RenderService (the grader's renderer in a child process); every number from
// grader::judgeImage with the lab's thresholds. This file opens and closes the window and runs
// the loop; what the loop calls lives beside it (viewer_window.h names the files).
#include "viewer_window.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "shaderlab/gl/gl.h"
// glad above provides the GL declarations; GLFW must not include its own.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include "grader/metrics/image.h"

namespace fs = std::filesystem;

namespace shaderlab::viewer {

namespace detail {

namespace {

ViewMode parseMode(const std::string& s) {
    if (s == "reference") return ViewMode::Reference;
    if (s == "diff") return ViewMode::Diff;
    if (s == "split") return ViewMode::Split;
    return ViewMode::Student;
}

// The frame times of a run, printed at its end.
void printFrameTimes(const std::vector<double>& frame_ms) {
    // The first frame compiles the panels' shaders: left out of the figures.
    if (frame_ms.size() > 1) {
        std::vector<double> t(frame_ms.begin() + 1, frame_ms.end());
        std::sort(t.begin(), t.end());
        double sum = 0.0;
        for (double v : t) sum += v;
        std::printf(
            "view: %zu frames, %.1f ms a frame on average, median %.1f, 95th percentile %.1f, at most "
            "%.1f "
            "(first frame %.1f)\n",
            frame_ms.size(), sum / static_cast<double>(t.size()), t[t.size() / 2],
            t[std::min(t.size() - 1, t.size() * 95 / 100)], t.back(), frame_ms[0]);
    }
}

}  // namespace

std::int64_t nowNs() {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(
               std::chrono::system_clock::now().time_since_epoch())
        .count();
}

void Viewer::layout() {
    int w = 0, h = 0;
    glfwGetWindowSize(window_, &w, &h);
    // Controls on the left, the picture, the verdict and grade on the right (as the page has them).
    const float panel = 320.0f;
    const float results = std::clamp(static_cast<float>(w) * 0.27f, 240.0f, 380.0f);
    drawControls(panel, static_cast<float>(h));
    drawPicture(panel, std::max(0.0f, static_cast<float>(w) - panel - results), static_cast<float>(h));
    drawResults(static_cast<float>(w) - results, results, static_cast<float>(h));
}

// Reads the back buffer just drawn: the picture one pixel per image pixel (the centre of each
// image pixel as shown), and the whole window.
void Viewer::saveScreenshots(const std::string& view_path, const std::string& window_path) {
    int fw = 0, fh = 0;
    glfwGetFramebufferSize(window_, &fw, &fh);
    std::vector<unsigned char> rgba(static_cast<std::size_t>(fw) * fh * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadBuffer(GL_BACK);
    glReadPixels(0, 0, fw, fh, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    auto at = [&](int x, int y, int c) {
        return rgba[(static_cast<std::size_t>(fh - 1 - y) * fw + x) * 4 + c] / 255.0f;
    };
    std::string err;
    if (!window_path.empty()) {
        grader::Image img(fw, fh, 3);
        for (int y = 0; y < fh; ++y)
            for (int x = 0; x < fw; ++x)
                for (int c = 0; c < 3; ++c) img.at(x, y, c) = at(x, y, c);
        if (grader::writePng(img, window_path, &err))
            std::printf("view: saved the window to %s\n", window_path.c_str());
        else
            std::fprintf(stderr, "view: %s\n", err.c_str());
    }
    if (!view_path.empty()) {
        if (image_w_ <= 0) {
            std::fprintf(stderr, "view: no picture on screen to save to %s\n", view_path.c_str());
        } else {
            const ImVec2 fb_scale = ImGui::GetIO().DisplayFramebufferScale;
            grader::Image img(image_w_, image_h_, 3);
            for (int y = 0; y < image_h_; ++y)
                for (int x = 0; x < image_w_; ++x) {
                    const int sx = std::clamp(
                        static_cast<int>((image_min_.x + (x + 0.5f) * image_scale_) * fb_scale.x), 0, fw - 1);
                    const int sy = std::clamp(
                        static_cast<int>((image_min_.y + (y + 0.5f) * image_scale_) * fb_scale.y), 0, fh - 1);
                    for (int c = 0; c < 3; ++c) img.at(x, y, c) = at(sx, sy, c);
                }
            if (grader::writePng(img, view_path, &err))
                std::printf("view: saved the picture to %s\n", view_path.c_str());
            else
                std::fprintf(stderr, "view: %s\n", err.c_str());
        }
    }
    std::fflush(stdout);
}

bool Viewer::openWindow() {
    glfwSetErrorCallback([](int, const char* what) { std::fprintf(stderr, "view: GLFW: %s\n", what); });
    if (!glfwInit()) {
        std::fprintf(stderr,
                     "view: cannot open a window (no display?). `shaderlab watch %s` checks your work "
                     "on every save without one.\n",
                     spec_.id.c_str());
        return false;
    }
    // 3.3 core, forward compatible: what macOS offers, so the window runs on every laptop.
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    const std::string title = "shaderlab view - " + spec_.id;
    window_ = glfwCreateWindow(opt_.width, opt_.height, title.c_str(), nullptr, nullptr);
    if (!window_) {
        std::fprintf(stderr, "view: cannot create an OpenGL 3.3 core window\n");
        glfwTerminate();
        return false;
    }
    glfwMakeContextCurrent(window_);
    glfwSwapInterval(1);
    GlInfo info;
    std::string error;
    if (!loadGl(glfwGetProcAddress, &info, &error)) {
        std::fprintf(stderr, "view: %s\n", error.c_str());
        glfwDestroyWindow(window_);
        glfwTerminate();
        return false;
    }
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini in the student's folder
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForOpenGL(window_, true);
    ImGui_ImplOpenGL3_Init("#version 150");
    return true;
}

void Viewer::closeWindow() {
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    glfwDestroyWindow(window_);
    glfwTerminate();
}

// A look at the student's folder, at most every 20 ms: a saved file renders the scene and grades
// the lab again.
void Viewer::pollFolder(Clock::time_point now) {
    if (now - last_poll_ > std::chrono::milliseconds(20)) {
        last_poll_ = now;
        if (watch_->poll()) {
            ++generation_;
            std::string names;
            for (const std::string& f : watch_->changedFiles()) names += (names.empty() ? "" : ", ") + f;
            std::printf("view: %s changed; rendering again\n", names.c_str());
            std::fflush(stdout);
            const std::int64_t mtime = watch_->changedMtimeNs();
            requestStudent(mtime > 0 ? mtime : nowNs());
            requestGrade();
        }
    }
}

int Viewer::run() {
    for (std::size_t i = 0; i < spec_.scenes.size(); ++i)
        if (spec_.scenes[i].name == opt_.scene) scene_ = static_cast<int>(i);
    mode_ = parseMode(opt_.view_mode);
    selected_ = opt_.image;
    orbit_ = opt_.orbit;
    if (!openWindow()) return 2;
    {
        queue_ = std::make_unique<RenderQueue>(service_, [] { glfwPostEmptyEvent(); });
        worker_ = std::make_unique<Worker>();
        watch_ = std::make_unique<FolderWatch>((fs::path(opt_.submission_root) / spec_.id).string());
        std::printf("view: %s from %s; save a file there and the picture follows\n", spec_.id.c_str(),
                    (fs::path(opt_.submission_root) / spec_.id).string().c_str());
        std::fflush(stdout);
        requestStudent(0);
        requestGrade();
        setDebug(opt_.debug_view);
        int frames_after_first = 0;
        std::vector<double> frame_ms;
        bool screenshot_due = false;
        while (!glfwWindowShouldClose(window_)) {
            // Wait for input, a finished render, or the next look at the files.
            glfwWaitEventsTimeout(0.02);
            const auto t0 = Clock::now();
            pollFolder(t0);
            takeResults();
            if (dirty_) refreshShown();
            if (judge_dirty_) {
                judge_dirty_ = false;
                judgeScene();
            }
            takeAnalyses();

            ImGui_ImplOpenGL3_NewFrame();
            ImGui_ImplGlfw_NewFrame();
            ImGui::NewFrame();
            handleKeys();
            layout();
            ImGui::Render();
            if (dirty_) refreshShown();  // a click this frame shows next frame
            int fw = 0, fh = 0;
            glfwGetFramebufferSize(window_, &fw, &fh);
            glViewport(0, 0, fw, fh);
            glClearColor(0.1f, 0.1f, 0.12f, 1.0f);
            glClear(GL_COLOR_BUFFER_BIT);
            ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());

            // Scripts want both pictures, judged, and the grade: count frames once all are in.
            const bool settled = got_first_result_ && (opt_.reference_root.empty() || reference_) &&
                                 !analysing() && !grading() && debugSettled();
            if (settled) ++frames_after_first;
            const bool done_frames = opt_.frames > 0 && frames_after_first >= opt_.frames;
            const bool done_reloads =
                opt_.exit_after_reloads > 0 && reloads_shown_ >= opt_.exit_after_reloads && settled;
            // The picture of a reload reaches the screen in the frame after it arrived.
            if (screenshot_due || done_frames) {
                if (!opt_.screenshot.empty() || !opt_.screenshot_window.empty())
                    saveScreenshots(opt_.screenshot, opt_.screenshot_window);
                if (!opt_.panel_text.empty()) savePanelText(opt_.panel_text);
                glfwSetWindowShouldClose(window_, GLFW_TRUE);
            }
            if (done_reloads) screenshot_due = true;
            glfwSwapBuffers(window_);
            const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
            frame_ms.push_back(ms);
        }
        printFrameTimes(frame_ms);
        service_->shutdown();
        queue_.reset();
        worker_.reset();
    }
    closeWindow();
    return 0;
}

}  // namespace detail

int runViewer(const ViewerOptions& options) {
    if (options.spec.scenes.empty()) {
        std::fprintf(stderr, "view: %s has no scenes to show\n", options.spec.id.c_str());
        return 2;
    }
    // The render server forks before the window opens any context or thread.
    std::string error;
    std::unique_ptr<RenderService> service = RenderService::start(options.spec, options.backend, &error);
    if (!service) {
        std::fprintf(stderr, "view: %s\n", error.c_str());
        return 2;
    }
    detail::Viewer viewer(options, service.get());
    return viewer.run();
}

}  // namespace shaderlab::viewer
