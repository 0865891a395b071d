// What the page is told (the state as JSON) and shown (pictures encoded as PNG, values under the
// pointer). Reads the snapshots the render thread publishes, the debug views' too; renders nothing.
#include <cmath>
#include <filesystem>

#include "grader/reports/report_images.h"
#include "shaderlab/grading/grading.h"
#include "shaderlab/render/debug_view.h"
#include "workbench_detail.h"

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace shaderlab::serve {

namespace {

// JSON has no infinity: an identical image's PSNR is null, with "identical" saying why.
json number(double v) { return std::isfinite(v) ? json(v) : json(); }

json boxJson(const grader::PixelBox& b) { return {{"x0", b.x0}, {"y0", b.y0}, {"x1", b.x1}, {"y1", b.y1}}; }

json worstJson(const grader::WorstRegion& w) {
    if (w.tile.empty() || w.mismatch_count == 0) return json();
    return {{"x", w.centre.x},
            {"y", w.centre.y},
            {"tile", boxJson(w.tile)},
            {"bounds", boxJson(w.mismatch_bounds)},
            {"count", w.mismatch_count}};
}

json nonFiniteJson(const grader::ImageVerdict& v) {
    if (v.nan_count + v.inf_count == 0 || v.non_finite_first.empty()) return json();
    return {{"x", v.non_finite_first.front().x},
            {"y", v.non_finite_first.front().y},
            {"box", boxJson(v.non_finite_box)},
            {"count", v.nan_count + v.inf_count}};
}

json verdictJson(const Judgement& j) {
    const grader::MetricSet& m = j.verdict.covered;
    return {{"passed", j.verdict.passed},
            {"reasons", j.verdict.reasons},
            {"metrics",
             {{"psnr_db", number(m.psnr_db)},
              {"identical", std::isinf(m.psnr_db) && m.psnr_db > 0},
              {"ssim", m.ssim_defined ? json(m.ssim) : json()},
              {"flip_mean", m.flip_mean},
              {"mismatch_fraction", m.mismatch_fraction},
              {"nan_count", j.verdict.nan_count},
              {"inf_count", j.verdict.inf_count}}},
            {"thresholds",
             {{"psnr_min_db", j.thresholds.psnr_min_db},
              {"ssim_min", j.thresholds.ssim_min},
              {"flip_mean_max", j.thresholds.flip_mean_max},
              {"mismatch_max", j.thresholds.mismatch_max},
              {"pixel_tolerance", j.thresholds.pixel_tolerance}}},
            {"range", j.hdr ? "hdr" : "display"},
            // Where the picture should point: the window of the worst mismatches, and the first
            // pixel that is not a number (with the box of all of them).
            {"worst", worstJson(j.verdict.worst)},
            {"non_finite", nonFiniteJson(j.verdict)}};
}

json pictureJson(const Snapshot& s) {
    std::vector<std::shared_ptr<const Judgement>> judged;
    {
        std::lock_guard<std::mutex> lock(s.m);
        judged = s.judged;
    }
    json images = json::array();
    bool all_passed = true, any_judged = false;
    for (std::size_t i = 0; i < s.images.size(); ++i) {
        const ImageEntry& e = s.images[i];
        json inputs = json::array();
        for (const InputEntry& in : e.inputs) {
            json j = {{"sampler", in.sampler}, {"from", in.from}, {"label", in.label}};
            if (in.image >= 0) j["image"] = in.image;
            if (in.file >= 0) j["file"] = in.file;
            inputs.push_back(std::move(j));
        }
        json img = {{"index", i},
                    {"key", e.student->pass + "." + e.student->attachment},
                    {"pass", e.student->pass},
                    {"target", e.student->target},
                    {"attachment", e.student->attachment},
                    {"graded", e.student->graded},
                    {"width", e.student->color.width},
                    {"height", e.student->color.height},
                    {"has_reference", e.reference != nullptr},
                    {"inputs", inputs},
                    {"verdict", json()}};
        if (e.pass) {
            img["vertex"] = e.pass->program.vertex;
            img["fragment"] = e.pass->program.fragment;
        }
        if (i < judged.size() && judged[i]) {
            img["verdict"] = verdictJson(*judged[i]);
            if (e.student->graded) {
                any_judged = true;
                all_passed = all_passed && judged[i]->verdict.passed;
            }
        }
        images.push_back(std::move(img));
    }
    const bool graded_view = !s.orbit.any();
    return {{"seq", s.seq},
            {"generation", s.generation},
            {"scene", s.scene},
            {"graded_view", graded_view},
            {"orbit", {{"yaw", s.orbit.yaw_deg}, {"pitch", s.orbit.pitch_deg}, {"zoom", s.orbit.zoom}}},
            {"render_ms", s.render_ms},
            {"latency_ms", s.latency_ms >= 0 ? json(s.latency_ms) : json()},
            {"reference_note", s.reference_note},
            {"final_image", s.final_image},
            {"judged", !judged.empty()},
            // What grading would say of this scene: only in the graded view, once judged.
            {"scene_passed", graded_view && any_judged ? json(all_passed) : json()},
            {"diagnostics", s.diagnostics},
            {"images", images}};
}

// The newest debug view drawn: its picture's number, what it shows and what it could not.
json debugJson(const Snapshot& s) {
    const DebugViewInfo* info = debugViewInfo(s.debug);
    const grader::Image& img = s.images.front().student->color;
    return {{"seq", s.seq},
            {"view", debugViewName(s.debug)},
            {"label", info ? info->label : ""},
            {"scene", s.scene},
            {"orbit", {{"yaw", s.orbit.yaw_deg}, {"pitch", s.orbit.pitch_deg}, {"zoom", s.orbit.zoom}}},
            {"width", img.width},
            {"height", img.height},
            {"render_ms", s.render_ms},
            {"notes", s.notes}};
}

// The student's picture as the page shows it: alpha dropped (it is coverage, not transparency),
// values clamped to 0..1, NaN and Inf in magenta as in the reports.
grader::Image shownColour(const grader::Image& img) {
    const grader::Image marked = grader::markNonFinite(img);
    if (marked.channels == 3) return marked;
    grader::Image rgb(marked.width, marked.height, 3);
    for (int y = 0; y < marked.height; ++y)
        for (int x = 0; x < marked.width; ++x)
            for (int c = 0; c < 3; ++c) rgb.at(x, y, c) = marked.at(x, y, std::min(c, marked.channels - 1));
    return rgb;
}

json rgba(const grader::Image& img, int x, int y) {
    json v = json::array();
    for (int c = 0; c < img.channels; ++c) {
        const float f = img.at(x, y, c);
        v.push_back(std::isfinite(f) ? json(f) : json(std::isnan(f) ? "NaN" : (f > 0 ? "+Inf" : "-Inf")));
    }
    return v;
}

}  // namespace

std::string pictureKindName(PictureKind kind) {
    switch (kind) {
        case PictureKind::Student:
            return "student";
        case PictureKind::Reference:
            return "reference";
        case PictureKind::Diff:
            return "diff";
        case PictureKind::File:
            return "file";
        case PictureKind::Debug:
            return "debug";
    }
    return "";
}

json Workbench::state() const {
    const Impl& w = *impl_;
    std::lock_guard<std::mutex> lock(w.m);
    json scenes = json::array();
    for (const SceneSpec& s : w.opt.spec.scenes) scenes.push_back(s.name);
    json files = json::array();
    for (std::size_t i = 0; i < w.input_files.size(); ++i)
        files.push_back({{"index", i}, {"path", w.input_files[i]}});
    json debug_views = json::array();
    for (const DebugViewInfo& v : debugViews()) debug_views.push_back({{"name", v.name}, {"label", v.label}});
    json goals = json::array();
    for (const GoalSpec& g : w.opt.spec.goals) {
        // The work a goal asks for ("phong.frag: diffuse", or a whole file), for the list of
        // goals the page shows before there is a grade to show them in.
        json work = json::array();
        for (const GoalWork& k : g.work)
            work.push_back(k.function.empty() ? k.file : k.file + ": " + k.function);
        goals.push_back(
            {{"id", g.id}, {"title", g.title}, {"points", g.points}, {"scenes", g.scenes}, {"work", work}});
    }
    json out = {
        {"version", w.version},
        {"lab",
         {{"id", w.opt.spec.id},
          {"title", w.opt.spec.title},
          {"folder", (fs::path(w.opt.submission_root) / w.opt.spec.id).string()},
          {"files", w.opt.spec.student_files},
          {"points", w.opt.spec.grading.points},
          {"goals", goals}}},
        {"scenes", scenes},
        {"input_files", files},
        {"reference", w.opt.reference_root.empty() ? "the stored golden images" : "the reference solution"},
        {"view",
         {{"scene", w.scene},
          {"yaw", w.orbit.yaw_deg},
          {"pitch", w.orbit.pitch_deg},
          {"zoom", w.orbit.zoom},
          {"graded_view", !w.orbit.any()},
          {"debug", debugViewName(w.debug)}}},
        {"debug_views", debug_views},
        {"debug", w.debug_snapshot ? debugJson(*w.debug_snapshot) : json()},
        {"debug_error", w.debug_error},
        {"generation", w.generation},
        {"busy", w.busy},
        {"busy_s", w.busy.empty() ? 0.0 : std::chrono::duration<double>(Clock::now() - w.busy_since).count()},
        {"picture", w.snapshot ? pictureJson(*w.snapshot) : json()},
        {"error", json()},
        {"grade", json()},
        {"heatmap", heatmapLegendJson()},
        {"unchanged_saves", {{"count", w.unchanged_saves}, {"files", w.unchanged_files}}},
    };
    if (w.failure) {
        out["error"] = {{"title", w.failure->title},
                        {"text", w.failure->text},
                        {"scene", w.failure->scene},
                        {"generation", w.failure->generation},
                        {"endless_loop", w.failure->endless_loop},
                        {"diagnostics", w.failure->diagnostics}};
    }
    if (!w.grade.is_null() || !w.grade_error.empty())
        out["grade"] = {{"generation", w.grade_generation},
                        {"pending", w.grade_generation != w.generation || w.want_grade},
                        {"error", w.grade_error},
                        {"lab", w.grade}};
    return out;
}

std::shared_ptr<const grader::Image> Workbench::Impl::inputFile(int index) {
    std::lock_guard<std::mutex> lock(m);
    if (index < 0 || index >= static_cast<int>(input_files.size())) return nullptr;
    auto it = files.find(index);
    if (it != files.end()) return it->second;
    // Only files the lab names, under the lab's folder (labFilePath): never a path from a request.
    const std::string path = labFilePath(opt.spec, input_files[static_cast<std::size_t>(index)]);
    auto img = std::make_shared<grader::Image>();
    std::string err;
    const bool hdr = fs::path(path).extension() == ".hdr";
    if (!(hdr ? grader::readHdr(path, img.get(), &err) : grader::readPng(path, img.get(), &err))) img.reset();
    files[index] = img;
    return img;
}

std::shared_ptr<const Snapshot> Workbench::Impl::findSnapshot(std::uint64_t seq) const {
    std::lock_guard<std::mutex> lock(m);
    for (const std::shared_ptr<const Snapshot>& s : {snapshot, previous, debug_snapshot, debug_previous})
        if (s && s->seq == seq) return s;
    return nullptr;
}

bool Workbench::picture(std::uint64_t seq, PictureKind kind, int index, std::string* png) {
    Impl& w = *impl_;
    if (kind == PictureKind::File) {
        const std::shared_ptr<const grader::Image> img = w.inputFile(index);
        if (!img) return false;
        std::vector<std::uint8_t> bytes;
        if (!grader::encodePng(shownColour(*img), &bytes, nullptr)) return false;
        png->assign(bytes.begin(), bytes.end());
        return true;
    }
    // A debug view's picture by the debug kind only, the lab's by the others.
    const std::shared_ptr<const Snapshot> snap = w.findSnapshot(seq);
    if (!snap || index < 0 || index >= static_cast<int>(snap->images.size())) return false;
    if ((snap->debug != DebugView::Off) != (kind == PictureKind::Debug)) return false;
    const std::string key = pictureKindName(kind) + "/" + std::to_string(index);
    {
        std::lock_guard<std::mutex> lock(snap->m);
        const auto it = snap->pngs.find(key);
        if (it != snap->pngs.end()) {
            *png = *it->second;
            return true;
        }
    }
    const ImageEntry& e = snap->images[static_cast<std::size_t>(index)];
    grader::Image picture;
    if (kind == PictureKind::Student || kind == PictureKind::Debug) {
        picture = shownColour(e.student->color);
    } else if (kind == PictureKind::Reference) {
        if (!e.reference) return false;
        picture = shownColour(e.reference->color);
    } else {
        std::shared_ptr<const Judgement> j;
        {
            std::lock_guard<std::mutex> lock(snap->m);
            if (static_cast<std::size_t>(index) < snap->judged.size())
                j = snap->judged[static_cast<std::size_t>(index)];
        }
        if (!j || j->heat.empty()) return false;
        picture = shownColour(j->heat);
    }
    std::vector<std::uint8_t> bytes;
    if (!grader::encodePng(picture, &bytes, nullptr)) return false;
    auto encoded = std::make_shared<const std::string>(bytes.begin(), bytes.end());
    *png = *encoded;
    std::lock_guard<std::mutex> lock(snap->m);
    snap->pngs[key] = std::move(encoded);
    return true;
}

bool Workbench::pixel(std::uint64_t seq, int index, int x, int y, json* out) const {
    const std::shared_ptr<const Snapshot> snap = impl_->findSnapshot(seq);
    if (!snap || index < 0 || index >= static_cast<int>(snap->images.size())) return false;
    const ImageEntry& e = snap->images[static_cast<std::size_t>(index)];
    const grader::Image& mine = e.student->color;
    if (x < 0 || y < 0 || x >= mine.width || y >= mine.height) return false;
    *out = {{"x", x}, {"y", y}, {"student", rgba(mine, x, y)}, {"reference", json()}, {"flip", json()}};
    if (snap->debug != DebugView::Off) {
        const std::size_t at = static_cast<std::size_t>(y) * mine.width + x;
        const bool covered = at >= e.student->coverage.size() || e.student->coverage[at] != 0;
        (*out)["debug"] =
            describeDebugPixel(snap->debug, mine.at(x, y, 0), mine.at(x, y, 1), mine.at(x, y, 2), covered);
        return true;
    }
    if (e.reference) (*out)["reference"] = rgba(e.reference->color, x, y);
    std::lock_guard<std::mutex> lock(snap->m);
    if (static_cast<std::size_t>(index) < snap->judged.size() &&
        snap->judged[static_cast<std::size_t>(index)]) {
        const std::vector<float>& flip = snap->judged[static_cast<std::size_t>(index)]->verdict.flip_map;
        const std::size_t at = static_cast<std::size_t>(y) * mine.width + x;
        if (at < flip.size()) (*out)["flip"] = number(flip[at]);
    }
    return true;
}

}  // namespace shaderlab::serve
