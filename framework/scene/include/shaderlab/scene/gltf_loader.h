// Loads a glTF 2.0 file (.gltf with external or embedded buffers, or .glb) into a Scene.
// Every accessor, buffer view and index is bounds-checked before it is read, so a malformed or
// hostile file is reported as an error naming the file and the problem, never a crash.
// Errors and warnings are returned separately (as tinygltf does); nothing is printed. Which
// extensions are read, refused or ignored, and what shaders receive: docs/scenes.md.
#pragma once

#include <string>

#include "shaderlab/scene/scene.h"

namespace shaderlab {

struct SceneLoadResult {
    bool ok = false;
    std::string error;                  // set when !ok: "<path>: <problem>"
    std::vector<std::string> warnings;  // e.g. "normals generated flat for mesh 'cube'"
};

// Loads the default scene (or scene 0) of `path`. External buffers must live in the same folder
// as the file or below it; a URI that escapes that folder is an error.
SceneLoadResult loadGltfScene(const std::string& path, Scene* out);

// The same for a file already in memory (a fuzzer's input): `path` names it in messages and
// fixes the folder external buffers are looked for in.
SceneLoadResult loadGltfSceneFromBytes(const std::string& bytes, const std::string& path, Scene* out);

}  // namespace shaderlab
