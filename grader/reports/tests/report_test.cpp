// The report writers: report.json round-trips through its reader, infinity and hostile text
// survive every format, the Gradescope and JUnit shapes hold what their consumers read, and the
// HTML page says where to look first, never rounds a failing number onto its threshold, and
// embeds its pictures within its budget.
#include "grader/reports/report.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>

#include "grader/metrics/image.h"

namespace fs = std::filesystem;

namespace {

grader::Report sampleReport() {
    grader::Report r;
    r.tool_version = "9.9.9";
    r.submission = "subs/alice";
    r.backend = "egl";
    r.renderer = "llvmpipe";
    r.score = 7.5;
    r.max_score = 20.0;

    grader::ReportLab built;
    built.id = "01-phong";
    built.title = "Phong";
    built.status = "failed";
    built.score = 7.5;
    built.max_score = 10.0;
    built.reference_source = "goldens";
    built.diagnostics.push_back({"phong.frag", 12, 3, "warning", "unused <variable> & \"x\""});
    grader::ReportScene same;
    same.name = "sphere";
    same.status = "passed";
    same.score = 5.0;
    same.max_score = 5.0;
    same.metrics.psnr_db = std::numeric_limits<double>::infinity();
    same.metrics.ssim = 1.0;
    same.student_image = "01-phong/sphere/student.png";
    grader::ReportScene off;
    off.name = "torus";
    off.status = "failed";
    off.score = 2.5;
    off.max_score = 5.0;
    off.message = "PSNR 20.0 dB is below 30.0 dB";
    off.first_failing_pass = "shade";
    off.metrics.psnr_db = 20.0;
    off.metrics.ssim = 0.8;
    off.metrics.flip_mean = 0.12;
    off.metrics.mismatch_fraction = 0.25;
    off.metrics.nan_count = 3;
    off.worst_region = {4, 5, 19, 20};
    off.hint = {"blinn-phong", "Blinn's half vector: the highlight has the wrong shape", "shade", 52.5};
    grader::ReportPass pass;
    pass.name = "shade";
    pass.pass = "shade";
    pass.reasons = {"PSNR 20.0 dB is below 30.0 dB"};
    pass.metrics = off.metrics;
    pass.metrics.ssim = 0.94996;  // rounds to the threshold with 3 or 4 decimals
    pass.thresholds = {true, 30.0, 0.95, 0.05, 0.01, 0.05};
    pass.width = 64;
    pass.height = 32;
    pass.worst_region = {4, 5, 19, 20};
    pass.zoom_region = {0, 0, 31, 31};
    pass.student_image = "01-phong/torus/student.png";
    pass.reference_image = "01-phong/torus/reference.png";
    pass.diff_image = "01-phong/torus/diff.png";
    pass.signed_image = "01-phong/torus/signed.png";
    pass.zoom_image = "01-phong/torus/zoom.png";
    off.passes.push_back(pass);
    built.scenes = {same, off};
    grader::ReportGoal lit;
    lit.id = "diffuse";
    lit.title = "Diffuse term";
    lit.points = 7.5;
    lit.met = true;
    lit.judged = "alone";
    lit.whole_failing = {"torus/shade"};
    lit.judged_with = {"phong.frag: main"};
    grader::ReportGoal lobe;
    lobe.id = "highlight";
    lobe.title = "Phong highlight";
    lobe.points = 2.5;
    lobe.failing = {"torus/shade"};
    lobe.scenes = {"torus"};
    lobe.judged = "whole";
    lobe.judged_note = "phong.frag has no function `float highlight(vec3 n)`";
    built.goals = {lit, lobe};

    grader::ReportLab broken;
    broken.id = "02-toon";
    broken.status = "compile_error";
    broken.max_score = 10.0;
    broken.message = "toon.frag:7: syntax error";
    broken.diagnostics.push_back({"toon.frag", 7, 13, "error", "missing `;` at the end of this line",
                                  "Every statement ends with `;`.", "\tfloat d = a < b",
                                  "0:8(2): syntax error", 2});
    r.labs = {built, broken};
    return r;
}

TEST(ReportJson, RoundTripsEveryField) {
    const grader::Report in = sampleReport();
    const std::string text = grader::reportToJson(in);
    grader::Report out;
    std::string error;
    ASSERT_TRUE(grader::reportFromJson(text, &out, &error)) << error;
    EXPECT_EQ(out.submission, in.submission);
    EXPECT_EQ(out.backend, "egl");
    EXPECT_DOUBLE_EQ(out.score, 7.5);
    ASSERT_EQ(out.labs.size(), 2u);
    EXPECT_EQ(out.labs[1].status, "compile_error");
    EXPECT_EQ(out.labs[1].diagnostics[0].line, 7);
    EXPECT_EQ(out.labs[0].diagnostics[0].message, in.labs[0].diagnostics[0].message);
    const grader::ReportDiagnostic& d = out.labs[1].diagnostics[0];
    EXPECT_EQ(d.column, 13);
    EXPECT_EQ(d.explanation, "Every statement ends with `;`.");
    EXPECT_EQ(d.source_line, "\tfloat d = a < b");
    EXPECT_EQ(d.driver_message, "0:8(2): syntax error");
    EXPECT_EQ(d.follow_on, 2);
    ASSERT_EQ(out.labs[0].scenes.size(), 2u);
    EXPECT_TRUE(std::isinf(out.labs[0].scenes[0].metrics.psnr_db));
    EXPECT_DOUBLE_EQ(out.labs[0].scenes[1].metrics.psnr_db, 20.0);
    EXPECT_EQ(out.labs[0].scenes[1].metrics.nan_count, 3u);
    EXPECT_EQ(out.labs[0].scenes[1].worst_region.x1, 19);
    EXPECT_EQ(out.labs[0].scenes[1].first_failing_pass, "shade");
    EXPECT_TRUE(out.labs[0].scenes[0].first_failing_pass.empty());
    EXPECT_EQ(out.labs[0].scenes[1].passes.at(0).reasons, in.labs[0].scenes[1].passes[0].reasons);
    ASSERT_EQ(out.labs[0].goals.size(), 2u);
    EXPECT_TRUE(out.labs[0].goals[0].met);
    EXPECT_EQ(out.labs[0].goals[1].failing, std::vector<std::string>{"torus/shade"});
    EXPECT_EQ(out.labs[0].goals[1].scenes, std::vector<std::string>{"torus"});
    EXPECT_EQ(out.labs[0].goals[0].judged, "alone");
    EXPECT_EQ(out.labs[0].goals[0].whole_failing, std::vector<std::string>{"torus/shade"});
    EXPECT_EQ(out.labs[0].goals[0].judged_with, std::vector<std::string>{"phong.frag: main"});
    EXPECT_TRUE(out.labs[0].goals[1].judged_with.empty());
    EXPECT_EQ(out.labs[0].goals[1].judged_note, in.labs[0].goals[1].judged_note);
    // The optional fields of schema 2.
    const grader::ReportPass& pass = out.labs[0].scenes[1].passes.at(0);
    EXPECT_TRUE(pass.thresholds.known);
    EXPECT_DOUBLE_EQ(pass.thresholds.ssim_min, 0.95);
    EXPECT_DOUBLE_EQ(pass.thresholds.pixel_tolerance, 0.05);
    EXPECT_EQ(pass.width, 64);
    EXPECT_EQ(pass.zoom_region.x1, 31);
    EXPECT_EQ(pass.signed_image, "01-phong/torus/signed.png");
    EXPECT_EQ(pass.zoom_image, "01-phong/torus/zoom.png");
    EXPECT_EQ(out.labs[0].scenes[1].hint.mistake, "blinn-phong");
    EXPECT_DOUBLE_EQ(out.labs[0].scenes[1].hint.psnr_db, 52.5);
    EXPECT_TRUE(out.labs[0].scenes[0].hint.mistake.empty());
    // Writing what was read gives the same text: nothing is lost or reinterpreted.
    EXPECT_EQ(grader::reportToJson(out), text);
}

TEST(ReportJson, InfinityIsNullWithIdenticalFlag) {
    const auto j = nlohmann::json::parse(grader::reportToJson(sampleReport()));
    const auto& m = j["labs"][0]["scenes"][0]["metrics"];
    EXPECT_TRUE(m["psnr_db"].is_null());
    EXPECT_TRUE(m["identical"].get<bool>());
    EXPECT_FALSE(j["labs"][0]["scenes"][1]["metrics"]["identical"].get<bool>());
    EXPECT_EQ(j["schema_version"], grader::kReportSchemaVersion);
}

// The explanation fields are optional within schema 2: absent when empty, defaults when read.
TEST(ReportJson, DiagnosticExtrasAreOptional) {
    const auto j = nlohmann::json::parse(grader::reportToJson(sampleReport()));
    const auto& plain = j["labs"][0]["diagnostics"][0];
    EXPECT_FALSE(plain.contains("explanation"));
    EXPECT_FALSE(plain.contains("follow_on"));
    EXPECT_TRUE(j["labs"][1]["diagnostics"][0].contains("source_line"));
    grader::Report out;
    std::string error;
    ASSERT_TRUE(grader::reportFromJson(R"({"schema_version": 2, "labs": [{"id": "01-phong", "diagnostics": [
        {"file": "phong.frag", "line": 26, "column": 2, "severity": "error", "message": "old"}]}]})",
                                       &out, &error))
        << error;
    const grader::ReportDiagnostic& d = out.labs.at(0).diagnostics.at(0);
    EXPECT_EQ(d.line, 26);
    EXPECT_TRUE(d.explanation.empty() && d.source_line.empty() && d.driver_message.empty());
    EXPECT_EQ(d.follow_on, 0);
}

