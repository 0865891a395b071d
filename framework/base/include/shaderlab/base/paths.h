// The one path resolver. Lab files (lab.json, scenes, textures) are resolved against the labs
// root; student files against the submission folder. Nothing is resolved against the working
// directory, and a student file may not leave its folder: an absolute path, a ".." that climbs
// out, or a symlink whose target lies outside is refused (student code is untrusted).
#pragma once

#include <cstddef>
#include <string>

namespace shaderlab {

struct PathResult {
    bool ok = false;
    // !ok because the file is not there for the submission: absent, a broken link, or a link or
    // `..` leading outside the root (not: a folder or other non-file in its place).
    bool missing = false;
    std::string path;   // absolute, canonical when ok
    std::string error;  // "<root>/<relative>: <problem>" when !ok
};

// Resolves `relative` inside `root`. The file must exist and be a regular file whose canonical
// path lies inside canonical(root).
PathResult resolveInside(const std::string& root, const std::string& relative);

// Reads a whole file resolved with resolveInside, refusing files larger than `max_bytes`.
struct FileText {
    bool ok = false;
    bool missing = false;  // !ok as PathResult::missing, or no such file (not: too large, not a file)
    std::string text;
    std::string path;
    std::string error;
};
FileText readFileInside(const std::string& root, const std::string& relative,
                        std::size_t max_bytes = 1u << 20);

// Reads any file by path (trusted inputs: lab files chosen by the instructor).
FileText readFile(const std::string& path, std::size_t max_bytes = 256u << 20);

// The labs folder the tools use by default: $SHADERLAB_LABS when set, else the labs/ folder of
// the course found from `start` (default: the current directory) upward: the nearest folder whose
// labs/ holds a lab (a sub-folder with a lab.json). "" when there is none.
std::string defaultLabsRoot(const std::string& start = "");

}  // namespace shaderlab
