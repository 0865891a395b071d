// Internal: the html pieces of Gradescope's output, written with the HTML report's helpers
// (report_markup.cpp) and placed into results.json by report_json.cpp.
#pragma once

#include <string>

#include "embed.h"
#include "grader/reports/report.h"

namespace grader::detail {

// A goal's test output: met or not, and for each failing check its reasons, a known-mistake hint
// and its pictures while `budget` lasts.
std::string gradescopeGoalHtml(const ReportLab& lab, const ReportGoal& goal, Budget& budget);

// Where to look first (the HTML report's summary box).
std::string gradescopeSummaryHtml(const Report& report);

}  // namespace grader::detail
