// The student's window as one class, Viewer, whose parts live in files of their own: the main
// loop and the window (viewer_window.cpp), renders and grades asked and taken
// (viewer_renders.cpp), the image on screen and its judgement (viewer_shown.cpp), keys and mouse
// (viewer_input.cpp), the panels of controls, verdict and grade (viewer_panels.cpp), the picture
// (viewer_picture.cpp) and the debug view of the scene's vertex data (viewer_debug.cpp).
// Private to the viewer; runViewer (viewer.h) is its only way in.
#pragma once

#include <imgui.h>

#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "grader/metrics/scoring.h"
#include "shaderlab/gl/gl.h"
#include "shaderlab/live/file_watch.h"
#include "shaderlab/live/render_service.h"
#include "shaderlab/viewer/viewer.h"
#include "viewer_grade_lines.h"
#include "viewer_jobs.h"

struct GLFWwindow;

namespace shaderlab::viewer::detail {

using Clock = std::chrono::steady_clock;

enum class ViewMode { Student, Reference, Diff, Split };

std::int64_t nowNs();

std::string formatPsnr(double v);

inline std::string imageKey(const PassImage& p) { return p.pass + "." + p.attachment; }

// A picture on the GPU as the window shows it: clamped to 0..1, 8 bits, NaN and Inf in
// magenta as in the reports, alpha ignored (an image's alpha is coverage, not transparency).
class Texture {
  public:
    ~Texture();
    void upload(const grader::Image& source);
    ImTextureID id() const { return reinterpret_cast<ImTextureID>(static_cast<std::intptr_t>(id_)); }
    int width() const { return width_; }
    int height() const { return height_; }

  private:
    GLuint id_ = 0;
    int width_ = 0, height_ = 0;
};

// One graded image judged for the verdict panel.
struct Judged {
    std::string label;
    grader::ImageVerdict verdict;
};

// What the window shows: an image of the student's render (a pass's output) or a texture a pass
// reads (another pass's output, or a file of the lab).
struct Shown {
    std::string label;
    const grader::Image* student = nullptr;
    const grader::Image* reference = nullptr;
    const PassImage* student_pass = nullptr;  // for coverage and thresholds
    const PassImage* reference_pass = nullptr;
    const PassSpec* pass = nullptr;  // the pass that made it, when it is a pass output
    std::string note;                // why there is nothing to show
};

class Viewer {
  public:
    Viewer(const ViewerOptions& options, RenderService* service)
        : opt_(options), spec_(options.spec), service_(service) {}
    int run();

  private:
    // viewer_window.cpp
    bool openWindow();
    void closeWindow();
    void pollFolder(Clock::time_point now);
    void layout();
    void saveScreenshots(const std::string& view_path, const std::string& window_path);
    // viewer_renders.cpp
    void requestStudent(std::int64_t save_ns);
    void requestReference();
    void requestGrade();
    void takeResults();
    void onStudent(const Finished& f);
    void onGrade(Finished& f);
    bool grading() const { return !grade_done_ || *grade_done_ != grade_asked_; }
    std::string changeScene(int delta);
    std::string sceneName() const { return spec_.scenes[static_cast<std::size_t>(scene_)].name; }
    const std::vector<PassImage>* studentPasses() const;
    const std::vector<PassImage>* referencePasses() const;
    std::shared_ptr<const void> referenceOwner() const;
    // viewer_shown.cpp
    void refreshShown();
    void showInput(const PassImage& out, const PassSpec& pass, const std::vector<PassImage>* mine,
                   const std::vector<PassImage>* theirs, std::size_t index);
    void judgeShown();
    void judgeScene();
    void takeAnalyses();
    bool analysing() const { return shown_pending_ || scene_pending_; }
    // viewer_input.cpp
    void handleKeys();
    void orbitByMouse();
    // viewer_panels.cpp
    void drawControls(float width, float height);
    void drawResults(float x, float width, float height);
    void drawImageList(const std::vector<PassImage>& mine);
    void drawVerdict(float height);
    void drawGrade();
    void drawKeys();
    void buildGradeLines();
    void savePanelText(const std::string& path) const;
    // viewer_picture.cpp
    void drawPicture(float x, float width, float height);
    void drawImage(float area_w, float area_h);
    void placeImage(const Texture& tex, float area_w, float area_h);
    void drawMissing(const std::string& why, float area_w, float area_h);
    void drawInspector();
    void drawMessages(const std::string& title, const std::string& text, bool error, float top, float h);
    // viewer_debug.cpp
    void setDebug(DebugView view);
    void requestDebug();
    void onDebug(const Finished& f);
    bool debugSettled() const;
    const PassImage* debugImage() const;
    void drawDebugControls();
    void drawDebugLabel();
    void drawDebugImage(float area_w, float area_h);
    void drawDebugInspector(int x, int y);

