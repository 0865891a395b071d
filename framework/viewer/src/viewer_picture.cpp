// The picture on the right of the window: the image on screen as a texture, in the mode chosen
// (student, reference, diff heat map, split; or a debug view, viewer_debug.cpp), the pixel
// inspector under it and the last failed render's messages. It picks and judges nothing
// (viewer_shown.cpp) and handles no keys.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "grader/reports/report_images.h"
#include "viewer_window.h"

namespace shaderlab::viewer::detail {

namespace {

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

}  // namespace

std::string formatPsnr(double v) {
    if (std::isinf(v)) return "identical";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.1f dB", v);
    return buf;
}

Texture::~Texture() {
    if (id_) glDeleteTextures(1, &id_);
}

void Texture::upload(const grader::Image& source) {
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
        ImGui::Text("%s (%.1f s)", busy.c_str(), busy_s);
    else
        ImGui::TextDisabled("%s", status_line_.empty() ? "starting" : status_line_.c_str());
    if (debug_ != DebugView::Off)
        drawDebugLabel();
    else
        ImGui::Text("%s", shown_.label.c_str());

    // Under the picture: the last failed render's errors, else the warnings of the one on screen.
    const bool error = !error_title_.empty();
    const bool warnings = !error && !warning_text_.empty() && debug_ == DebugView::Off;
    const float message_h = error      ? std::min(240.0f, height * 0.38f)
                            : warnings ? std::min(170.0f, height * 0.26f)
                                       : 0.0f;
    const float inspector_h = 80.0f;
    const ImVec2 avail = ImGui::GetContentRegionAvail();
    const float area_w = avail.x, area_h = avail.y - message_h - inspector_h;

    drawImage(area_w, area_h);
    drawInspector();
    if (error) drawMessages(error_title_, error_text_, true, height - message_h - 8.0f, message_h);
    if (warnings) drawMessages(warning_title_, warning_text_, false, height - message_h - 8.0f, message_h);
    ImGui::End();
}

// The picture in the mode chosen (student, reference, diff heat map, or student and reference
// split), scaled to fit `area_w` x `area_h` (a whole number of screen pixels per image pixel
// when it fits at least once), or why there is none.
void Viewer::drawImage(float area_w, float area_h) {
    if (debug_ != DebugView::Off) return drawDebugImage(area_w, area_h);
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
        drawMissing(missing, area_w, area_h);
        return;
    }
    placeImage(*tex, area_w, area_h);
    if (mode_ == ViewMode::Split && shown_.reference) {
        const ImVec2 p0 = image_min_;
        const ImVec2 size(static_cast<float>(image_w_) * image_scale_,
                          static_cast<float>(image_h_) * image_scale_);
        const float sx = p0.x + size.x * split_;
        ImDrawList* dl = ImGui::GetWindowDrawList();
        dl->AddImage(tex_reference_.id(), ImVec2(sx, p0.y), ImVec2(p0.x + size.x, p0.y + size.y),
                     ImVec2(split_, 0), ImVec2(1, 1));
        dl->AddLine(ImVec2(sx, p0.y), ImVec2(sx, p0.y + size.y), IM_COL32(255, 255, 0, 255), 1.0f);
        dl->AddText(ImVec2(p0.x + 4, p0.y + 4), IM_COL32(255, 255, 0, 255), "student");
        dl->AddText(ImVec2(p0.x + size.x - 68, p0.y + 4), IM_COL32(255, 255, 0, 255), "reference");
    }
}

// `tex` scaled to fit `area_w` x `area_h` (a whole number of screen pixels per image pixel when it
// fits at least once), where the mouse turns the camera; remembered for the inspector and the
// screenshots.
void Viewer::placeImage(const Texture& tex, float area_w, float area_h) {
    const float w = static_cast<float>(tex.width()), h = static_cast<float>(tex.height());
    float scale = std::min(area_w / w, area_h / h);
    scale = scale >= 1.0f ? std::floor(scale) : scale;
    const ImVec2 size(w * scale, h * scale);
    const ImVec2 p0 = ImGui::GetCursorScreenPos();
    ImGui::InvisibleButton("image", size);
    ImGui::GetWindowDrawList()->AddImage(tex.id(), p0, ImVec2(p0.x + size.x, p0.y + size.y));
    image_min_ = p0;
    image_scale_ = scale;
    image_w_ = tex.width();
    image_h_ = tex.height();
    orbitByMouse();
}

// Why there is no picture, in the middle of the area.
void Viewer::drawMissing(const std::string& why, float area_w, float area_h) {
    ImGui::Dummy(ImVec2(area_w, area_h * 0.4f));
    ImGui::TextWrapped("%s", why.c_str());
    ImGui::Dummy(ImVec2(area_w, area_h * 0.6f - ImGui::GetTextLineHeight()));
    image_w_ = 0;
}

// Pixel inspector: the values under the mouse, and the figures of the image on screen.
void Viewer::drawInspector() {
    ImGui::Separator();
    const ImVec2 mouse = ImGui::GetIO().MousePos;
    const int px = static_cast<int>(std::floor((mouse.x - image_min_.x) / image_scale_));
    const int py = static_cast<int>(std::floor((mouse.y - image_min_.y) / image_scale_));
    if (debug_ != DebugView::Off) {
        if (image_w_ > 0) drawDebugInspector(px, py);
        return;
    }
    if (image_w_ > 0 && shown_.student) {
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
}

// A failed render's errors (red) or a picture's warnings (amber), at the bottom of the picture's
// window: each message with the lines around it, its caret, and its explanation.
void Viewer::drawMessages(const std::string& title, const std::string& text, bool error, float top, float h) {
    ImGui::SetCursorPosY(top);
    ImGui::PushStyleColor(ImGuiCol_ChildBg,
                          error ? ImVec4(0.25f, 0.05f, 0.05f, 1.0f) : ImVec4(0.2f, 0.16f, 0.05f, 1.0f));
    ImGui::BeginChild(error ? "errors" : "warnings", ImVec2(0, h), true,
                      ImGuiWindowFlags_HorizontalScrollbar);
    ImGui::TextColored(error ? ImVec4(1, 0.45f, 0.4f, 1) : ImVec4(1, 0.8f, 0.3f, 1), "%s", title.c_str());
    // Source lines and carets keep their columns; the explanations ("= ...") wrap.
    std::istringstream lines(text);
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

}  // namespace shaderlab::viewer::detail
