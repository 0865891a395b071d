// The labs' own generated assets (docs/scenes.md, "Lab-local assets"): for each lab listed in
// lab_assets.cpp, the whole folder <labs_dir>/<id>/assets/, meshes and textures, written the same
// way on every run. scripts/regenerate_scenes.sh replaces each such folder in labs/ with it;
// tests/lab_assets_test.cpp fails while a committed folder differs.
#pragma once

#include <filesystem>

namespace shaderlab::scenegen {

// Writes every lab's generated assets under `labs_dir` (which may be a scratch folder). Prints
// each file written; false, with a message on stderr, when one could not be.
bool writeLabAssets(const std::filesystem::path& labs_dir);

}  // namespace shaderlab::scenegen