// The source line, a caret under the column (tabs kept so it lines up), the explanation and the
// count of dropped follow-on errors; the column itself is not repeated in the header.
TEST(FormatDiagnostic, ShowsLineCaretAndExplanation) {
    const grader::ReportDiagnostic d = sampleReport().labs[1].diagnostics[0];
    EXPECT_EQ(grader::formatDiagnostic(d, "02-toon/", "  "),
              "  02-toon/toon.frag:7: error: missing `;` at the end of this line\n"
              "   7 | \tfloat d = a < b\n"
              "     | \t           ^\n"
              "     = Every statement ends with `;`. (2 more errors after this one, probably caused by it)");
    grader::ReportDiagnostic bare{"lab.json", 0, 0, "warning", "no output writes attachment 'color'"};
    EXPECT_EQ(grader::formatDiagnostic(bare), "lab.json: warning: no output writes attachment 'color'");
    grader::ReportDiagnostic no_caret = d;
    no_caret.column = 0;
    no_caret.follow_on = 0;
    EXPECT_EQ(grader::formatDiagnostic(no_caret).find('^'), std::string::npos);
}

TEST(ReportJson, RejectsOtherSchemaVersions) {
    grader::Report out;
    std::string error;
    EXPECT_FALSE(grader::reportFromJson("{\"schema_version\": 99}", &out, &error));
    EXPECT_NE(error.find("99"), std::string::npos);
    EXPECT_FALSE(grader::reportFromJson("not json", &out, &error));
}

