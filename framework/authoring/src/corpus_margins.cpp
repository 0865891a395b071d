// `shaderlab corpus --margins` (corpus_margins.h): the factors by which a lab's corpus verdicts
// hold, from the reports `corpus` wrote. Reads report.json files; writes margins.json; prints.
#include "shaderlab/authoring/corpus_margins.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace shaderlab::authoring {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// One metric of one image beside its threshold.
struct MetricMargin {
    std::string name;      // as in report.json's metrics: psnr_db, ssim, flip_mean, mismatch_fraction
    double value = kNaN;   // NaN: not measured (SSIM on an image smaller than its window)
    double limit = kNaN;   // the threshold it was judged with
    double factor = kNaN;  // above 1: on the passing side by that factor; infinite: no error
};

// One graded image of one case.
struct ImageMargin {
    std::string scene, image, pass;
    bool passed = false;
    std::string expected;   // "pass", "fail" (a goal the mistake breaks), "either" (a goal resting on it)
    bool isolated = false;  // judged on the reference's inputs (pass isolation), as its goals are
    bool identical = false;
    std::vector<MetricMargin> metrics;
    double margin = kNaN;  // NaN: failed on something no threshold measures (see `reason`)
    std::string limiting;  // the metric that sets `margin`
    std::string reason;    // the report's first reason, when `margin` is NaN
    bool thin = false;     // an expected verdict holding by less than the lab's factor
};

// A goal a mistake breaks: its "not met" holds by its most decisive failing image.
struct GoalMargin {
    std::string goal, scene, image;
    double margin = kNaN;
    bool thin = false;
};

struct CaseMargins {
    std::string name, kind, report, error;
    std::vector<ImageMargin> images;
    std::vector<GoalMargin> goals;
};

double number(const json& object, const char* key) {
    if (!object.is_object()) return kNaN;
    const auto it = object.find(key);
    return it != object.end() && it->is_number() ? it->get<double>() : kNaN;
}

double limitOf(const json& thresholds, const char* key, float fallback) {
    const double v = number(thresholds, key);
    return std::isnan(v) ? static_cast<double>(fallback) : v;
}

// The four thresholded metrics of `metrics` as factors (corpus_margins.h gives the formulas).
std::vector<MetricMargin> metricMargins(const json& metrics, const json& thresholds,
                                        const GradingThresholds& lab) {
    std::vector<MetricMargin> out(4);
    MetricMargin& psnr = out[0];
    psnr.name = "psnr_db";
    psnr.limit = limitOf(thresholds, "psnr_min_db", lab.psnr_min_db);
    psnr.value = metrics.value("identical", false) ? kInf : number(metrics, "psnr_db");
    if (!std::isnan(psnr.value)) psnr.factor = std::pow(10.0, (psnr.value - psnr.limit) / 10.0);
    MetricMargin& ssim = out[1];
    ssim.name = "ssim";
    ssim.limit = limitOf(thresholds, "ssim_min", lab.ssim_min);
    ssim.value = number(metrics, "ssim");
    if (!std::isnan(ssim.value))
        ssim.factor = ssim.value >= 1.0 ? kInf : (1.0 - ssim.limit) / (1.0 - ssim.value);
    // Lower is better: the limit over the value.
    const struct {
        const char *metric, *threshold;
        float lab;
    } lower[2] = {{"flip_mean", "flip_mean_max", lab.flip_mean_max},
                  {"mismatch_fraction", "mismatch_max", lab.mismatch_max}};
    for (int i = 0; i < 2; ++i) {
        MetricMargin& m = out[2 + i];
        m.name = lower[i].metric;
        m.limit = limitOf(thresholds, lower[i].threshold, lower[i].lab);
        m.value = number(metrics, lower[i].metric);
        if (!std::isnan(m.value)) m.factor = m.value <= 0.0 ? kInf : m.limit / m.value;
    }
    return out;
}

// The image's margin: its smallest factor for a pass, the inverse of it for a fail.
void decide(ImageMargin* im, const json& reasons) {
    double smallest = kInf;
    for (const MetricMargin& m : im->metrics)
        if (!std::isnan(m.factor) && (im->limiting.empty() || m.factor < smallest)) {
            smallest = m.factor;
            im->limiting = m.name;
        }
    if (std::isinf(smallest)) im->limiting.clear();  // no metric sees an error
    if (im->passed) {
        im->margin = smallest;
    } else if (smallest < 1.0) {
        im->margin = 1.0 / smallest;
    } else {
        im->limiting.clear();
        im->reason = reasons.is_array() && !reasons.empty() && reasons[0].is_string()
                         ? reasons[0].get<std::string>()
                         : "failed on a check no threshold measures";
    }
}

