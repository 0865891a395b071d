#!/usr/bin/env bash
# Installs the Debian 12 packages shaderlab needs (only those missing), then configures and
# builds into ./build. Usage: bash scripts/setup.sh [extra cmake -D options]
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  build-essential cmake pkg-config
  libosmesa6-dev libegl-dev libegl1-mesa-dev libgl-dev libgl1-mesa-dri
  libglfw3-dev libglm-dev nlohmann-json3-dev libtinygltf-dev libstb-dev libcli11-dev
  libgtest-dev libgmock-dev libbenchmark-dev python3-glad clang-format libvalijson-dev libpng-dev
  libdraco-dev libmeshoptimizer-dev  # compressed glTF meshes (framework/scene/src/gltf_loader.cpp)
  libarchive-dev libxxhash-dev  # shaderlab batch: submitted zips, content hashes
  chromium tidy  # tests/report_page_test.cpp renders and validates report.html (skipped without them)
  gnuplot-nox    # scripts/bench.sh draws the plots of docs/performance.md
  libimgui-dev                  # the student viewer's panels (`shaderlab view`); GLFW is above
  xvfb xauth                    # tests/viewer_test.cpp opens the viewer on a virtual display (skipped without)
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

cmake -S . -B build -DCMAKE_BUILD_TYPE=RelWithDebInfo "$@" >/dev/null
cmake --build build -j"$(nproc)"
echo "setup: built into $(pwd)/build"
