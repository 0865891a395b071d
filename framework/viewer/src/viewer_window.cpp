// The student's window; see viewer.h. One main loop in the style of Dear ImGui's own examples:
// poll the folder, take finished renders, handle keys, lay out the panels, draw, swap. Every
// picture comes from RenderService (the grader's renderer in a child process); every number from
// grader::judgeImage with the lab's thresholds.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <sstream>
#include <thread>
#include <vector>

#include "shaderlab/gl/gl.h"
// glad above provides the GL declarations; GLFW must not include its own.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include "grader/metrics/heatmap.h"
#include "grader/reports/report.h"
#include "grader/reports/report_images.h"
#include "grader/metrics/scoring.h"
#include "shaderlab/grading/grading.h"
#include "shaderlab/live/file_watch.h"
#include "shaderlab/live/render_service.h"
#include "shaderlab/viewer/viewer.h"
#include "viewer_jobs.h"

namespace fs = std::filesystem;

namespace shaderlab::viewer {

namespace {

using Clock = std::chrono::steady_clock;

enum class ViewMode { Student, Reference, Diff, Split };

ViewMode parseMode(const std::string& s) {
    if (s == "reference") return ViewMode::Reference;
    if (s == "diff") return ViewMode::Diff;
    if (s == "split") return ViewMode::Split;
    return ViewMode::Student;
}

std::int64_t nowNs() {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(
               std::chrono::system_clock::now().time_since_epoch())
        .count();
}

bool sameOrbit(const CameraOrbit& a, const CameraOrbit& b) {
    return a.yaw_deg == b.yaw_deg && a.pitch_deg == b.pitch_deg && a.zoom == b.zoom;
}

// ---------------------------------------------------------------------------------------------

// A picture on the GPU as the window shows it: clamped to 0..1, 8 bits, NaN and Inf in
// magenta as in the reports, alpha ignored (an image's alpha is coverage, not transparency).
class Texture {
  public:
    ~Texture() {
        if (id_) glDeleteTextures(1, &id_);
    }
    void upload(const grader::Image& source) {
        const grader::Image img = grader::markNonFinite(source);
        std::vector<unsigned char> rgba(static_cast<std::size_t>(img.width) * img.height * 4, 255);
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x)
                for (int c = 0; c < 3; ++c) {
                    const float v = img.at(x, y, img.channels >= 3 ? c : 0);
                    rgba[(static_cast<std::size_t>(y) * img.width + x) * 4 + c] =
                        static_cast<unsigned char>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
                }
        if (!id_) glGenTextures(1, &id_);
        glBindTexture(GL_TEXTURE_2D, id_);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, img.width, img.height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                     rgba.data());
        glBindTexture(GL_TEXTURE_2D, 0);
        width_ = img.width;
        height_ = img.height;
    }
    ImTextureID id() const { return reinterpret_cast<ImTextureID>(static_cast<std::intptr_t>(id_)); }
    int width() const { return width_; }
    int height() const { return height_; }

  private:
    GLuint id_ = 0;
    int width_ = 0, height_ = 0;
};

std::string formatValue(float v) {
    if (std::isnan(v)) return "NaN";
    if (std::isinf(v)) return v > 0 ? "+Inf" : "-Inf";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4f", v);
    return buf;
}

std::string pixelText(const grader::Image& img, int x, int y) {
    if (img.empty() || x < 0 || y < 0 || x >= img.width || y >= img.height) return "-";
    std::string out;
    for (int c = 0; c < img.channels; ++c) out += (c ? " " : "") + formatValue(img.at(x, y, c));
    return out;
}

std::string formatPsnr(double v) {
    if (std::isinf(v)) return "identical";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.1f dB", v);
    return buf;
}

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

// Room at the bottom of the controls for the list of keys.
constexpr float kKeysHeight = 172.0f;

std::string imageKey(const PassImage& p) { return p.pass + "." + p.attachment; }

class Viewer {
  public:
    Viewer(const ViewerOptions& options, RenderService* service)
        : opt_(options), spec_(options.spec), service_(service) {}
    int run();

