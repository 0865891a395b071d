// Turns a lab's lab.json into the typed, validated LabSpec of lab_spec.h.
//
// The work happens in separate steps:
//   1. load      read the file (size-capped), parse the JSON text, report syntax errors with a
//                line and column; refuse duplicate keys (the DOM would silently keep one), very
//                deep nesting and very long strings (both before any recursive code sees them);
//   2. schema    check the DOM against docs/lab.schema.json with a packaged validator
//                (json_schema_check.h): types, allowed values, ranges, names, unknown keys;
//   3. read      expand templates and walk the DOM into a LabSpec (types are known good now);
//   4. validate  what a schema cannot say: unique names, references between passes, targets,
//                attachments, scenes and goals, reads before writes, repeat groups, the disk;
//   5. complete  the defaults that depend on other fields (clears of later writers, the last
//                pass graded, implicit goals, compare modes).
// Every problem is collected as "<origin>: <json path>: <problem>"; steps 3-5 run only on a file
// the schema accepts, so one mistake gives one message rather than a cascade. Steps 1, 3 and 4
// have files of their own (lab_spec_load.cpp, lab_spec_read*.cpp, lab_spec_check_*.cpp, sharing
// lab_spec_steps.h); this file holds the schema step, the order of the checks, the completion and
// the public functions of lab_spec.h.
//
// It does not load scenes, images or shaders (the renderer does), and knows no lab by name.
#include "shaderlab/lab/lab_spec.h"

#include <algorithm>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include "lab_spec_steps.h"
#include "shaderlab/base/json_messages.h"
#include "shaderlab/base/paths.h"
#include "shaderlab/lab/json_schema_check.h"

