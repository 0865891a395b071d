#!/usr/bin/env bash
# Installs the Debian packages shaderlab needs (only those missing; Debian 12 and 13), then
# configures and builds into ./build.
# Usage: bash scripts/setup.sh [--grader-only] [extra cmake -D options]
#   --grader-only  what grading needs and nothing more: no viewer (GLFW, Dear ImGui), no tests,
#                  no benchmarks (a Gradescope image, a grading server, a container)
set -euo pipefail
cd "$(dirname "$0")/.."

grader_only=0
if [ "${1:-}" = "--grader-only" ]; then
  grader_only=1
  shift
fi

# What building and grading need.
packages=(
  build-essential cmake pkg-config
  libegl-dev libegl1-mesa-dev libgl-dev libgl1-mesa-dri  # EGL headers; Mesa's llvmpipe renders
  libglm-dev nlohmann-json3-dev libtinygltf-dev libstb-dev libcli11-dev python3-glad libvalijson-dev libpng-dev
  libdraco-dev libmeshoptimizer-dev  # compressed glTF meshes (framework/scene/src/gltf_accessors.cpp)
  libarchive-dev libxxhash-dev       # shaderlab batch: submitted zips, content hashes
  libcpp-httplib-dev                 # shaderlab serve: the browser workbench's HTTP server
)
# The tests, the benchmarks and the student viewer.
if ((grader_only == 0)); then
  packages+=(
    libgtest-dev libgmock-dev libbenchmark-dev clang-format
    universal-ctags  # scripts/house-check.sh: function lengths (test house_check)
    chromium tidy    # tests/report_page_test.cpp renders and validates report.html (skipped without them)
    python3 python3-websocket  # tests/serve/: the workbench page driven in headless Chromium
    gnuplot-nox      # scripts/bench.sh draws the plots of docs/performance.md
    libglfw3-dev libimgui-dev  # the student viewer (`shaderlab view`)
    xvfb xauth       # tests/viewer_test.cpp opens the viewer on a virtual display (skipped without)
  )
fi
installed() { dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q "install ok installed"; }
missing=()
for p in "${packages[@]}"; do
  installed "$p" || missing+=("$p")
done
# OSMesa (the default backend where it exists) is a run-time library, opened when a context is
# made; Mesa 25.1 and later ship none, and EGL renders the same images.
installed libosmesa6 || missing+=(libosmesa6?)

sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
if ((${#missing[@]})); then
  $sudo apt-get update -qq
  wanted=()
  for p in "${missing[@]}"; do
    if [[ "$p" == *\? ]]; then
      p=${p%\?}
      if [ -z "$(apt-cache policy "$p" 2>/dev/null | sed -n 's/^ *Candidate: //p' | grep -v '(none)')" ]; then
        echo "setup: $p is not packaged here; shaderlab will render through EGL"
        continue
      fi
    fi
    wanted+=("$p")
  done
  if ((${#wanted[@]})); then
    echo "setup: installing ${wanted[*]}"
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${wanted[@]}"
  fi
fi

options=(-DCMAKE_BUILD_TYPE=RelWithDebInfo)
if ((grader_only)); then
  options+=(-DSHADERLAB_GRADER_ONLY=ON -DSHADERLAB_BUILD_TESTS=OFF -DSHADERLAB_BUILD_BENCH=OFF)
fi
cmake -S . -B build "${options[@]}" "$@" >/dev/null
cmake --build build -j"$(nproc)"
echo "setup: built into $(pwd)/build"
