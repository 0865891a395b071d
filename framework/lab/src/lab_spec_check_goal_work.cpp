// Step 4 of the lab.json parser, for goal isolation: a goal's "work" names student files, and
// functions the starter declares (a student cannot be asked to keep a function the starter does not
// give), and a goal judged on its own work rests on no other goal. The starter is read only when
// the parser looks at the disk.
#include <algorithm>
#include <string>

#include "lab_spec_steps.h"
#include "shaderlab/base/paths.h"
#include "shaderlab/glsl/glsl_outline.h"

namespace shaderlab::lab_spec_detail {

void Validator::checkGoalWork() {
    for (std::size_t i = 0; i < spec_.goals.size(); ++i) {
        const GoalSpec& g = spec_.goals[i];
        if (g.work.empty()) continue;
        const std::string path = joinIndex("goals", i);
        if (!g.depends_on.empty())
            diag_.error(
                joinKey(path, "depends_on"),
                "a goal with \"work\" is judged on the student's own work for it and rests on no other "
                "goal; leave \"depends_on\" out");
        if (g.pipeline)
            diag_.error(
                joinKey(path, "pipeline"),
                "a goal with \"work\" is judged on its own work, not on the student's pipeline; leave "
                "\"pipeline\" out");
        for (std::size_t k = 0; k < g.work.size(); ++k) {
            const GoalWork& w = g.work[k];
            const std::string at = joinIndex(joinKey(path, "work"), k);
            if (std::find(spec_.student_files.begin(), spec_.student_files.end(), w.file) ==
                spec_.student_files.end()) {
                diag_.error(at, quoteJson(w.file) + " is not one of the lab's student_files" +
                                    didYouMean(w.file, spec_.student_files));
                continue;
            }
            if (w.function.empty() || !check_disk_) continue;
            const FileText starter = readFileInside(spec_.lab_dir, w.file);
            if (!starter.ok) continue;  // checkFiles says why
            const glsl::Outline outline = glsl::outlineGlsl(starter.text);
            const std::vector<const glsl::Declaration*> found = glsl::declarationsNamed(outline, w.function);
            if (std::none_of(found.begin(), found.end(),
                             [](const glsl::Declaration* d) { return d->kind == glsl::DeclKind::Function; }))
                diag_.error(at,
                            "the starter's " + w.file + " has no function `" + w.function +
                                "`: a goal's work is a function the starter gives the student to fill in");
        }
    }
}

}  // namespace shaderlab::lab_spec_detail