namespace shaderlab {

extern const char* const kLabSchemaJson;  // generated from docs/lab.schema.json

using namespace lab_spec_detail;

namespace {

// =============================================================================================
// Step 2: schema

const json& labSchema() {
    static const json schema = json::parse(kLabSchemaJson);
    return schema;
}

const JsonSchemaChecker& labSchemaChecker() {
    static const JsonSchemaChecker checker(labSchema());
    return checker;
}

}  // namespace

// =============================================================================================
// Step 4: validate

namespace lab_spec_detail {

void Validator::run() {
    if (check_disk_) checkId();
    collectTargets();
    resolvePassTargets();
    buildLoops();
    checkInputs();
    checkPassReferences();
    checkGraded();
    checkCameras();
    checkScenes();
    checkGoals();
    checkGoalWork();
    checkWork();
    if (check_disk_) checkFiles();
}

}  // namespace lab_spec_detail

namespace {

// =============================================================================================
// Step 5: complete

void complete(LabSpec& spec) {
    if (spec.title.empty()) spec.title = spec.id;
    if (spec.student_files.empty()) {
        for (const PassSpec& p : spec.passes) {
            for (const std::string* f : {&p.program.vertex, &p.program.fragment}) {
                if (isSharedPath(*f)) continue;
                if (std::find(spec.student_files.begin(), spec.student_files.end(), *f) ==
                    spec.student_files.end())
                    spec.student_files.push_back(*f);
            }
        }
    }
}

LabSpecResult parse(const std::string& text, const std::string& origin, const std::string& lab_dir,
                    bool check_disk) {
    LabSpecResult result;
    Diagnostics diag(origin);
    LabSpec& spec = result.spec;
    std::error_code ec;
    fs::path dir = fs::absolute(lab_dir, ec).lexically_normal();
    if (dir.has_filename() == false) dir = dir.parent_path();
    spec.lab_dir = dir.string();
    spec.labs_root = dir.parent_path().string();

    json doc;
    if (!loadJson(text, diag, doc)) {
        result.errors = diag.take();
        return result;
    }
    for (const SchemaProblem& p : labSchemaChecker().check(doc)) diag.error(p.path, p.problem);
    if (diag.any()) {
        result.errors = diag.take();
        return result;
    }
    Reader reader(doc, diag, spec);
    reader.run();
    std::vector<PassDraft>& drafts = reader.drafts();
    Validator validator(spec, drafts, diag, check_disk);
    if (!diag.any()) validator.run();
    if (!diag.any()) complete(spec);
    result.errors = diag.take();
    result.ok = result.errors.empty();
    return result;
}

}  // namespace

bool isFloatFormat(TargetFormat f) { return f == TargetFormat::RGBA16F || f == TargetFormat::RGBA32F; }

GradingThresholds ThresholdOverrides::applyTo(GradingThresholds t) const {
    if (psnr_min_db) t.psnr_min_db = *psnr_min_db;
    if (ssim_min) t.ssim_min = *ssim_min;
    if (flip_mean_max) t.flip_mean_max = *flip_mean_max;
    if (mismatch_max) t.mismatch_max = *mismatch_max;
    if (pixel_tolerance) t.pixel_tolerance = *pixel_tolerance;
    return t;
}

bool CameraOverride::any() const {
    return position || target || up || fov_y_deg || z_near || z_far || projection || height || light;
}

const TargetSpec* LabSpec::findTarget(const std::string& name) const {
    for (const TargetSpec& t : targets)
        if (t.name == name) return &t;
    return nullptr;
}

StandInSource standInSource(const LabSpec& spec, std::size_t reader, const PassInput& in) {
    StandInSource out;
    const TargetSpec* t = spec.findTarget(in.target);
    if (in.source != InputSource::Target || in.attachment == "depth" || !t || t->attachments.empty() ||
        reader >= spec.passes.size())
        return out;
    const std::string attachment = in.attachment.empty() ? t->attachments.front() : in.attachment;
    const int loop = spec.passes[reader].loop;
    for (std::size_t j = reader; j-- > 0;) {
        const PassSpec& p = spec.passes[j];
        if (p.target != in.target) continue;
        if ((loop >= 0 && p.loop == loop) ||
            std::find(p.graded.begin(), p.graded.end(), attachment) == p.graded.end())
            return out;
        out.pass = &p;
        out.attachment = attachment;
        return out;
    }
    return out;
}

const PassSpec* LabSpec::findPass(const std::string& name) const {
    for (const PassSpec& p : passes)
        if (p.name == name) return &p;
    return nullptr;
}

const std::string& labSchemaText() {
    static const std::string text = kLabSchemaJson;
    return text;
}

std::string sharedFolder(const std::string& labs_root) { return (fs::path(labs_root) / "shared").string(); }

std::string labFilePath(const LabSpec& spec, const std::string& path) {
    return (fs::path(isSharedPath(path) ? spec.labs_root : spec.lab_dir) / path).string();
}

LabSpecResult parseLabSpec(const std::string& lab_dir) {
    const fs::path file = fs::path(lab_dir) / "lab.json";
    const std::string origin = file.string();
    std::error_code ec;
    if (!fs::is_directory(lab_dir, ec)) {
        // "02-ton": the course's labs beside it are the likely meaning.
        std::vector<std::string> labs;
        const fs::path parent = fs::path(lab_dir).parent_path();
        for (fs::directory_iterator it(parent.empty() ? "." : parent, ec), end; !ec && it != end;
             it.increment(ec))
            if (fs::is_regular_file(it->path() / "lab.json", ec))
                labs.push_back(it->path().filename().string());
        std::sort(labs.begin(), labs.end());
        LabSpecResult r;
        r.errors.push_back(origin + ": the lab folder " + lab_dir + " does not exist" +
                           didYouMean(fs::path(lab_dir).filename().string(), labs));
        return r;
    }
    const FileText t = readFile(file.string(), kMaxLabJsonBytes);
    if (!t.ok) {
        // readFile names the file itself; the message names it once, as the origin.
        std::string problem = fs::exists(file, ec) ? t.error : "file not found";
        if (problem.rfind(origin + ": ", 0) == 0) problem.erase(0, origin.size() + 2);
        LabSpecResult r;
        r.errors.push_back(origin + ": " + problem);
        return r;
    }
    return parse(t.text, origin, lab_dir, true);
}

LabSpecResult parseLabSpecText(const std::string& json_text, const std::string& origin,
                               const std::string& lab_dir) {
    return parse(json_text, origin, lab_dir, true);
}

}  // namespace shaderlab
