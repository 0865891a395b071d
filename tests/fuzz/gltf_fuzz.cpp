// libFuzzer target for the glTF loader: every input is loaded as a scene file (.gltf or .glb by
// its first bytes) and must end as a Scene or an error message, never as a crash, a sanitizer
// report, a hang or unbounded memory. Built only by scripts/fuzz-gltf.sh (clang, -fsanitize=
// fuzzer,address,undefined); tinygltf is compiled into the target (tinygltf_impl.cpp) so its
// parsing is instrumented too.
#include <cstddef>
#include <cstdint>
#include <string>

#include "shaderlab/scene/gltf_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string bytes(reinterpret_cast<const char*>(data), size);
    // External URIs resolve in a folder that holds nothing, so only embedded data is read.
    const bool glb = size >= 4 && bytes.compare(0, 4, "glTF") == 0;
    shaderlab::Scene scene;
    const shaderlab::SceneLoadResult r = shaderlab::loadGltfSceneFromBytes(
        bytes, glb ? "/nonexistent/fuzz.glb" : "/nonexistent/fuzz.gltf", &scene);
    if (r.ok) {
        // A loaded scene is safe to draw: every index names a vertex.
        for (const shaderlab::Mesh& mesh : scene.meshes)
            for (std::uint32_t i : mesh.indices)
                if (i >= mesh.positions.size()) __builtin_trap();
    } else if (r.error.empty()) {
        __builtin_trap();  // a refusal always says why
    }
    return 0;
}