TEST(ReportGradescope, OneTestPerGoalAndOnePerBrokenLab) {
    const auto j = nlohmann::json::parse(grader::reportToGradescope(sampleReport()));
    EXPECT_DOUBLE_EQ(j["score"].get<double>(), 7.5);
    ASSERT_EQ(j["tests"].size(), 3u);
    EXPECT_EQ(j["tests"][0]["name"], "01-phong / Diffuse term");
    EXPECT_EQ(j["tests"][0]["status"], "passed");
    EXPECT_DOUBLE_EQ(j["tests"][0]["score"].get<double>(), 7.5);
    EXPECT_EQ(j["tests"][1]["status"], "failed");
    EXPECT_DOUBLE_EQ(j["tests"][1]["score"].get<double>(), 0.0);
    EXPECT_DOUBLE_EQ(j["tests"][1]["max_score"].get<double>(), 2.5);
    // The failing check is named with the scene's reasons and the known mistake, in html.
    const std::string lobe = j["tests"][1]["output"].get<std::string>();
    EXPECT_EQ(j["tests"][1]["output_format"], "html");
    EXPECT_NE(lobe.find("<h4>torus (shade)</h4>"), std::string::npos) << lobe;
    EXPECT_NE(lobe.find("PSNR 20.0 dB is below 30.0 dB"), std::string::npos) << lobe;
    EXPECT_NE(lobe.find("known mistake"), std::string::npos) << lobe;
    EXPECT_EQ(lobe.find("<img"), std::string::npos);  // no folder given: no pictures
    EXPECT_NE(j["output"].get<std::string>().find("Look here first"), std::string::npos);
    EXPECT_EQ(j["tests"][2]["name"], "02-toon");
    EXPECT_NE(j["tests"][2]["output"].get<std::string>().find("toon.frag:7"), std::string::npos);
    EXPECT_NE(j["tests"][2]["output"].get<std::string>().find("Every statement ends with"),
              std::string::npos);
    for (const auto& t : j["tests"]) EXPECT_EQ(t["visibility"], "visible");
}

