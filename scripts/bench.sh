#!/usr/bin/env bash
# Regenerates docs/performance.md and its plots (docs/performance/*.svg): builds the programs it
# times into ./build, then runs bench/run_bench.py, which grades every lab of reference_solutions
# with phase timings, times process start and `compare`, runs the metric, tessellation and bloom
# benchmarks and the render-resolution sweep over the corpus. About 4-6 minutes on a quiet 2-core
# machine; run it on a quiet one, since every figure is a wall-clock time.
#   bash scripts/bench.sh            # the page
#   bash scripts/bench.sh --quick    # fewer repetitions and resolutions, to try the machinery
#   bash scripts/bench.sh --replot   # no measuring: the page and plots again from the last results
# Raw results: build/bench-results/results.json. Needs gnuplot for the plots (scripts/setup.sh
# installs it; without it the page has tables only) and installs python3-skimage, if it can, to
# time scikit-image's SSIM beside ours.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ ! -f build/CMakeCache.txt ]; then
  cmake -S . -B build -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
fi
cmake --build build -j"$(nproc)" --target shaderlab bench_metrics bench_tessellation >/dev/null
command -v gnuplot >/dev/null || echo "bench: gnuplot not found (apt-get install gnuplot-nox): tables only" >&2
# scikit-image is timed against our SSIM in the same run where it is installed; Debian packages it.
if ! /usr/bin/python3 -c "import skimage" 2>/dev/null; then
  sudo=""; [ "$(id -u)" = 0 ] || sudo="sudo"
  $sudo apt-get install -y --no-install-recommends python3-skimage >/dev/null 2>&1 ||
    echo "bench: python3-skimage could not be installed: no scikit-image column" >&2
fi
# The system Python: the script needs its standard library only.
python=/usr/bin/python3
[ -x "$python" ] || python=python3
exec "$python" bench/run_bench.py --build build --out build/bench-results --command "bash scripts/bench.sh" "$@"
