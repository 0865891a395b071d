// Known-mistake hints: a lab's corpus of mistakes (tests/corpus/<lab>/cases.json) rendered once by
// `shaderlab goldens` and stored beside the goldens as small pictures, so that grading can say
// "this looks like a known mistake: <what it is>" when a failing scene's picture is much closer
// to a mistake's than to the reference, without the corpus or the reference solution at hand.
//
// Storage, per lab: <lab>/hints/hints.json and <lab>/hints/<case>/<scene>.<image>.png, one
// picture per scene the mistake fails (of the scene's first wrong image, as the report shows it),
// `factor` times smaller, 8-bit RGB. Never edited by hand; `shaderlab corpus` fails when stale.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "grader/metrics/image.h"
#include "grader/metrics/mask.h"
#include "grader/reports/report.h"

namespace shaderlab {

struct MistakeHint {
    std::string mistake;  // the corpus case
    std::string about;    // its sentence
    std::string scene;
    std::string image;  // the graded image (a ReportPass name)
    std::string file;   // relative to the hints folder
    grader::Image picture;
};

struct LabHints {
    int factor = 2;             // pictures are stored this many times smaller
    double min_psnr_db = 40.0;  // and match a student's picture from this PSNR up
    std::vector<MistakeHint> hints;
    // Pictures left out because the mistake does not draw them the same way twice (it reads
    // memory nothing wrote): the file names they would have.
    std::vector<std::string> unstable;
    // The GL renderer the pictures were drawn with (GL_RENDERER and GL_VERSION): on the same one
    // a fresh set must equal the stored one to the bit, on another only match it (min_psnr_db).
    std::string renderer;
};

// What a failing picture of a mistake becomes in storage: downsampled, 8-bit RGB.
grader::Image hintPicture(const grader::Image& picture, int factor);

// Reads <hints_dir>/hints.json and its pictures. A lab without the folder has no hints: true with
// none. False with `error` when the folder is there but broken.
bool loadLabHints(const std::string& hints_dir, LabHints* out, std::string* error);

// Writes `hints` (pictures already hintPicture()s) into hints_dir, replacing what was there.
bool writeLabHints(const std::string& hints_dir, const LabHints& hints, std::string* error);

// Mistakes that draw a scene alike cannot be told apart there: drops every picture that matches
// another mistake's picture of the same scene and image (within min_psnr_db).
void dropAmbiguousHints(LabHints* hints);

// A failing scene's first wrong image, as the report shows it.
struct FailingPicture {
    std::string image;        // its ReportPass name
    grader::Image picture;    // the student's (NaN and Inf in magenta)
    grader::Image reference;  // the reference's
    grader::Mask graded;      // the pixels judged
};

// The known mistake behind a submission's failures, per failing scene (keyed by scene name). A
// mistake explains the submission only when every one of its pictures matches: each scene it
// fails, the submission fails too, with the same first wrong image, drawn within min_psnr_db of
// the mistake's and closer to it than to the reference. One matching scene alone proves little
// (an unfinished shader that draws only the ambient light looks like many mistakes somewhere).
// When two mistakes explain a scene, the closer picture wins.
std::map<std::string, grader::ReportHint> explainFailures(
    const LabHints& hints, const std::map<std::string, FailingPicture>& failing);

}  // namespace shaderlab