TEST(ReportJunit, CountsFailuresAndEscapes) {
    const std::string x = grader::reportToJunit(sampleReport());
    EXPECT_NE(x.find("<testsuites name=\"shaderlab\" tests=\"3\" failures=\"2\">"), std::string::npos) << x;
    EXPECT_NE(x.find("name=\"build\""), std::string::npos);
    EXPECT_EQ(x.find("<variable>"), std::string::npos);
}

TEST(ReportHtml, EscapesStudentTextAndLinksImages) {
    const std::string h = grader::reportToHtml(sampleReport());
    EXPECT_EQ(h.find("<variable>"), std::string::npos);
    EXPECT_NE(h.find("&lt;variable&gt; &amp; &quot;x&quot;"), std::string::npos);
    EXPECT_NE(h.find("src=\"01-phong/sphere/student.png\""), std::string::npos);
    // The student's own line is escaped too, with the caret under it.
    EXPECT_NE(h.find("7 | \tfloat d = a &lt; b\n"), std::string::npos);
    EXPECT_NE(h.find("= Every statement ends with `;`."), std::string::npos);
    EXPECT_NE(h.find("src=\"01-phong/torus/signed.png\""), std::string::npos);
    EXPECT_NE(h.find("linked from the folders beside this page"), std::string::npos);
    EXPECT_EQ(h.find("<script"), std::string::npos);
}

TEST(ReportHtml, SummarySaysWhereToLookFirst) {
    const std::string h = grader::reportToHtml(sampleReport());
    const std::size_t first = h.find("Look here first");
    ASSERT_NE(first, std::string::npos);
    // The first goal not met, its first failing scene, linked to that scene's section.
    EXPECT_NE(h.find("href=\"#scene-01-phong--torus\"", first), std::string::npos);
    EXPECT_NE(h.find("id=\"scene-01-phong--torus\""), std::string::npos);
    EXPECT_NE(h.find("Phong highlight", first), std::string::npos);
    EXPECT_NE(h.find("This looks like a known mistake:</b> Blinn&#39;s half vector"), std::string::npos);
    EXPECT_NE(h.find("1 of 2</b> scenes pass"), std::string::npos);
    // Partial credit is explained with the goals.
    EXPECT_NE(h.find("Points follow the learning goals"), std::string::npos);
    EXPECT_NE(h.find("Here 1 of 2 goals are met: 7.50 of 10.00 points"), std::string::npos);
}

