// report.json and Gradescope results.json; see report.h and docs/report-format.md.
#include <cmath>
#include <cstdio>
#include <limits>
#include <nlohmann/json.hpp>

#include "grader/reports/report.h"
#include "report_markup.h"

namespace grader {

namespace {

using json = nlohmann::ordered_json;

// JSON has no infinity, and nlohmann writes NaN/Inf as null without a word, so every double
// passes through here: +inf PSNR becomes null (paired with "identical": true); any other
// non-finite value is a bug upstream and is written as null too, never as a misleading number.
json number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

double fromNumber(const json& j, double if_null) { return j.is_number() ? j.get<double>() : if_null; }

json box(const PixelBox& b) {
    if (b.empty()) return nullptr;
    return {{"x0", b.x0}, {"y0", b.y0}, {"x1", b.x1}, {"y1", b.y1}};
}

PixelBox boxFrom(const json& j) {
    PixelBox b;
    if (j.is_object()) {
        b.x0 = j.value("x0", 0);
        b.y0 = j.value("y0", 0);
        b.x1 = j.value("x1", -1);
        b.y1 = j.value("y1", -1);
    }
    return b;
}

json metrics(const ReportMetrics& m) {
    return {{"psnr_db", number(m.psnr_db)},
            {"identical", std::isinf(m.psnr_db) && m.psnr_db > 0},
            {"ssim", m.ssim_defined ? number(m.ssim) : json(nullptr)},
            {"flip_mean", number(m.flip_mean)},
            {"flip_weighted_median", number(m.flip_weighted_median)},
            {"mismatch_fraction", number(m.mismatch_fraction)},
            {"nan_count", m.nan_count},
            {"inf_count", m.inf_count},
            {"pixel_count", m.pixel_count}};
}

ReportMetrics metricsFrom(const json& j) {
    ReportMetrics m;
    if (!j.is_object()) return m;
    const bool identical = j.value("identical", false);
    m.psnr_db =
        fromNumber(j.value("psnr_db", json()), identical ? std::numeric_limits<double>::infinity() : 0.0);
    m.ssim_defined = j.value("ssim", json()).is_number();
    m.ssim = fromNumber(j.value("ssim", json()), 0.0);
    m.flip_mean = fromNumber(j.value("flip_mean", json()), 0.0);
    m.flip_weighted_median = fromNumber(j.value("flip_weighted_median", json()), 0.0);
    m.mismatch_fraction = fromNumber(j.value("mismatch_fraction", json()), 0.0);
    m.nan_count = j.value("nan_count", std::size_t{0});
    m.inf_count = j.value("inf_count", std::size_t{0});
    m.pixel_count = j.value("pixel_count", std::size_t{0});
    return m;
}

// The two pictures every graded image has, then the ones a failing image adds when they exist.
json images(const std::string& student, const std::string& reference, const std::string& diff,
            const std::string& signed_image, const std::string& zoom) {
    json j = {{"student", student}, {"reference", reference}};
    if (!diff.empty()) j["diff"] = diff;
    if (!signed_image.empty()) j["signed_difference"] = signed_image;
    if (!zoom.empty()) j["zoom"] = zoom;
    return j;
}

json thresholds(const ReportThresholds& t) {
    if (!t.known) return nullptr;
    return {{"psnr_min_db", number(t.psnr_min_db)},
            {"ssim_min", number(t.ssim_min)},
            {"flip_mean_max", number(t.flip_mean_max)},
            {"mismatch_max", number(t.mismatch_max)},
            {"pixel_tolerance", number(t.pixel_tolerance)}};
}

ReportThresholds thresholdsFrom(const json& j) {
    ReportThresholds t;
    if (!j.is_object()) return t;
    t.known = true;
    t.psnr_min_db = fromNumber(j.value("psnr_min_db", json()), 0.0);
    t.ssim_min = fromNumber(j.value("ssim_min", json()), 0.0);
    t.flip_mean_max = fromNumber(j.value("flip_mean_max", json()), 0.0);
    t.mismatch_max = fromNumber(j.value("mismatch_max", json()), 0.0);
    t.pixel_tolerance = fromNumber(j.value("pixel_tolerance", json()), 0.0);
    return t;
}

json hint(const ReportHint& h) {
    if (h.mistake.empty()) return nullptr;
    return {{"mistake", h.mistake},
            {"about", h.about},
            {"image", h.image},
            {"psnr_db", number(h.psnr_db)},
            {"identical", std::isinf(h.psnr_db) && h.psnr_db > 0}};
}

ReportHint hintFrom(const json& j) {
    ReportHint h;
    if (!j.is_object()) return h;
    h.mistake = j.value("mistake", "");
    h.about = j.value("about", "");
    h.image = j.value("image", "");
    h.psnr_db = fromNumber(j.value("psnr_db", json()),
                           j.value("identical", false) ? std::numeric_limits<double>::infinity() : 0.0);
    return h;
}

}  // namespace

std::string reportToJson(const Report& report) {
    json labs = json::array();
    for (const ReportLab& lab : report.labs) {
        json diags = json::array();
        for (const ReportDiagnostic& d : lab.diagnostics) {
            json j = {{"file", d.file},
                      {"line", d.line},
                      {"column", d.column},
                      {"severity", d.severity},
                      {"message", d.message}};
            // Optional within schema 2: absent when empty, so older readers see what they knew.
            if (!d.explanation.empty()) j["explanation"] = d.explanation;
            if (!d.source_line.empty()) j["source_line"] = d.source_line;
            if (!d.driver_message.empty()) j["driver_message"] = d.driver_message;
            if (d.follow_on > 0) j["follow_on"] = d.follow_on;
            diags.push_back(std::move(j));
        }
        json scenes = json::array();
        for (const ReportScene& s : lab.scenes) {
            json passes = json::array();
            for (const ReportPass& p : s.passes) {
                json alone = nullptr;
                if (p.isolated)
                    alone = {{"passed", p.isolated_passed},
                             {"reasons", p.isolated_reasons},
                             {"metrics", metrics(p.isolated_metrics)}};
                passes.push_back({{"name", p.name},
                                  {"pass", p.pass},
                                  {"attachment", p.attachment},
                                  {"range", p.range},
                                  {"hdr_scale", number(p.hdr_scale)},
                                  {"passed", p.passed},
                                  {"reasons", p.reasons},
                                  {"metrics", metrics(p.metrics)},
                                  {"thresholds", thresholds(p.thresholds)},
                                  {"width", p.width},
                                  {"height", p.height},
                                  {"worst_region", box(p.worst_region)},
                                  {"non_finite_region", box(p.non_finite_box)},
                                  {"zoom_region", box(p.zoom_region)},
                                  {"images", images(p.student_image, p.reference_image, p.diff_image,
                                                    p.signed_image, p.zoom_image)},
                                  {"on_reference_inputs", alone}});
            }
            scenes.push_back({{"name", s.name},
                              {"status", s.status},
                              {"score", number(s.score)},
                              {"max_score", number(s.max_score)},
                              {"message", s.message},
                              {"first_failing_pass",
                               s.first_failing_pass.empty() ? json(nullptr) : json(s.first_failing_pass)},
                              {"metrics", metrics(s.metrics)},
                              {"frame_metrics", metrics(s.frame_metrics)},
                              {"worst_region", box(s.worst_region)},
                              {"non_finite_region", box(s.non_finite_box)},
                              {"images", images(s.student_image, s.reference_image, s.diff_image,
                                                s.signed_image, s.zoom_image)},
                              {"passes", passes},
                              {"hint", hint(s.hint)},
                              {"render_ms", number(s.render_ms)}});
        }
        json goals = json::array();
        for (const ReportGoal& g : lab.goals) {
            json goal = {{"id", g.id},        {"title", g.title},     {"points", number(g.points)},
                         {"met", g.met},      {"failing", g.failing}, {"not_met_because", g.not_met_because},
                         {"scenes", g.scenes}};
            if (!g.judged.empty()) goal["judged"] = g.judged;
            if (!g.judged_note.empty()) goal["judged_note"] = g.judged_note;
            if (!g.whole_failing.empty()) goal["whole_failing"] = g.whole_failing;
            if (!g.judged_with.empty()) goal["judged_with"] = g.judged_with;
            goals.push_back(std::move(goal));
        }
        labs.push_back({{"id", lab.id},
                        {"title", lab.title},
                        {"folder", lab.folder},
                        {"files", lab.files},
                        {"status", lab.status},
                        {"score", number(lab.score)},
                        {"max_score", number(lab.max_score)},
                        {"message", lab.message},
                        {"reference_source", lab.reference_source},
                        {"diagnostics", diags},
                        {"goals", goals},
                        {"scenes", scenes},
                        {"wall_ms", number(lab.wall_ms)}});
        if (!lab.limit.empty()) labs.back()["limit"] = lab.limit;
    }
    json root = {{"schema_version", kReportSchemaVersion},
                 {"tool", "shaderlab"},
                 {"tool_version", report.tool_version},
                 {"submission", report.submission},
                 {"backend", report.backend},
                 {"renderer", report.renderer},
                 {"score", number(report.score)},
                 {"max_score", number(report.max_score)},
                 {"labs", labs}};
    return root.dump(2, ' ', false, json::error_handler_t::replace) + "\n";
}

bool reportFromJson(const std::string& text, Report* out, std::string* error) {
    const json root = json::parse(text, nullptr, false);
    if (root.is_discarded() || !root.is_object()) {
        *error = "report is not a JSON object";
        return false;
    }
    if (root.value("schema_version", 0) != kReportSchemaVersion) {
        *error = "report schema_version " + std::to_string(root.value("schema_version", 0)) + ", expected " +
                 std::to_string(kReportSchemaVersion);
        return false;
    }
    Report r;
    r.tool_version = root.value("tool_version", "");
    r.submission = root.value("submission", "");
    r.backend = root.value("backend", "");
    r.renderer = root.value("renderer", "");
    r.score = fromNumber(root.value("score", json()), 0.0);
    r.max_score = fromNumber(root.value("max_score", json()), 0.0);
    for (const json& l : root.value("labs", json::array())) {
        ReportLab lab;
        lab.id = l.value("id", "");
        lab.title = l.value("title", "");
        lab.folder = l.value("folder", "");
        lab.files = l.value("files", std::vector<std::string>{});
        lab.status = l.value("status", "");
        lab.score = fromNumber(l.value("score", json()), 0.0);
        lab.max_score = fromNumber(l.value("max_score", json()), 0.0);
        lab.message = l.value("message", "");
        lab.reference_source = l.value("reference_source", "");
        lab.wall_ms = fromNumber(l.value("wall_ms", json()), 0.0);
        lab.limit = l.value("limit", "");
        for (const json& d : l.value("diagnostics", json::array()))
            lab.diagnostics.push_back({d.value("file", ""), d.value("line", 0), d.value("column", 0),
                                       d.value("severity", ""), d.value("message", ""),
                                       d.value("explanation", ""), d.value("source_line", ""),
                                       d.value("driver_message", ""), d.value("follow_on", 0)});
        for (const json& g : l.value("goals", json::array())) {
            ReportGoal goal;
            goal.id = g.value("id", "");
            goal.title = g.value("title", "");
            goal.points = fromNumber(g.value("points", json()), 0.0);
            goal.met = g.value("met", false);
            goal.failing = g.value("failing", std::vector<std::string>{});
            goal.scenes = g.value("scenes", std::vector<std::string>{});
            goal.not_met_because = g.value("not_met_because", std::vector<std::string>{});
            goal.judged = g.value("judged", "");
            goal.judged_note = g.value("judged_note", "");
            goal.whole_failing = g.value("whole_failing", std::vector<std::string>{});
            goal.judged_with = g.value("judged_with", std::vector<std::string>{});
            lab.goals.push_back(std::move(goal));
        }
        for (const json& s : l.value("scenes", json::array())) {
            ReportScene scene;
            scene.name = s.value("name", "");
            scene.status = s.value("status", "");
            scene.score = fromNumber(s.value("score", json()), 0.0);
            scene.max_score = fromNumber(s.value("max_score", json()), 0.0);
            scene.message = s.value("message", "");
            const json ffp = s.value("first_failing_pass", json());
            scene.first_failing_pass = ffp.is_string() ? ffp.get<std::string>() : "";
            scene.metrics = metricsFrom(s.value("metrics", json()));
            scene.frame_metrics = metricsFrom(s.value("frame_metrics", json()));
            scene.worst_region = boxFrom(s.value("worst_region", json()));
            scene.non_finite_box = boxFrom(s.value("non_finite_region", json()));
            const json im = s.value("images", json::object());
            scene.student_image = im.value("student", "");
            scene.reference_image = im.value("reference", "");
            scene.diff_image = im.value("diff", "");
            scene.signed_image = im.value("signed_difference", "");
            scene.zoom_image = im.value("zoom", "");
            scene.hint = hintFrom(s.value("hint", json()));
            scene.render_ms = fromNumber(s.value("render_ms", json()), 0.0);
            for (const json& p : s.value("passes", json::array())) {
                ReportPass pass;
                pass.name = p.value("name", "");
                pass.pass = p.value("pass", "");
                pass.attachment = p.value("attachment", "");
                pass.range = p.value("range", "");
                pass.hdr_scale = fromNumber(p.value("hdr_scale", json()), 1.0);
                pass.passed = p.value("passed", false);
                pass.reasons = p.value("reasons", std::vector<std::string>{});
                pass.metrics = metricsFrom(p.value("metrics", json()));
                const json pim = p.value("images", json::object());
                pass.student_image = pim.value("student", "");
                pass.reference_image = pim.value("reference", "");
                pass.diff_image = pim.value("diff", "");
                pass.signed_image = pim.value("signed_difference", "");
                pass.zoom_image = pim.value("zoom", "");
                pass.thresholds = thresholdsFrom(p.value("thresholds", json()));
                pass.width = p.value("width", 0);
                pass.height = p.value("height", 0);
                pass.worst_region = boxFrom(p.value("worst_region", json()));
                pass.non_finite_box = boxFrom(p.value("non_finite_region", json()));
                pass.zoom_region = boxFrom(p.value("zoom_region", json()));
                const json alone = p.value("on_reference_inputs", json());
                if (alone.is_object()) {
                    pass.isolated = true;
                    pass.isolated_passed = alone.value("passed", false);
                    pass.isolated_reasons = alone.value("reasons", std::vector<std::string>{});
                    pass.isolated_metrics = metricsFrom(alone.value("metrics", json()));
                }
                scene.passes.push_back(std::move(pass));
            }
            lab.scenes.push_back(std::move(scene));
        }
        r.labs.push_back(std::move(lab));
    }
    *out = std::move(r);
    return true;
}

// Gradescope autograder results.json (https://gradescope-autograders.readthedocs.io/en/latest/specs/):
// top-level score and output, one test per learning goal (or one per lab when the lab never
// rendered), status "passed"/"failed", visible to the student. Goal outputs and the top-level
// output are html ("output_format"), with the failing images embedded while the budget lasts.
std::string reportToGradescope(const Report& report, const ImageEmbedding& images) {
    detail::Budget budget(images);
    json tests = json::array();
    for (const ReportLab& lab : report.labs) {
        if (lab.scenes.empty()) {
            std::string output = lab.status + ": " + lab.message;
            for (const ReportDiagnostic& d : lab.diagnostics) output += "\n" + formatDiagnostic(d);
            tests.push_back({{"name", lab.id},
                             {"score", number(lab.score)},
                             {"max_score", number(lab.max_score)},
                             {"status", "failed"},
                             {"output", output},
                             {"output_format", "text"},
                             {"visibility", "visible"}});
            continue;
        }
        // One test per learning goal: what the student learned is what earns points.
        for (const ReportGoal& g : lab.goals) {
            tests.push_back({{"name", lab.id + " / " + g.title},
                             {"score", number(g.met ? g.points : 0.0)},
                             {"max_score", number(g.points)},
                             {"status", g.met ? "passed" : "failed"},
                             {"output", detail::gradescopeGoalHtml(lab, g, budget)},
                             {"output_format", "html"},
                             {"visibility", "visible"}});
        }
    }
    char summary[160];
    std::snprintf(summary, sizeof summary, "<p>shaderlab %s: <b>%.2f / %.2f</b> points.</p>\n",
                  report.tool_version.c_str(), report.score, report.max_score);
    std::string output = summary + detail::gradescopeSummaryHtml(report);
    if (budget.left_out() > 0)
        output += "<p>" + std::to_string(budget.left_out()) +
                  " pictures were left out to keep this page small; report.html has all of them.</p>\n";
    json root = {{"score", number(report.score)},
                 {"output", output},
                 {"output_format", "html"},
                 {"visibility", "visible"},
                 {"tests", tests}};
    return root.dump(2, ' ', false, json::error_handler_t::replace) + "\n";
}

}  // namespace grader
