#!/usr/bin/env bash
# Regenerates docs/performance.md and its plots (docs/performance/*.svg): builds the programs it
# times into ./build, then runs bench/run_bench.py, which grades every lab of reference_solutions
# with phase timings, times process start and `compare`, runs the metric, tessellation and bloom
# benchmarks and the render-resolution sweep over the corpus, then measures grading against
# rendering, `check` latency and `batch` throughput with the caches kept between runs, beside the
# same figures of an older binary when given one. About 4-6 minutes on a quiet 2-core machine, 3-4
# more for the caches, and as much again for a baseline; run it on a quiet one, since every figure
# is a wall-clock time.
#   bash scripts/bench.sh            # the page
#   bash scripts/bench.sh --quick    # fewer repetitions and resolutions, to try the machinery
#   bash scripts/bench.sh --replot   # no measuring: the page and plots again from the last results
#   bash scripts/bench.sh --baseline-commit 604cdf7   # also that commit, built in build/baseline-604cdf7
#   bash scripts/bench.sh --baseline PATH             # also that shaderlab binary
# A baseline commit is checked out in a git worktree under build/ and its grader alone built there
# (no viewer, tests or benchmarks); it grades its own commit's labs, since an older program need
# not read today's lab.json. Without a baseline the page says "not measured" in its columns.
# Raw results: build/bench-results/results.json. Needs gnuplot for the plots (scripts/setup.sh
# installs it; without it the page has tables only) and installs python3-skimage, if it can, to
# time scikit-image's SSIM beside ours.
set -euo pipefail
cd "$(dirname "$0")/.."
args=() baseline="" baseline_commit="" command="bash scripts/bench.sh"
while [ $# -gt 0 ]; do
  case "$1" in
    --baseline) baseline="${2:?--baseline needs a shaderlab binary}"; shift 2 ;;
    --baseline=*) baseline="${1#*=}"; shift ;;
    --baseline-commit) baseline_commit="${2:?--baseline-commit needs a commit}"; shift 2 ;;
    --baseline-commit=*) baseline_commit="${1#*=}"; shift ;;
    --quick) args+=("$1"); command+=" --quick"; shift ;;
    *) args+=("$1"); shift ;;
  esac
done
if [ -n "$baseline" ] && [ -n "$baseline_commit" ]; then
  echo "bench: --baseline and --baseline-commit: one or the other" >&2
  exit 2
fi
replot=0
for a in ${args[@]+"${args[@]}"}; do [ "$a" = --replot ] && replot=1; done
if [ "$replot" = 0 ]; then
  if [ ! -f build/CMakeCache.txt ]; then
    cmake -S . -B build -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
  fi
  cmake --build build -j"$(nproc)" --target shaderlab bench_metrics bench_tessellation >/dev/null
fi
if [ -n "$baseline_commit" ] && [ "$replot" = 0 ]; then
  short="$(git rev-parse --short "$baseline_commit^{commit}")"
  tree="build/baseline-$short"
  if [ ! -d "$tree" ]; then
    git worktree add --detach "$tree" "$short" >/dev/null
  fi
  if [ ! -f "$tree/build/CMakeCache.txt" ]; then
    cmake -S "$tree" -B "$tree/build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSHADERLAB_GRADER_ONLY=ON \
      -DSHADERLAB_BUILD_TESTS=OFF -DSHADERLAB_BUILD_BENCH=OFF >/dev/null
  fi
  echo "bench: building $short in $tree (once; its grader only)" >&2
  cmake --build "$tree/build" -j"$(nproc)" --target shaderlab >/dev/null
  baseline="$tree/build/framework/shaderlab"
  args+=(--baseline-name "$short")
  command+=" --baseline-commit $short"
fi
if [ -n "$baseline" ]; then
  args+=(--baseline "$baseline")
  [ -n "$baseline_commit" ] || command+=" --baseline $baseline"
fi
command -v gnuplot >/dev/null || echo "bench: gnuplot not found (apt-get install gnuplot-nox): tables only" >&2
# scikit-image is timed against our SSIM in the same run where it is installed; Debian packages it.
if [ "$replot" = 0 ] && ! /usr/bin/python3 -c "import skimage" 2>/dev/null; then
  sudo=""; [ "$(id -u)" = 0 ] || sudo="sudo"
  $sudo apt-get install -y --no-install-recommends python3-skimage >/dev/null 2>&1 ||
    echo "bench: python3-skimage could not be installed: no scikit-image column" >&2
fi
# The system Python: the script needs its standard library only.
python=/usr/bin/python3
[ -x "$python" ] || python=python3
exec "$python" bench/run_bench.py --build build --out build/bench-results --command "$command" \
  ${args[@]+"${args[@]}"}
