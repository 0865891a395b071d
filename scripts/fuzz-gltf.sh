#!/usr/bin/env bash
# Fuzzes the glTF loader with libFuzzer for a fixed time (default 60 s) and fails on any crash,
# sanitizer report, timeout or out-of-memory. Builds tests/fuzz/ with clang into its own folder.
# Usage: bash scripts/fuzz-gltf.sh [seconds] [build folder]
# The seed corpus is every fixture in tests/data/gltf*/; inputs that reach new code are kept in
# <build folder>/corpus between runs. Prints libFuzzer's final statistics (executions, exec/s).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
build="${2:-build-fuzz}"
command -v clang++ >/dev/null || { echo "fuzz-gltf: clang++ is not installed (apt-get install clang)"; exit 1; }
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  "${launcher[@]}" -DSHADERLAB_FUZZ=ON -DSHADERLAB_BUILD_TESTS=OFF -DSHADERLAB_BUILD_BENCH=OFF >/dev/null
CCACHE_BASEDIR="$PWD" cmake --build "$build" --target gltf_fuzz -j"$(nproc)" >/dev/null
mkdir -p "$build/corpus" "$build/artifacts"
seeds="$build/seeds"
rm -rf "$seeds" && mkdir -p "$seeds"
find tests/data/gltf tests/data/gltf_realworld -maxdepth 1 -type f \( -name '*.gltf' -o -name '*.glb' \) \
  -exec cp {} "$seeds"/ \;
# Leaks are checked too (LSan); the loader has no GL driver in it, so nothing is suppressed.
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:allocator_may_return_null=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
log="$build/fuzz.log"
set +e
"$build/tests/fuzz/gltf_fuzz" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=65536 \
  -print_final_stats=1 -artifact_prefix="$build/artifacts/" "$build/corpus" "$seeds" >"$log" 2>&1
status=$?
set -e
grep -E "^(stat::number_of_executed_units|stat::average_exec_per_sec|stat::new_units_added|stat::peak_rss_mb)" "$log" || true
if [ "$status" -ne 0 ]; then
  echo "fuzz-gltf: the fuzzer stopped with status $status; the input is in $build/artifacts/, the log in $log"
  tail -n 40 "$log"
  exit 1
fi
echo "fuzz-gltf: ${seconds} s without a crash"