TEST(ReportHtml, MetricsBesideThresholdsNeverReadEqualWhenFailing) {
    const std::string h = grader::reportToHtml(sampleReport());
    // SSIM 0.94996 against 0.950: printed with the decimals that tell them apart, and a margin
    // that does not read 0.
    EXPECT_NE(h.find("<td class=\"num\">0.94996</td><td class=\"num\">\xE2\x89\xA5 0.95000</td>"),
              std::string::npos);
    EXPECT_NE(h.find("short by 0.00004"), std::string::npos);
    EXPECT_EQ(h.find(">0.950</td><td class=\"num\">\xE2\x89\xA5 0.950<"), std::string::npos);
    EXPECT_NE(h.find("<td class=\"num\">20.0 dB</td><td class=\"num\">\xE2\x89\xA5 30.0 dB</td>"),
              std::string::npos);
    EXPECT_NE(h.find("short by 10.0 dB"), std::string::npos);
    // The worst region is boxed over the pictures, in percent of the image.
    EXPECT_NE(h.find("class=\"box\" style=\"left:0.000%;top:0.000%;width:50.000%;height:100.000%\""),
              std::string::npos);
}

fs::path writePictures(const std::string& name, int size) {
    const fs::path root = fs::temp_directory_path() / ("shaderlab_report_" + name);
    fs::remove_all(root);
    fs::create_directories(root / "01-phong/torus");
    fs::create_directories(root / "01-phong/sphere");
    const grader::Image picture(size, size, 3, 0.5f);
    std::string error;
    for (const char* p :
         {"01-phong/torus/student.png", "01-phong/torus/reference.png", "01-phong/torus/diff.png",
          "01-phong/torus/signed.png", "01-phong/torus/zoom.png", "01-phong/sphere/student.png"})
        EXPECT_TRUE(grader::writePng(picture, (root / p).string(), &error)) << error;
    return root;
}

TEST(ReportHtml, EmbedsPicturesWithinItsBudgetOrLinksThemAll) {
    const fs::path root = writePictures("embed", 8);
    const std::string embedded = grader::reportToHtml(sampleReport(), {root.string(), 1u << 20});
    EXPECT_EQ(embedded.find("src=\"01-phong/"), std::string::npos);
    EXPECT_NE(embedded.find("src=\"data:image/png;base64,iVBORw0KGgo"), std::string::npos);
    EXPECT_NE(embedded.find("embedded in this page"), std::string::npos);
    // Over the budget: every picture linked, none embedded.
    const std::string linked = grader::reportToHtml(sampleReport(), {root.string(), 100});
    EXPECT_EQ(linked.find("data:image"), std::string::npos);
    EXPECT_NE(linked.find("src=\"01-phong/torus/zoom.png\""), std::string::npos);
    // A missing file: linked too.
    fs::remove(root / "01-phong/torus/zoom.png");
    EXPECT_EQ(grader::reportToHtml(sampleReport(), {root.string(), 1u << 20}).find("data:image"),
              std::string::npos);
}

TEST(ReportGradescope, CarriesTheFailingPicturesWithinItsBudget) {
    const fs::path root = writePictures("gradescope", 8);
    const auto j =
        nlohmann::json::parse(grader::reportToGradescope(sampleReport(), {root.string(), 1u << 20}));
    const std::string lobe = j["tests"][1]["output"].get<std::string>();
    // Yours, the reference, the signed difference and the FLIP map of the failing check.
    std::size_t images = 0;
    for (std::size_t at = lobe.find("<img src=\"data:image/png;base64,"); at != std::string::npos;
         at = lobe.find("<img src=\"data:image/png;base64,", at + 1))
        ++images;
    EXPECT_EQ(images, 4u) << lobe;
    EXPECT_EQ(j["tests"][0]["output"].get<std::string>().find("<img"),
              std::string::npos);  // met: no pictures
    // A tiny budget leaves them out and says so.
    const auto small = nlohmann::json::parse(grader::reportToGradescope(sampleReport(), {root.string(), 10}));
    EXPECT_EQ(small["tests"][1]["output"].get<std::string>().find("<img"), std::string::npos);
    EXPECT_NE(small["output"].get<std::string>().find("left out"), std::string::npos);
}