  private:
    bool openWindow();
    void closeWindow();
    void requestStudent(std::int64_t save_ns);
    void requestReference();
    void takeResults();
    void onStudent(const Finished& f);
    void handleKeys();
    void layout();
    void drawControls(float width, float height);
    void drawPicture(float x, float width, float height);
    void refreshShown();
    void judgeScene();
    void saveScreenshots(const std::string& view_path, const std::string& window_path);
    std::string changeScene(int delta);
    std::string sceneName() const { return spec_.scenes[static_cast<std::size_t>(scene_)].name; }
    const std::vector<PassImage>* studentPasses() const;
    const std::vector<PassImage>* referencePasses() const;
    std::shared_ptr<const void> referenceOwner() const;
    void takeAnalyses();
    bool analysing() const { return shown_pending_ || scene_pending_; }
    std::string timeoutCulprit(const IsolatedRender& r) const;

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

    std::shared_ptr<const IsolatedRender> reference_;
    std::string reference_scene_;
    CameraOrbit reference_orbit_;
    std::string reference_error_;
    std::map<std::string, std::shared_ptr<const std::vector<PassImage>>> goldens_;  // by scene
    std::map<std::string, std::string> golden_errors_;
    std::map<std::string, grader::Image> files_;  // input files, by path

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

const std::vector<PassImage>* Viewer::studentPasses() const {
    if (!student_ || student_->render.scenes.empty()) return nullptr;
    return &student_->render.scenes[0].passes;
}

// The reference for the picture on screen: the reference solution rendered for the same scene
// and camera, or (graded view only) the stored goldens.
const std::vector<PassImage>* Viewer::referencePasses() const {
    if (!student_) return nullptr;
    if (!opt_.reference_root.empty()) {
        if (!reference_ || reference_->status != IsolatedStatus::Ok || reference_->render.scenes.empty() ||
            reference_scene_ != student_scene_ || !sameOrbit(reference_orbit_, student_orbit_))
            return nullptr;
        return &reference_->render.scenes[0].passes;
    }
    if (student_orbit_.any()) return nullptr;
    const auto it = goldens_.find(student_scene_);
    return it == goldens_.end() ? nullptr : it->second.get();
}

// What keeps referencePasses() alive while the worker judges with it.
std::shared_ptr<const void> Viewer::referenceOwner() const {
    if (!opt_.reference_root.empty()) return reference_;
    const auto it = goldens_.find(student_scene_);
    return it == goldens_.end() ? nullptr : it->second;
}

std::string Viewer::timeoutCulprit(const IsolatedRender& r) const {
    std::istringstream in(r.last_event);
    std::string kind, a, b;
    in >> kind >> a >> b;
    if (kind == "compile") return a + " / " + b;
    if (kind == "pass") {
        if (const PassSpec* p = spec_.findPass(b))
            return p->program.fragment + " (pass '" + b + "', with " + p->program.vertex + ")";
        return "pass '" + b + "'";
    }
    return "your shaders";
}

void Viewer::requestStudent(std::int64_t save_ns) {
    Job job;
    job.kind = kStudent;
    job.request.shader_dir = (fs::path(opt_.submission_root) / spec_.id).string();
    job.request.containment_root = opt_.submission_root;
    job.request.scene = sceneName();
    job.request.orbit = orbit_;
    job.request.timeout_s = opt_.timeout_s;
    job.generation = generation_;
    job.save_ns = save_ns;
    queue_->submit(std::move(job));
    requestReference();
}

void Viewer::requestReference() {
    if (opt_.reference_root.empty()) {
        const std::string scene = sceneName();
        if (!goldens_.count(scene) && !golden_errors_.count(scene)) {
            std::vector<PassImage> images;
            std::string error;
            if (loadGoldenScene(spec_, spec_.lab_dir, scene, &images, &error))
                goldens_[scene] = std::make_shared<const std::vector<PassImage>>(std::move(images));
            else
                golden_errors_[scene] = error;
        }
        return;
    }
    if (reference_ && reference_scene_ == sceneName() && sameOrbit(reference_orbit_, orbit_)) return;
    Job job;
    job.kind = kReference;
    job.request.shader_dir = (fs::path(opt_.reference_root) / spec_.id).string();
    job.request.containment_root = opt_.reference_root;
    job.request.scene = sceneName();
    job.request.orbit = orbit_;
    job.request.timeout_s = std::max(opt_.timeout_s, 30.0);
    queue_->submit(std::move(job));
}

void Viewer::onStudent(const Finished& f) {
    const IsolatedRender& r = f.result;
    got_first_result_ = true;
    const bool fresh_reload = f.job.save_ns != 0;
    if (r.status == IsolatedStatus::Ok && !r.render.scenes.empty()) {
        student_ = std::make_shared<const IsolatedRender>(r);
        student_scene_ = f.job.request.scene;
        student_orbit_ = f.job.request.orbit;
        error_title_.clear();
        error_text_.clear();
        last_printed_error_.clear();
        dirty_ = judge_dirty_ = true;
        char line[256];
        std::snprintf(line, sizeof line, "scene %s rendered in %.0f ms", student_scene_.c_str(), r.wall_ms);
        status_line_ = line;
        if (fresh_reload) {
            const double latency_ms = static_cast<double>(nowNs() - f.job.save_ns) / 1e6;
            std::printf("view: %s; on screen %.0f ms after the save\n", line, latency_ms);
        } else {
            std::printf("view: %s\n", line);
        }
    } else {
        std::string title, text;
        switch (r.status) {
            case IsolatedStatus::CompileError:
            case IsolatedStatus::LinkError:
                title = r.status == IsolatedStatus::CompileError ? "Your shader does not compile"
                                                                 : "Your shaders do not link";
                break;
            case IsolatedStatus::Timeout:
                title = "Timed out: " + timeoutCulprit(r);
                break;
            case IsolatedStatus::Missing:
                title = "A file is missing";
                break;
            default:
                title = "The render failed (" + std::string(isolatedStatusName(r.status)) + ")";
        }
        for (const Diagnostic& d : r.render.diagnostics)
            if (d.severity == "error" || r.status == IsolatedStatus::CompileError ||
                r.status == IsolatedStatus::LinkError)
                text += grader::formatDiagnostic(toReportDiagnostic(d)) + "\n";
        if (text.empty() || r.status == IsolatedStatus::Timeout) text = r.message + "\n" + text;
        error_title_ = title + (student_ ? " - the last good picture is shown" : "");
        error_text_ = text;
        const std::string printed = title + "\n" + text;
        if (printed != last_printed_error_) {
            std::printf("view: %s\n%s", title.c_str(), text.c_str());
            last_printed_error_ = printed;
        }
        status_line_ = title;
    }
    if (fresh_reload) ++reloads_shown_;
    std::fflush(stdout);
}

void Viewer::takeResults() {
    for (Finished& f : queue_->take()) {
        if (f.job.kind == kStudent) {
            onStudent(f);
        } else {
            reference_error_.clear();
            if (f.result.status != IsolatedStatus::Ok)
                reference_error_ = "the reference solution did not render: " + f.result.message;
            reference_ = std::make_shared<const IsolatedRender>(std::move(f.result));
            reference_scene_ = f.job.request.scene;
            reference_orbit_ = f.job.request.orbit;
            dirty_ = judge_dirty_ = true;
        }
    }
}

std::string Viewer::changeScene(int delta) {
    const int n = static_cast<int>(spec_.scenes.size());
    scene_ = ((scene_ + delta) % n + n) % n;
    requestStudent(0);
    return sceneName();
}

// Picks the image on screen from the selection and works out its texture, verdict and diff.
void Viewer::refreshShown() {
    dirty_ = false;
    shown_ = Shown();
    shown_verdict_.reset();
    ++shown_seq_;  // whatever the worker is judging is for another picture now
    shown_pending_ = false;
    const std::vector<PassImage>* mine = studentPasses();
    const std::vector<PassImage>* theirs = referencePasses();
    if (!mine || mine->empty()) {
        shown_.note = "no picture yet";
        return;
    }
    // The selected pass output, else the final graded image.
    std::size_t index = mine->size() - 1;
    for (std::size_t i = 0; i < mine->size(); ++i)
        if ((*mine)[i].graded) index = i;
    for (std::size_t i = 0; i < mine->size(); ++i)
        if (!selected_.empty() && imageKey((*mine)[i]) == selected_) index = i;
    const PassImage& out = (*mine)[index];
    const PassSpec* pass = spec_.findPass(out.pass);
    auto findIn = [](const std::vector<PassImage>* list, const std::string& key) -> const PassImage* {
        if (!list) return nullptr;
        for (const PassImage& p : *list)
            if (imageKey(p) == key) return &p;
        return nullptr;
    };
    if (input_ < 0 || !pass || input_ >= static_cast<int>(pass->inputs.size())) {
        input_ = -1;
        shown_.label = "pass " + out.pass + " -> " + out.target + "." + out.attachment;
        shown_.student_pass = &out;
        shown_.reference_pass = findIn(theirs, imageKey(out));
        shown_.pass = pass;
    } else {
        const PassInput& in = pass->inputs[static_cast<std::size_t>(input_)];
        shown_.label = "pass " + out.pass + " reads " + in.sampler;
        if (in.source == InputSource::Target) {
            // What the pass read: the latest image of that target drawn before it, or (a
            // repeated pass reading its own group's output) the latest of all.
            auto latest = [&](const std::vector<PassImage>* list, std::size_t before) -> const PassImage* {
                if (!list) return nullptr;
                const PassImage* found = nullptr;
                for (std::size_t i = 0; i < list->size(); ++i) {
                    const PassImage& p = (*list)[i];
                    const bool same =
                        p.target == in.target && (in.attachment.empty() || p.attachment == in.attachment);
                    if (same && (i < before || !found)) found = &p;
                }
                return found;
            };
            shown_.student_pass = latest(mine, index);
            const PassImage* mine_input = shown_.student_pass;
            shown_.reference_pass = mine_input ? findIn(theirs, imageKey(*mine_input)) : nullptr;
            shown_.label += " <- target " + in.target + (in.attachment.empty() ? "" : "." + in.attachment);
            if (!mine_input) shown_.note = "the render did not read back target " + in.target;
        } else if (in.source == InputSource::File) {
            const std::string path = labFilePath(spec_, in.file);
            auto it = files_.find(path);
            if (it == files_.end()) {
                grader::Image img;
                std::string err;
                const bool hdr = fs::path(path).extension() == ".hdr";
                if (!(hdr ? grader::readHdr(path, &img, &err) : grader::readPng(path, &img, &err)))
                    img = grader::Image();
                it = files_.emplace(path, std::move(img)).first;
            }
            shown_.label += " <- file " + in.file;
            if (it->second.empty())
                shown_.note = "cannot show " + in.file;
            else
                shown_.student = shown_.reference = &it->second;
        } else {
            shown_.label +=
                in.source == InputSource::Cube ? " <- cube map" : " <- generated " + in.generated.pattern;
            shown_.note = "a texture the framework makes or a cube map: nothing to show here";
        }
    }
    if (shown_.student_pass) shown_.student = &shown_.student_pass->color;
    if (shown_.reference_pass) shown_.reference = &shown_.reference_pass->color;
    if (shown_.student) tex_student_.upload(*shown_.student);
    if (shown_.reference) tex_reference_.upload(*shown_.reference);
    if (shown_.student && shown_.reference && shown_.student->width == shown_.reference->width &&
        shown_.student->height == shown_.reference->height && shown_.student != shown_.reference) {
        const PassSpec* judge_pass =
            shown_.student_pass ? spec_.findPass(shown_.student_pass->pass) : nullptr;
        const grader::Thresholds t =
            judge_pass ? imageThresholds(spec_, student_scene_, *judge_pass) : grader::Thresholds();
        const grader::ImageRange range = judge_pass && judge_pass->compare == CompareMode::Hdr
                                             ? grader::ImageRange::Hdr
                                             : grader::ImageRange::Display;
        // The shared pointers keep the images alive for the worker (input files live in files_,
        // which only grows).
        const std::uint64_t seq = shown_seq_;
        shown_pending_ = true;
        worker_->submit(0, [this, seq, t, range, mine = student_, theirs = referenceOwner(),
                            shown = shown_]() {
            static const std::vector<std::uint8_t> none;
            ShownAnalysis a;
            a.seq = seq;
            a.verdict = grader::judgeImage(
                *shown.reference, shown.reference_pass ? shown.reference_pass->coverage : none,
                *shown.student, shown.student_pass ? shown.student_pass->coverage : none, t, range);
            grader::HeatmapConfig hc;
            hc.outline = a.verdict.mismatches.empty() ? nullptr : &a.verdict.mismatches;
            a.heat = grader::diffHeatmap(a.verdict.flip_map, shown.student->width, shown.student->height, hc);
            std::lock_guard<std::mutex> lock(analysis_m_);
            shown_ready_ = std::move(a);
            glfwPostEmptyEvent();
        });
    }
}

// The verdict grading would give this scene: every graded image against its reference.
void Viewer::judgeScene() {
    judged_.clear();
    judged_graded_view_ = !student_orbit_.any();
    const std::uint64_t seq = ++scene_seq_;
    scene_pending_ = false;
    const std::vector<PassImage>* mine = studentPasses();
    const std::vector<PassImage>* theirs = referencePasses();
    if (!mine || !theirs) return;
    scene_pending_ = true;
    worker_->submit(1, [this, seq, mine, theirs, keep_mine = student_, keep_theirs = referenceOwner(),
                        scene = student_scene_]() {
        SceneAnalysis a;
        a.seq = seq;
        for (const PassImage& p : *mine) {
            if (!p.graded) continue;
            const PassSpec* pass = spec_.findPass(p.pass);
            const PassImage* ref = nullptr;
            for (const PassImage& q : *theirs)
                if (imageKey(q) == imageKey(p)) ref = &q;
            if (!pass || !ref || ref->color.width != p.color.width || ref->color.height != p.color.height)
                continue;
            Judged j;
            j.label = imageKey(p);
            j.verdict = grader::judgeImage(
                ref->color, ref->coverage, p.color, p.coverage, imageThresholds(spec_, scene, *pass),
                pass->compare == CompareMode::Hdr ? grader::ImageRange::Hdr : grader::ImageRange::Display);
            a.judged.push_back(std::move(j));
        }
        std::lock_guard<std::mutex> lock(analysis_m_);
        scene_ready_ = std::move(a);
        glfwPostEmptyEvent();
    });
}

// Takes what the worker judged, when it is about the pictures on screen now.
void Viewer::takeAnalyses() {
    std::optional<ShownAnalysis> shown;
    std::optional<SceneAnalysis> scene;
    {
        std::lock_guard<std::mutex> lock(analysis_m_);
        shown.swap(shown_ready_);
        scene.swap(scene_ready_);
    }
    if (shown && shown->seq == shown_seq_) {
        shown_pending_ = false;
        tex_diff_.upload(shown->heat);
        shown_verdict_ = std::move(shown->verdict);
    }
    if (scene && scene->seq == scene_seq_) {
        scene_pending_ = false;
        judged_ = std::move(scene->judged);
        if (judged_.empty() || !judged_graded_view_) return;
        bool passed = true;
        for (const Judged& j : judged_) passed = passed && j.verdict.passed;
        std::printf("view: scene %s %s\n", student_scene_.c_str(), passed ? "passes" : "FAILS");
        for (const Judged& j : judged_)
            for (const std::string& reason : j.verdict.reasons)
                std::printf("      %s: %s\n", j.label.c_str(), reason.c_str());
        std::fflush(stdout);
    }
}

void Viewer::handleKeys() {
    ImGuiIO& io = ImGui::GetIO();
    if (io.WantTextInput) return;
    if (ImGui::IsKeyPressed(GLFW_KEY_1)) mode_ = ViewMode::Student;
    if (ImGui::IsKeyPressed(GLFW_KEY_2)) mode_ = ViewMode::Reference;
    if (ImGui::IsKeyPressed(GLFW_KEY_3)) mode_ = ViewMode::Diff;
    if (ImGui::IsKeyPressed(GLFW_KEY_4)) mode_ = ViewMode::Split;
    if (ImGui::IsKeyPressed(GLFW_KEY_RIGHT)) changeScene(1);
    if (ImGui::IsKeyPressed(GLFW_KEY_LEFT)) changeScene(-1);
    const std::vector<PassImage>* mine = studentPasses();
    if (mine && !mine->empty() && (ImGui::IsKeyPressed(GLFW_KEY_DOWN) || ImGui::IsKeyPressed(GLFW_KEY_UP))) {
        int index = -1;
        for (std::size_t i = 0; i < mine->size(); ++i)
            if (shown_.student_pass == &(*mine)[i] && input_ < 0) index = static_cast<int>(i);
        if (index < 0) {
            for (std::size_t i = 0; i < mine->size(); ++i)
                if (imageKey((*mine)[i]) == selected_) index = static_cast<int>(i);
        }
        if (index < 0) index = static_cast<int>(mine->size()) - 1;
        index += ImGui::IsKeyPressed(GLFW_KEY_DOWN) ? 1 : -1;
        index = std::clamp(index, 0, static_cast<int>(mine->size()) - 1);
        selected_ = imageKey((*mine)[static_cast<std::size_t>(index)]);
        input_ = -1;
        dirty_ = scroll_to_shown_ = true;
    }
    if (ImGui::IsKeyPressed(GLFW_KEY_TAB) && shown_.student_pass) {
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
    if (ImGui::IsKeyPressed(GLFW_KEY_R) && orbit_.any()) {
        orbit_ = CameraOrbit();
        requestStudent(0);
    }
    if (ImGui::IsKeyPressed(GLFW_KEY_LEFT_BRACKET)) split_ = std::max(0.0f, split_ - 0.05f);
    if (ImGui::IsKeyPressed(GLFW_KEY_RIGHT_BRACKET)) split_ = std::min(1.0f, split_ + 0.05f);
    if (ImGui::IsKeyPressed(GLFW_KEY_F5)) requestStudent(0);
    if (ImGui::IsKeyPressed(GLFW_KEY_S, false)) {
        const std::string stem =
            "shaderlab-" + spec_.id + "-" + sceneName() + "-" + std::to_string(++screenshot_count_);
        saveScreenshots(stem + ".png", stem + "-window.png");
    }
    if (ImGui::IsKeyPressed(GLFW_KEY_ESCAPE) || ImGui::IsKeyPressed(GLFW_KEY_Q))
        glfwSetWindowShouldClose(window_, GLFW_TRUE);
}

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
    if (mine) {
        ImGui::Separator();
        ImGui::Text("images of this scene [up/down]");
        ImGui::BeginChild("passes",
                          ImVec2(0, std::min(150.0f, 20.0f * static_cast<float>(mine->size()) + 8.0f)), true);
        for (const PassImage& p : *mine) {
            const std::string label =
                (p.graded ? "* " : "  ") + p.pass + " -> " + p.target + "." + p.attachment;
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
        for (const PassImage& p : *mine)
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

    // The verdict grading would give.
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
    ImGui::End();
}

void Viewer::drawPicture(float x, float width, float height) {
    ImGui::SetNextWindowPos(ImVec2(x, 0));
    ImGui::SetNextWindowSize(ImVec2(width, height));
    ImGui::Begin("picture", nullptr,
                 ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoMove |
                     ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoBringToFrontOnFocus |
                     ImGuiWindowFlags_NoScrollWithMouse);
    double busy_s = 0.0;
    const std::string busy = queue_->running(&busy_s);
    if (!busy.empty())
        ImGui::Text("rendering %s (%.1f s)", busy.c_str(), busy_s);
    else
        ImGui::TextDisabled("%s", status_line_.empty() ? "starting" : status_line_.c_str());
    ImGui::Text("%s", shown_.label.c_str());

    const float error_h = error_title_.empty() ? 0.0f : std::min(200.0f, height * 0.35f);
    const float inspector_h = 80.0f;
    const ImVec2 avail = ImGui::GetContentRegionAvail();
    const float area_w = avail.x, area_h = avail.y - error_h - inspector_h;

    const bool want_reference = mode_ == ViewMode::Reference;
    const Texture* tex = nullptr;
    std::string missing;
    if (mode_ == ViewMode::Student || mode_ == ViewMode::Split) {
        tex = shown_.student ? &tex_student_ : nullptr;
        if (!tex) missing = shown_.note.empty() ? "no picture yet" : shown_.note;
        if (mode_ == ViewMode::Split && !shown_.reference) missing = "no reference to split against";
    } else if (want_reference) {
        tex = shown_.reference ? &tex_reference_ : nullptr;
        if (!tex)
            missing = "no reference for this image" + std::string(orbit_.any() ? " in a turned view" : "");
    } else {
        tex = shown_verdict_ ? &tex_diff_ : nullptr;
        if (!tex) missing = shown_pending_ ? "comparing..." : "no diff: it needs both pictures";
    }
    if (!missing.empty() && !(mode_ == ViewMode::Split && tex)) {
        ImGui::Dummy(ImVec2(area_w, area_h * 0.4f));
        ImGui::TextWrapped("%s", missing.c_str());
        ImGui::Dummy(ImVec2(area_w, area_h * 0.6f - ImGui::GetTextLineHeight()));
        image_w_ = 0;
    } else {
        const float w = static_cast<float>(tex->width()), h = static_cast<float>(tex->height());
        float scale = std::min(area_w / w, area_h / h);
        scale = scale >= 1.0f ? std::floor(scale) : scale;
        const ImVec2 size(w * scale, h * scale);
        const ImVec2 p0 = ImGui::GetCursorScreenPos();
        ImGui::InvisibleButton("image", size);
        ImDrawList* dl = ImGui::GetWindowDrawList();
        if (mode_ == ViewMode::Split && shown_.reference) {
            const float sx = p0.x + size.x * split_;
            dl->AddImage(tex_student_.id(), p0, ImVec2(sx, p0.y + size.y), ImVec2(0, 0), ImVec2(split_, 1));
            dl->AddImage(tex_reference_.id(), ImVec2(sx, p0.y), ImVec2(p0.x + size.x, p0.y + size.y),
                         ImVec2(split_, 0), ImVec2(1, 1));
            dl->AddLine(ImVec2(sx, p0.y), ImVec2(sx, p0.y + size.y), IM_COL32(255, 255, 0, 255), 1.0f);
            dl->AddText(ImVec2(p0.x + 4, p0.y + 4), IM_COL32(255, 255, 0, 255), "student");
            dl->AddText(ImVec2(p0.x + size.x - 68, p0.y + 4), IM_COL32(255, 255, 0, 255), "reference");
        } else {
            dl->AddImage(tex->id(), p0, ImVec2(p0.x + size.x, p0.y + size.y));
        }
        image_min_ = p0;
        image_scale_ = scale;
        image_w_ = tex->width();
        image_h_ = tex->height();
        // Orbit and zoom: drag and wheel over the picture.
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

    // Pixel inspector.
    ImGui::Separator();
    const ImVec2 mouse = ImGui::GetIO().MousePos;
    if (image_w_ > 0 && shown_.student) {
        const int px = static_cast<int>(std::floor((mouse.x - image_min_.x) / image_scale_));
        const int py = static_cast<int>(std::floor((mouse.y - image_min_.y) / image_scale_));
        if (px >= 0 && py >= 0 && px < image_w_ && py < image_h_) {
            ImGui::Text("pixel %d, %d", px, py);
            ImGui::Text("student   %s", pixelText(*shown_.student, px, py).c_str());
            ImGui::Text("reference %s",
                        shown_.reference ? pixelText(*shown_.reference, px, py).c_str() : "(none)");
            if (shown_verdict_ && !shown_verdict_->flip_map.empty())
                ImGui::Text(
                    "FLIP error %s",
                    formatValue(shown_verdict_->flip_map[static_cast<std::size_t>(py) * image_w_ + px])
                        .c_str());
        } else {
            ImGui::TextDisabled("point at the picture to read its pixels");
        }
    }
    if (shown_verdict_) {
        const grader::MetricSet& m = shown_verdict_->covered;
        ImGui::TextDisabled("this image: PSNR %s  SSIM %.4f  FLIP %.4f  mismatch %.2f%%",
                            formatPsnr(m.psnr_db).c_str(), m.ssim, m.flip_mean, 100.0 * m.mismatch_fraction);
    }

    if (!error_title_.empty()) {
        ImGui::SetCursorPosY(height - error_h - 8.0f);
        ImGui::PushStyleColor(ImGuiCol_ChildBg, ImVec4(0.25f, 0.05f, 0.05f, 1.0f));
        ImGui::BeginChild("errors", ImVec2(0, error_h), true);
        ImGui::TextColored(ImVec4(1, 0.45f, 0.4f, 1), "%s", error_title_.c_str());
        // Source lines and carets keep their columns; the explanations ("= ...") wrap.
        std::istringstream lines(error_text_);
        for (std::string line; std::getline(lines, line);) {
            const std::size_t first = line.find_first_not_of(' ');
            if (first != std::string::npos && line.compare(first, 2, "= ") == 0)
                ImGui::TextWrapped("%s", line.c_str());
            else
                ImGui::TextUnformatted(line.c_str());
        }
        ImGui::EndChild();
        ImGui::PopStyleColor();
    }
    ImGui::End();
}

void Viewer::layout() {
    int w = 0, h = 0;
    glfwGetWindowSize(window_, &w, &h);
    const float panel = 340.0f;
    drawControls(panel, static_cast<float>(h));
    drawPicture(panel, static_cast<float>(w) - panel, static_cast<float>(h));
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
        int frames_after_first = 0;
        std::vector<double> frame_ms;
        bool screenshot_due = false;
        while (!glfwWindowShouldClose(window_)) {
            // Wait for input, a finished render, or the next look at the files.
            glfwWaitEventsTimeout(0.02);
            const auto t0 = Clock::now();
            if (t0 - last_poll_ > std::chrono::milliseconds(20)) {
                last_poll_ = t0;
                if (watch_->poll()) {
                    ++generation_;
                    std::string names;
                    for (const std::string& f : watch_->changedFiles())
                        names += (names.empty() ? "" : ", ") + f;
                    std::printf("view: %s changed; rendering again\n", names.c_str());
                    std::fflush(stdout);
                    const std::int64_t mtime = watch_->changedMtimeNs();
                    requestStudent(mtime > 0 ? mtime : nowNs());
                }
            }
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

            // Scripts want both pictures: count frames once the reference is in too.
            // and judged.
            const bool settled =
                got_first_result_ && (opt_.reference_root.empty() || reference_) && !analysing();
            if (settled) ++frames_after_first;
            const bool done_frames = opt_.frames > 0 && frames_after_first >= opt_.frames;
            const bool done_reloads =
                opt_.exit_after_reloads > 0 && reloads_shown_ >= opt_.exit_after_reloads && settled;
            // The picture of a reload reaches the screen in the frame after it arrived.
            if (screenshot_due || done_frames) {
                if (!opt_.screenshot.empty() || !opt_.screenshot_window.empty())
                    saveScreenshots(opt_.screenshot, opt_.screenshot_window);
                glfwSetWindowShouldClose(window_, GLFW_TRUE);
            }
            if (done_reloads) screenshot_due = true;
            glfwSwapBuffers(window_);
            const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
            frame_ms.push_back(ms);
        }
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
        service_->shutdown();
        queue_.reset();
        worker_.reset();
    }
    closeWindow();
    return 0;
}

}  // namespace

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
    Viewer viewer(options, service.get());
    return viewer.run();
}

}  // namespace shaderlab::viewer
