// What a corpus case's grade must be (docs/grading.md, "Proof that a grade follows the goals"): the
// reference and an alternative full marks; the starter renders and fails; a broken case ends with
// its status; a mistake fails exactly its goals and those resting on them, each failing goal with
// work of its own judged on that work alone unless the case lists it in `whole`. It judges a
// report; grading the case is the caller's.
#pragma once

#include <string>

#include "grader/reports/report.h"
#include "shaderlab/authoring/corpus_cases.h"
#include "shaderlab/lab/lab_spec.h"

namespace shaderlab::authoring {

// "" when the graded lab `lab` is what case `c` of `spec` must give; otherwise the expectations
// that did not hold, joined with "; ". The kinds "reference" and "starter" are the corpus run's own.
std::string expectationsMissed(const LabSpec& spec, const Case& c, const grader::ReportLab& lab);

}  // namespace shaderlab::authoring