    ViewerOptions opt_;
    const LabSpec& spec_;
    RenderService* service_;
    GLFWwindow* window_ = nullptr;
    std::unique_ptr<RenderQueue> queue_;
    std::unique_ptr<FolderWatch> watch_;
    Clock::time_point last_poll_{};

    int scene_ = 0;
    CameraOrbit orbit_;
    ViewMode mode_ = ViewMode::Student;
    float split_ = 0.5f;
    std::string selected_;  // imageKey of the selected pass output; empty: the final graded image
    int input_ = -1;        // -1: the pass's output; else the index of the input it reads

    // The last picture that rendered, and what it was rendered for.
    std::shared_ptr<const IsolatedRender> student_;
    std::string student_scene_;
    CameraOrbit student_orbit_;
    std::uint64_t generation_ = 0;  // bumped by each file change
    bool got_first_result_ = false;
    int reloads_shown_ = 0;
    std::string error_title_, error_text_;  // the last failed render (cleared by a good one)
    std::string last_printed_error_;
    // The warnings of the picture on screen (with the lines around each), and the last printed.
    std::string warning_title_, warning_text_, warnings_printed_;

    // The debug view of the vertex data: which one is on (Off: the lab's picture), and the last
    // one drawn, for what.
    DebugView debug_ = DebugView::Off;
    std::shared_ptr<const IsolatedRender> debug_render_;
    DebugView debug_render_view_ = DebugView::Off;
    std::string debug_render_scene_;
    CameraOrbit debug_render_orbit_;
    std::string debug_error_;               // the last debug render that failed (cleared by a good one)
    std::vector<std::string> debug_notes_;  // what it could not show (a mesh without tangents)
    Texture tex_debug_;

    std::shared_ptr<const IsolatedRender> reference_;
    std::string reference_scene_;
    CameraOrbit reference_orbit_;
    std::string reference_error_;
    std::map<std::string, std::shared_ptr<const std::vector<PassImage>>> goldens_;  // by scene
    std::map<std::string, std::string> golden_errors_;
    std::map<std::string, grader::Image> files_;  // input files, by path

    // The lab graded as `check` grades it: the newest grade asked (by the files' version) and
    // the last one that came back.
    std::uint64_t grade_asked_ = 0;
    std::optional<std::uint64_t> grade_done_;
    std::optional<grader::ReportLab> grade_;
    std::string grade_error_;
    std::vector<PanelLine> grade_lines_;  // the goals, failing scenes and hints of grade_

    // Derived, recomputed when `dirty_` is set.
    bool dirty_ = true;
    bool judge_dirty_ = false;     // new pictures: judge the scene again
    bool scroll_to_shown_ = true;  // bring the shown image into the list's view
    Shown shown_;
    Texture tex_student_, tex_reference_, tex_diff_;
    std::optional<grader::ImageVerdict> shown_verdict_;
    std::vector<Judged> judged_;  // graded images of the scene (graded view only)
    bool judged_graded_view_ = false;

    // Judgements made on the worker: the newest request's number, and what came back.
    struct ShownAnalysis {
        std::uint64_t seq = 0;
        grader::ImageVerdict verdict;
        grader::Image heat;
    };
    struct SceneAnalysis {
        std::uint64_t seq = 0;
        std::vector<Judged> judged;
    };
    std::mutex analysis_m_;
    std::optional<ShownAnalysis> shown_ready_;
    std::optional<SceneAnalysis> scene_ready_;
    std::uint64_t shown_seq_ = 0, scene_seq_ = 0;
    bool shown_pending_ = false, scene_pending_ = false;
    std::unique_ptr<Worker> worker_;  // made in run(), gone before the window

    // Where the picture was drawn last frame (window coordinates), for the inspector and screenshots.
    ImVec2 image_min_{0, 0};
    float image_scale_ = 1.0f;
    int image_w_ = 0, image_h_ = 0;
    std::string status_line_;
    int screenshot_count_ = 0;
};

}  // namespace shaderlab::viewer::detail
