// `shaderlab scene-sweep` (command_scene_sweep.cpp), its judging side: from the reports of every
// corpus case graded on the candidate scenes, how well each candidate separates each goal's
// mistakes from the alternatives; the ranking, the table and sweep.json. It grades nothing
// (the command does) and writes nothing but what it prints.
//
// Per candidate and goal, with each image's factor as `corpus --margins` computes it (above 1: the
// verdict holds by that factor on the error; corpus_margins.h):
//   a case's pass factor   the smallest factor of its images of the goal's passes, inverted for a
//                          failing image (so below 1 when one fails); each image as the grader
//                          takes it for that goal (on the reference's inputs where pass isolation
//                          judged it, unless the goal is "pipeline")
//   mistake factor         over the goal's mistakes, the smallest of 1 / pass factor: how far the
//                          mistake that is closest to passing fails (below 1: one passes, "misses")
//   alternative factor     over the alternatives, the smallest pass factor (below 1: one fails)
//   separates              every mistake of the goal fails and every alternative passes
//   also fails             a mistake of another goal (not one this goal rests on) that fails here:
//                          the scene does not isolate the goal, and that mistake would lose it
//   score                  min(mistake factor, alternative factor)
// A candidate's problems are its misses, failed alternatives and "also fails" over the goals it is
// judged under, and its score the smallest of their scores; the ranking is fewest problems first,
// then the highest score, then the highest factor among the mistakes it catches (so that among
// scenes that all miss a mistake no single scene of the kind can show, the one that shows the
// others most plainly comes first). A mistake that is not `required` is judged by no candidate
// of its own goals (`--mistake` names the ones a scene is for).
#pragma once

#include <cstddef>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "shaderlab/authoring/corpus_margins.h"
#include "shaderlab/authoring/scene_sweep.h"
#include "shaderlab/lab/lab_spec.h"

namespace shaderlab::authoring::sweep {

// One graded image of one case drawn on one candidate.
struct ImageResult {
    std::string pass;
    VerdictMargin pipeline;     // the case's own pipeline
    bool has_isolated = false;  // judged again on the reference's inputs (pass isolation)
    VerdictMargin isolated;
};

// One corpus case (a mistake or an alternative), with its images on every candidate.
struct CaseResult {
    std::string name, kind;
    std::vector<std::string> fails;  // a mistake's goals
    std::set<std::string> may_fail;  // those and the goals resting on them (expectedFailures)
    bool required = true;  // a mistake its goals' candidates must catch (--mistake names the only ones)
    std::vector<std::string> problems;  // renders that did not give images: "c00-c31: timeout: ..."
    std::map<std::string, std::vector<ImageResult>> images;  // candidate id -> its graded images
};

// Adds the images of `report_lab` (one lab of a report.json) to `out`, for the candidates among
// `candidates` whose scenes it holds (a scene with "times" gives "c03_t0", "c03_t1", ...).
void collectImages(const nlohmann::json& report_lab, const std::vector<Candidate>& candidates,
                   const GradingThresholds& lab, CaseResult* out);

// How one case does on one goal of one candidate.
struct CaseOnGoal {
    std::string name;
    std::string goal;        // a mistake's (first) goal
    double factor = 0.0;     // a mistake of the goal: how far it fails; any other case: how far it passes
    bool as_wanted = false;  // a mistake of the goal fails; an alternative or another goal's mistake passes
};

struct GoalScore {
    std::string goal;
    std::vector<CaseOnGoal> mistakes, alternatives, others;
    double mistake_factor = 0.0, alternative_factor = 0.0, isolation_factor = 0.0;  // +inf: no such case
    bool separates = false, isolates = false;
    double score = 0.0;
    double caught_factor = 0.0;  // the smallest factor of the mistakes it catches (+inf: none)
    int problems = 0;
};

struct CandidateScore {
    std::size_t candidate = 0;  // index into the candidates
    std::vector<GoalScore> goals;
    int problems = 0;
    double score = 0.0;
    double caught_factor = 0.0;
};

// Every candidate judged under `goals`, best first (see the top of this file).
std::vector<CandidateScore> rankCandidates(const LabSpec& spec, const std::vector<Candidate>& candidates,
                                           const std::vector<std::string>& goals,
                                           const std::vector<CaseResult>& cases);

// The ranked table: a row per candidate and goal with the varied values, then a line for each
// kind of problem.
void printRanking(const std::vector<Candidate>& candidates, const std::vector<Variation>& vary,
                  const std::vector<CandidateScore>& ranked);

// The scene to paste into lab.json for `c`, named `<base>_<id>`.
ojson pasteableScene(const Candidate& c, const std::string& base_name);

// Every candidate, best first, with its values, scene, picture and per-goal scores.
ojson rankingJson(const std::vector<Candidate>& candidates, const std::vector<Variation>& vary,
                  const std::vector<CandidateScore>& ranked, const std::string& base_name);

}  // namespace shaderlab::authoring::sweep