bool inGoal(const GoalSpec& g, const std::string& scene, const std::string& pass) {
    return std::find(g.scenes.begin(), g.scenes.end(), scene) != g.scenes.end() &&
           std::find(g.passes.begin(), g.passes.end(), pass) != g.passes.end();
}

// What the case's image should do: a mistake fails the goals it names (an image of one may still
// pass: one failing image is enough), may fail those resting on them, and passes the rest.
std::string expectation(const LabSpec& spec, const Case& c, const json& report_goals,
                        const std::string& scene, const std::string& pass) {
    if (c.kind != "mistake") return "pass";
    std::string out = "pass";
    for (const GoalSpec& g : spec.goals) {
        if (!inGoal(g, scene, pass)) continue;
        if (std::find(c.fails.begin(), c.fails.end(), g.id) != c.fails.end()) return "fail";
        for (const json& rg : report_goals)
            if (rg.value("id", "") == g.id && rg.contains("not_met_because") &&
                !rg["not_met_because"].empty())
                out = "either";
    }
    return out;
}

// Whether the image's goals take its verdict on the reference's inputs (when it has one): every
// goal but one judged on the pipeline does.
bool judgedIsolated(const LabSpec& spec, const std::string& scene, const std::string& pass) {
    bool any = false;
    for (const GoalSpec& g : spec.goals) {
        if (!inGoal(g, scene, pass)) continue;
        if (!g.pipeline) return true;
        any = true;
    }
    return !any;
}

CaseMargins readCase(const LabSpec& spec, const Case& c, const fs::path& report_file, double factor) {
    CaseMargins cm;
    cm.name = c.name;
    cm.kind = c.kind;
    cm.report = report_file.string();
    std::ifstream in(report_file);
    const json report = json::parse(in, nullptr, false);
    if (report.is_discarded() || !report.contains("labs") || report["labs"].empty()) {
        cm.error = report_file.string() + ": cannot be read";
        return cm;
    }
    const json& lab = report["labs"][0];
    const json no_goals = json::array();
    const json& goals = lab.contains("goals") ? lab["goals"] : no_goals;
    for (const json& scene : lab.value("scenes", json::array())) {
        for (const json& pass : scene.value("passes", json::array())) {
            ImageMargin im;
            im.scene = scene.value("name", "");
            im.image = pass.value("name", "");
            im.pass = pass.value("pass", im.image);
            const json& alone = pass.contains("on_reference_inputs") ? pass["on_reference_inputs"] : no_goals;
            im.isolated = alone.is_object() && judgedIsolated(spec, im.scene, im.pass);
            const json& judged = im.isolated ? alone : pass;
            const json metrics = judged.value("metrics", json::object());
            im.passed = judged.value("passed", false);
            im.identical = metrics.value("identical", false);
            im.expected = expectation(spec, c, goals, im.scene, im.pass);
            const json thresholds = pass.contains("thresholds") ? pass["thresholds"] : json();
            im.metrics = metricMargins(metrics, thresholds, spec.grading.thresholds);
            decide(&im, judged.value("reasons", json::array()));
            const bool as_expected = im.expected == (im.passed ? "pass" : "fail");
            im.thin = as_expected && !std::isnan(im.margin) && im.margin < factor;
            cm.images.push_back(std::move(im));
        }
    }
    for (const std::string& goal_id : c.fails) {
        GoalMargin gm;
        gm.goal = goal_id;
        const auto goal = std::find_if(spec.goals.begin(), spec.goals.end(),
                                       [&](const GoalSpec& g) { return g.id == goal_id; });
        for (const ImageMargin& im : cm.images) {
            if (goal == spec.goals.end() || im.passed || !inGoal(*goal, im.scene, im.pass)) continue;
            if (std::isnan(im.margin) || (!std::isnan(gm.margin) && im.margin <= gm.margin)) continue;
            gm.margin = im.margin;
            gm.scene = im.scene;
            gm.image = im.image;
        }
        gm.thin = !std::isnan(gm.margin) && gm.margin < factor;
        cm.goals.push_back(std::move(gm));
    }
    return cm;
}

