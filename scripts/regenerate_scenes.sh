#!/usr/bin/env bash
# Regenerates the bundled glTF scenes in labs/scenes/ with shaderlab_make_scenes, and the sky
# cube map in labs/shared/sky/ with shaderlab_make_sky.
# Usage: scripts/regenerate_scenes.sh [build_dir]   (default: ./build)
# Builds the tool in build_dir if needed (configuring the build dir when it has never been
# configured), removes the scene files it owns from labs/scenes/ so that a scene dropped from
# the tool does not linger, and writes the new ones. Commit the result; the ScenesFresh test
# fails while the committed scenes differ from what the tool writes.
set -euo pipefail

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$repo/build}"
out="$repo/labs/scenes"

if [[ ! -f "$build/CMakeCache.txt" ]]; then
    cmake -S "$repo" -B "$build"
fi
cmake --build "$build" --target shaderlab_make_scenes shaderlab_make_sky -j"$(nproc 2>/dev/null || echo 2)"

tool="$(find "$build" -type f -name shaderlab_make_scenes -perm -u+x | head -n 1)"
if [[ -z "$tool" ]]; then
    echo "regenerate_scenes.sh: shaderlab_make_scenes not found under $build" >&2
    exit 1
fi

mkdir -p "$out"
find "$out" -maxdepth 1 -type f \( -name '*.gltf' -o -name '*.glb' -o -name '*.bin' \) -delete
"$tool" "$out"
echo "scenes written to $out"

# The sky cube map shared by the course (labs/shared/sky/), from the analytic sky.
sky_tool="$(find "$build" -type f -name shaderlab_make_sky -perm -u+x | head -n 1)"
sky_out="$repo/labs/shared/sky"
mkdir -p "$sky_out"
find "$sky_out" -maxdepth 1 -type f -name 'sky_*.png' -delete
"$sky_tool" "$sky_out"
echo "sky written to $sky_out"
