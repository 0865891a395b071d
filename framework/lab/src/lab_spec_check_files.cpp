// Step 4 of the lab.json parser, on disk: the id matching the lab folder, and every file lab.json
// names (programs, textures, cube faces, student files, scenes) being a regular file inside the
// lab folder, or inside the course's shared folder for shared/... paths. Skipped when the parser
// is told not to look at the disk.
#include <string>
#include <system_error>

#include "lab_spec_steps.h"
#include "shaderlab/base/paths.h"

namespace shaderlab::lab_spec_detail {

bool isSharedPath(const std::string& p) { return p.rfind("shared/", 0) == 0; }

void Validator::checkId() {
    const std::string folder = fs::path(spec_.lab_dir).filename().string();
    if (spec_.id != folder)
        diag_.error("id", "is " + quoteJson(spec_.id) + " but the lab folder is " + quoteJson(folder) +
                              "; they must be the same");
}

// A file named in lab.json: a regular file inside the lab folder, or inside labs/shared for
// shared/... paths.
void Validator::checkFile(const std::string& path, const std::string& file) {
    const bool shared = isSharedPath(file);
    const PathResult r = resolveInside(shared ? spec_.labs_root : spec_.lab_dir, file);
    if (!r.ok) diag_.error(path, r.error);
}

void Validator::checkFiles() {
    std::error_code ec;
    if (fs::exists(fs::path(spec_.lab_dir) / "shared", ec))
        diag_.error("",
                    "the lab folder has a sub-folder \"shared\", which would hide the course's shared folder "
                    "(labs/shared/) from its paths; rename it");
    for (const PassSpec& p : spec_.passes) {
        checkFile(joinKey(joinKey(p.path, "program"), "vertex"), p.program.vertex);
        checkFile(joinKey(joinKey(p.path, "program"), "fragment"), p.program.fragment);
        for (const PassInput& in : p.inputs) {
            if (in.source == InputSource::File) checkFile(joinKey(in.path, "texture"), in.file);
            for (std::size_t k = 0; k < in.cube_files.size(); ++k)
                checkFile(joinIndex(joinKey(in.path, "cube"), k), in.cube_files[k]);
        }
    }
    for (std::size_t k = 0; k < spec_.student_files.size(); ++k) {
        const std::string& f = spec_.student_files[k];
        const std::string path = joinIndex("student_files", k);
        if (isSharedPath(f)) {
            diag_.error(path, "a shared file cannot be a student file (every lab would share one copy)");
            continue;
        }
        checkFile(path, f);
    }
    std::set<std::string> checked;
    for (const SceneSpec& s : spec_.scenes) {
        if (s.file.empty() || !checked.insert(s.path.substr(0, s.path.find(".times"))).second) continue;
        const PathResult r = resolveInside(spec_.labs_root, s.file);
        if (!r.ok) diag_.error(joinKey(s.path.substr(0, s.path.find(".times")), "file"), r.error);
    }
}

}  // namespace shaderlab::lab_spec_detail