json finite(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

std::string metricCell(const MetricMargin& m) {
    if (std::isnan(m.value)) return "-";
    char buf[48];
    if (std::isinf(m.value))
        std::snprintf(buf, sizeof buf, "inf/%.3g", m.limit);
    else
        std::snprintf(buf, sizeof buf, "%.4g/%.3g", m.value, m.limit);
    return buf;
}

json imageJson(const ImageMargin& im) {
    json metrics = json::object();
    for (const MetricMargin& m : im.metrics)
        metrics[m.name] = {
            {"value", finite(m.value)}, {"limit", finite(m.limit)}, {"factor", finite(m.factor)}};
    json j = {{"scene", im.scene},
              {"image", im.image},
              {"verdict", im.passed ? "passed" : "failed"},
              {"expected", im.expected},
              {"judged_on", im.isolated ? "reference_inputs" : "own_inputs"},
              {"identical", im.identical},
              {"metrics", metrics},
              {"margin", finite(im.margin)},
              {"limiting_metric", im.limiting},
              {"thin", im.thin}};
    if (!im.reason.empty()) j["reason"] = im.reason;
    return j;
}

// Where a case's (or a lab's) verdicts are tightest.
struct Tightest {
    const CaseMargins* c = nullptr;
    const ImageMargin* image = nullptr;
    const GoalMargin* goal = nullptr;
    double margin = kInf;
};

json tightestJson(const Tightest& t, bool with_case) {
    if (t.c == nullptr) return nullptr;
    json j = json::object();
    if (with_case) j["case"] = t.c->name;
    if (t.goal != nullptr) j["goal"] = t.goal->goal;
    j["scene"] = t.image ? t.image->scene : t.goal->scene;
    j["image"] = t.image ? t.image->image : t.goal->image;
    if (t.image) j["metric"] = t.image->limiting;
    j["margin"] = finite(t.margin);
    return j;
}

// The tightest passing image that should pass, and failing image that should fail, of `cm`.
void tighten(const CaseMargins& cm, Tightest* pass, Tightest* fail) {
    for (const ImageMargin& im : cm.images) {
        if (std::isnan(im.margin)) continue;
        Tightest* t = im.passed && im.expected == "pass"    ? pass
                      : !im.passed && im.expected == "fail" ? fail
                                                            : nullptr;
        if (t != nullptr && (t->c == nullptr || im.margin < t->margin)) *t = {&cm, &im, nullptr, im.margin};
    }
}

json caseJson(const CaseMargins& cm) {
    Tightest pass, fail;
    tighten(cm, &pass, &fail);
    json goals = json::array();
    int thin = 0;
    for (const ImageMargin& im : cm.images) thin += im.thin;
    for (const GoalMargin& g : cm.goals) {
        goals.push_back({{"goal", g.goal},
                         {"scene", g.scene},
                         {"image", g.image},
                         {"margin", finite(g.margin)},
                         {"thin", g.thin}});
        thin += g.thin;
    }
    json j = {{"tightest_pass", tightestJson(pass, false)},
              {"tightest_fail", tightestJson(fail, false)},
              {"thin", thin}};
    if (cm.kind == "mistake") j["goals"] = goals;
    if (!cm.error.empty()) j["error"] = cm.error;
    return j;
}

void printTable(const std::vector<CaseMargins>& all, double factor, const fs::path& file) {
    std::printf(
        "  margins: how far each verdict is from turning, as a factor on the error (flagged below %gx, "
        "lab.json grading.margin_factor)\n",
        factor);
    std::printf("  %-28s %-26s %-14s %-9s %-14s %-13s %-15s %-15s %-24s\n", "case", "scene", "image",
                "verdict", "PSNR dB/min", "SSIM/min", "FLIP/max", "mismatch/max", "margin");
    int identical = 0;
    for (const CaseMargins& cm : all) {
        if (!cm.error.empty()) std::printf("  %-28s %s\n", cm.name.c_str(), cm.error.c_str());
        for (const ImageMargin& im : cm.images) {
            if (im.identical) {
                ++identical;
                continue;
            }
            std::string verdict = std::string(im.passed ? "pass" : "fail") + (im.isolated ? "/iso" : "");
            std::string margin = factorText(im.margin) + (im.limiting.empty() ? "" : " " + im.limiting);
            if (!im.reason.empty()) margin += " (" + im.reason + ")";
            const char* flag = im.thin                               ? "  THIN"
                               : im.expected == "pass" && !im.passed ? "  unexpected fail"
                               : im.expected == "fail" && im.passed  ? "  not caught by this image"
                                                                     : "";
            std::printf("  %-28s %-26s %-14s %-9s %-14s %-13s %-15s %-15s %s%s\n", cm.name.c_str(),
                        im.scene.c_str(), im.image.c_str(), verdict.c_str(),
                        metricCell(im.metrics[0]).c_str(), metricCell(im.metrics[1]).c_str(),
                        metricCell(im.metrics[2]).c_str(), metricCell(im.metrics[3]).c_str(), margin.c_str(),
                        flag);
        }
    }
    std::printf("  (%d images identical to the reference's are not listed; every image is in %s)\n",
                identical, file.string().c_str());
}

void printTightest(const char* what, const Tightest& t) {
    if (t.c == nullptr) {
        std::printf("  %-26s none\n", what);
        return;
    }
    const std::string where =
        t.image ? t.image->scene + "/" + t.image->image + " (" + t.image->limiting + ")"
                : "goal " + t.goal->goal + ", through " + t.goal->scene + "/" + t.goal->image;
    std::printf("  %-26s %-8s %s, %s\n", what, factorText(t.margin).c_str(), t.c->name.c_str(),
                where.c_str());
}

}  // namespace

