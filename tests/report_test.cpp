// The report writers: report.json round-trips through its reader, infinity and hostile text
// survive every format, and the Gradescope and JUnit shapes hold what their consumers read.
#include "grader/report.h"

#include <gtest/gtest.h>

#include <limits>
#include <nlohmann/json.hpp>

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
    grader::ReportPass pass;
    pass.name = "shade";
    pass.reasons = {"PSNR 20.0 dB is below 30.0 dB"};
    pass.metrics = off.metrics;
    off.passes.push_back(pass);
    built.scenes = {same, off};
    grader::ReportGoal lit;
    lit.id = "diffuse";
    lit.title = "Diffuse term";
    lit.points = 7.5;
    lit.met = true;
    grader::ReportGoal lobe;
    lobe.id = "highlight";
    lobe.title = "Phong highlight";
    lobe.points = 2.5;
    lobe.failing = {"torus/shade"};
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
    // The failing check is named with the scene's reasons.
    EXPECT_NE(j["tests"][1]["output"].get<std::string>().find("torus/shade: PSNR 20.0"), std::string::npos);
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
    EXPECT_NE(h.find("&infin;"), std::string::npos);
    EXPECT_NE(h.find("first failing pass"), std::string::npos);
    // The student's own line is escaped too, with the caret under it.
    EXPECT_NE(h.find("7 | \tfloat d = a &lt; b\n"), std::string::npos);
    EXPECT_NE(h.find("= Every statement ends with `;`."), std::string::npos);
}

}  // namespace
