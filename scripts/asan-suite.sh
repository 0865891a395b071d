#!/usr/bin/env bash
# The whole test suite under AddressSanitizer and UBSan: configures build-asan/ (in the checkout:
# the CLI finds the course from the working folder upward), builds it and runs ctest there. Any
# arguments go to ctest (e.g. -R Hostile). Not part of .ci/run: on 2 cores the build takes about
# 25 minutes from an empty folder and the tests about 6 (docs/scenes.md, "Checking files").
# Under SHADERLAB_SANITIZE every test runs with tests/asan/lsan.supp, which suppresses the GL
# driver's own leaks only; a leak of ours fails its test (LeakSanitizer.OurLeakIsReported...
# checks that), and so does any UBSan report.
set -euo pipefail
cd "$(dirname "$0")/.."
build=build-asan
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSHADERLAB_SANITIZE=ON -DSHADERLAB_BUILD_BENCH=OFF \
  "${launcher[@]}" >/dev/null
CCACHE_BASEDIR="$PWD" cmake --build "$build" -j"$(nproc)"
ctest --test-dir "$build" --output-on-failure -j"$(nproc)" "$@"
