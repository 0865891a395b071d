// Reference renders kept between runs. A lab's reference images depend only on the program, the
// renderer, the lab folder, the folders beside the labs and the reference solution; hashed
// together they name a folder of the cache, <cache>/<lab>-<key>/<lab>/ holding golden/ (the
// reference's images, written as `shaderlab goldens` writes them) and hints/ (the lab's, beside
// them as grading reads them). `batch` fills its cache with its workers (plan.h); `grade` and
// `check` fill theirs here, the first time a lab is graded, so a second grade of the same lab
// never renders its reference again. An entry is made in a temporary folder and renamed into
// place, so a reader sees a whole entry or none, whoever else fills the same cache.
#pragma once

#include <string>

#include "shaderlab/batch/batch.h"
#include "shaderlab/gl/gl_context.h"

namespace shaderlab::batch {

// What the lab's reference images depend on, added to `h`: the program (`tool_version`, and the
// size and time of the file `exe`, so that a rebuilt program is another key), `backend`, the
// `renderer` (GL_RENDERER and GL_VERSION), the lab folder `<labs_root>/<lab_id>` (its golden/
// left out when there is a reference solution, which the images are rendered from), every folder
// beside the labs that is not a lab (scenes, shared GLSL), and `<reference_root>/<lab_id>` when
// `reference_root` holds it.
void addReferenceInputs(Hasher* h, const std::string& tool_version, const std::string& exe,
                        const std::string& backend, const std::string& renderer, const std::string& labs_root,
                        const std::string& lab_id, const std::string& reference_root);

struct ReferenceCacheSettings {
    std::string dir;  // the cache folder; created when missing
    std::string tool_version;
    std::string labs_root;
    std::string reference_root;
    Backend backend = Backend::OSMesa;
    int keep_per_lab = 4;  // older entries of a lab (another reference, renderer or program) go
};

// The root holding `<lab_id>/golden/` and `<lab_id>/hints/` for the lab's reference as `renderer`
// draws it: found in the cache, or rendered into it now (writeGoldens, in a child process).
// Empty, with the reason in `error`, when there is no reference solution for the lab or the
// entry cannot be made (an unwritable cache, a reference that does not render): the caller then
// renders the reference itself.
std::string cachedReference(const ReferenceCacheSettings& settings, const std::string& lab_id,
                            const std::string& renderer, std::string* error);

// The entry cachedReference would give for the renderer it was last asked for with this backend
// (remembered in the cache folder), when that entry exists; else empty. It renders nothing, so it
// can run while a student's render does and say which images to read meanwhile.
std::string guessCachedReference(const ReferenceCacheSettings& settings, const std::string& lab_id);

}  // namespace shaderlab::batch
