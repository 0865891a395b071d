// `shaderlab corpus --margins`: how far each verdict of a lab's corpus is from turning. Reads the
// report.json that `corpus` wrote for the reference and every case, and for each graded image
// puts every metric beside its threshold as a factor (above 1: on the passing side), prints a
// table and a summary, and writes <out>/<lab>/margins.json. Advice for the instructor choosing
// scenes and thresholds: it grades nothing, judges nothing and never fails the corpus run.
//
// The factor of one metric, "how many times the error may grow (or must shrink) before the
// verdict turns", with the error measured so that a factor means the same on every metric:
//   PSNR               10^((psnr_db - psnr_min_db) / 10), the ratio of the MSEs (identical: infinite)
//   SSIM               (1 - ssim_min) / (1 - ssim), SSIM's distance from 1 (1: infinite)
//   FLIP, mismatch     limit / value (0: infinite)
// A passing image holds by its smallest factor (the metric closest to failing); a failing one by
// the inverse of it, the metric that fails by the most, since one failing metric is enough.
#pragma once

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "shaderlab/authoring/corpus_cases.h"
#include "shaderlab/lab/lab_spec.h"

namespace shaderlab::authoring {

// For the lab `spec` whose corpus `cases` were graded into `lab_out`/reports/<case>/report.json
// (the reference's under "reference"): prints the margins table and summary, writes
// `lab_out`/margins.json, and returns for each case name (reference included) its entry for
// corpus.json's `margins` field. A report that cannot be read is named in the table and skipped.
std::map<std::string, nlohmann::json> reportLabMargins(const LabSpec& spec, const std::vector<Case>& cases,
                                                       const std::filesystem::path& lab_out);

// One graded image's verdict and the factor by which it holds, as the table above gives it:
// `judged` is the image's entry in report.json (a scene's "passes" item, or its
// "on_reference_inputs"), `thresholds` that entry's "thresholds" (null: the lab's). `margin` is
// NaN for an image that failed on something no threshold measures (NaN pixels), `reason` then
// saying what; `limiting` names the metric that sets it.
struct VerdictMargin {
    bool passed = false;
    double margin = 0.0;
    std::string limiting, reason;
};
VerdictMargin verdictMargin(const nlohmann::json& judged, const nlohmann::json& thresholds,
                            const GradingThresholds& lab);

// A factor as the table prints it: "2.5x", ">1000x", "inf", "n/a" (NaN).
std::string factorText(double f);

}  // namespace shaderlab::authoring