std::string factorText(double f) {
    if (std::isnan(f)) return "n/a";
    if (std::isinf(f)) return "inf";
    char buf[32];
    if (f >= 1000.0) return ">1000x";
    std::snprintf(buf, sizeof buf, "%.3gx", f);
    return buf;
}

VerdictMargin verdictMargin(const json& judged, const json& thresholds, const GradingThresholds& lab) {
    ImageMargin im;
    im.passed = judged.value("passed", false);
    im.metrics = metricMargins(judged.value("metrics", json::object()), thresholds, lab);
    decide(&im, judged.value("reasons", json::array()));
    return {im.passed, im.margin, im.limiting, im.reason};
}

std::map<std::string, json> reportLabMargins(const LabSpec& spec, const std::vector<Case>& cases,
                                             const fs::path& lab_out) {
    const double factor = spec.grading.margin_factor;
    std::vector<Case> graded;
    Case reference;
    reference.name = "reference";
    reference.kind = "reference";
    graded.push_back(reference);
    for (const Case& c : cases)
        if (c.kind != "broken") graded.push_back(c);
    std::vector<CaseMargins> all;
    for (const Case& c : graded)
        all.push_back(readCase(spec, c, lab_out / "reports" / c.name / "report.json", factor));

    Tightest pass, fail, mistake;
    int thin_images = 0, thin_goals = 0;
    json cases_json = json::array();
    std::map<std::string, json> per_case;
    for (const CaseMargins& cm : all) {
        tighten(cm, &pass, &fail);
        for (const GoalMargin& g : cm.goals) {
            thin_goals += g.thin;
            if (!std::isnan(g.margin) && (mistake.c == nullptr || g.margin < mistake.margin))
                mistake = {&cm, nullptr, &g, g.margin};
        }
        json images = json::array();
        for (const ImageMargin& im : cm.images) {
            thin_images += im.thin;
            images.push_back(imageJson(im));
        }
        per_case[cm.name] = caseJson(cm);
        json entry = {{"case", cm.name}, {"kind", cm.kind}, {"report", cm.report}, {"images", images}};
        if (per_case[cm.name].contains("goals")) entry["goals"] = per_case[cm.name]["goals"];
        if (!cm.error.empty()) entry["error"] = cm.error;
        cases_json.push_back(std::move(entry));
    }
    const fs::path file = lab_out / "margins.json";
    const json doc = {
        {"lab", spec.id},
        {"margin_factor", factor},
        {"factors",
         "above 1: the verdict holds by that factor on the error; PSNR 10^(dB difference/10), SSIM "
         "on 1 - SSIM, FLIP and mismatch limit/value (inverted for a fail); null: infinite"},
        {"cases", cases_json},
        {"tightest_pass", tightestJson(pass, true)},
        {"tightest_fail", tightestJson(fail, true)},
        {"tightest_mistake", tightestJson(mistake, true)},
        {"thin_images", thin_images},
        {"thin_goals", thin_goals}};
    std::ofstream(file) << doc.dump(2) << "\n";

    printTable(all, factor, file);
    printTightest("tightest pass:", pass);
    printTightest("tightest fail:", fail);
    printTightest("tightest mistake verdict:", mistake);
    if (thin_images + thin_goals > 0)
        std::printf(
            "  %d image%s and %d mistake goal%s hold by less than %gx (advice: the run does not fail on "
            "it)\n",
            thin_images, thin_images == 1 ? "" : "s", thin_goals, thin_goals == 1 ? "" : "s", factor);
    else
        std::printf("  every verdict holds by %gx or more\n", factor);
    std::printf("\n");
    return per_case;
}

}  // namespace shaderlab::authoring
