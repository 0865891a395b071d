#!/usr/bin/env bash
# Regenerates the bundled glTF scenes in labs/scenes/ with shaderlab_make_scenes, the labs'
# generated assets in labs/<id>/assets/ (shaderlab_make_scenes --lab-assets), and the sky cube map
# in labs/shared/sky/ with shaderlab_make_sky.
# Usage: scripts/regenerate_scenes.sh [build_dir]   (default: ./build)
# Builds the tool in build_dir if needed (configuring the build dir when it has never been
# configured), removes the scene files it owns from labs/scenes/ so that a scene dropped from
# the tool does not linger, and writes the new ones. A lab's generated assets folder belongs to
# the tool as a whole: it is replaced, so a file dropped from the tool (or put there by hand)
# does not linger either. Commit the result; the ScenesFresh and LabAssets.Fresh tests fail
# while the committed files differ from what the tool writes.
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

# Each lab's generated assets: written into a scratch folder, then each labs/<id>/assets/ the tool
# writes is replaced by its fresh copy.
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
"$tool" --lab-assets "$scratch" >/dev/null
for made in "$scratch"/*/assets; do
    id="$(basename "$(dirname "$made")")"
    if [[ ! -d "$repo/labs/$id" ]]; then
        echo "regenerate_scenes.sh: the tool writes assets for $id, which has no folder in labs/" >&2
        exit 1
    fi
    rm -rf "$repo/labs/$id/assets"
    cp -r "$made" "$repo/labs/$id/assets"
    echo "assets written to labs/$id/assets"
done

# The sky cube map shared by the course (labs/shared/sky/), from the analytic sky.
sky_tool="$(find "$build" -type f -name shaderlab_make_sky -perm -u+x | head -n 1)"
sky_out="$repo/labs/shared/sky"
mkdir -p "$sky_out"
find "$sky_out" -maxdepth 1 -type f -name 'sky_*.png' -delete
"$sky_tool" "$sky_out"
echo "sky written to $sky_out"