TEST(ReportHtml, OlderReportsWithoutThresholdsStillRender) {
    grader::Report r = sampleReport();
    r.labs[0].scenes[1].passes[0].thresholds = {};
    const std::string h = grader::reportToHtml(r);
    EXPECT_NE(h.find("<td class=\"num\">0.950</td><td class=\"num\"></td>"), std::string::npos);
    r.labs[0].scenes[1].passes.clear();  // no passes at all: the scene's own pictures
    EXPECT_NE(grader::reportToHtml(r).find("id=\"scene-01-phong--torus\""), std::string::npos);
}

}  // namespace

// Runs of plain ASCII are copied whole; every byte around them still gets its own treatment.
TEST(ReportMarkup, EscapesEveryKindOfByteInsideAndBetweenPlainRuns) {
    const std::string base64_run(5000, 'Q');
    const std::string in = "ab&c<d>e\"f'g\x01h\ni\tj\r" + base64_run + "\xC3\xA9k\xFFl\x7Fm\xE2\x82";
    const std::string expected =
        "ab&amp;c&lt;d&gt;e&quot;f&#39;g?h\ni\tj\r" + base64_run + "\xC3\xA9k?l\x7Fm??";
    EXPECT_EQ(grader::escapeMarkup(in), expected);
    EXPECT_EQ(grader::escapeMarkup(""), "");
    EXPECT_EQ(grader::escapeMarkup("plain"), "plain");
}

TEST(ReportGoalJudgement, SaysHowEachGoalWasJudged) {
    grader::ReportGoal g;
    g.met = true;
    EXPECT_EQ(grader::goalJudgement(g), "");  // an older report, or met on the whole shaders
    g.judged = "whole";
    EXPECT_EQ(grader::goalJudgement(g), "");
    g.judged = "alone";
    g.whole_failing = {"torus/shade"};
    EXPECT_EQ(grader::goalJudgement(g),
              "Your own work for it is right: its pictures fail only because of another part.");
    g.met = false;
    EXPECT_NE(grader::goalJudgement(g).find("still wrong"), std::string::npos);
    g.judged_with = {"grayscale.frag: main"};
    EXPECT_EQ(grader::goalJudgement(g),
              "Judged on your own work for it (with your changes to grayscale.frag: main, code the starter "
              "gave that uses it), the rest taken from the reference solution: still wrong.");
    g.judged_with.push_back("sobel.frag: main");
    EXPECT_NE(grader::goalJudgement(g).find("grayscale.frag: main and sobel.frag: main,"), std::string::npos);
    g.judged_with.clear();
    g.judged = "whole";
    g.judged_note = "phong.frag has no function `vec3 diffuse(vec3 n)`";
    EXPECT_EQ(
        grader::goalJudgement(g),
        "Judged on your whole shaders, because your work for it could not be taken alone: phong.frag has no "
        "function `vec3 diffuse(vec3 n)`.");
    // The report page says it beside the goal, escaped.
    grader::Report r;
    grader::ReportLab lab;
    lab.id = "01-phong";
    lab.goals = {g};
    r.labs = {lab};
    EXPECT_NE(grader::reportToHtml(r).find("could not be taken alone: phong.frag has no function `vec3 "
                                           "diffuse(vec3 n)`."),
              std::string::npos);
}
