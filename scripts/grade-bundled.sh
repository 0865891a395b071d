#!/usr/bin/env bash
# The main job on the bundled material: grades the reference solutions and the starter code,
# then every lab's corpus of known mistakes and correct alternatives (tests/corpus/), checking
# that each verdict is the expected one, and prints where the reports are.
# Usage: bash scripts/grade-bundled.sh [output folder, default out/bundled]
set -uo pipefail
cd "$(dirname "$0")/.."
out=${1:-out/bundled}
bin=build/framework/shaderlab
[ -x "$bin" ] || { echo "grade-bundled: $bin not built; run scripts/setup.sh first" >&2; exit 2; }

status=0
for s in reference_solutions labs; do
  echo "== $s"
  # Exit 1 means "graded, and not everything passed": expected for the starter code.
  "$bin" grade "$s" --out "$out/$s" --timeout 10 --format gradescope --format junit | sed 's/^/   /'
  rc=${PIPESTATUS[0]}
  if [ "$rc" -ge 2 ]; then status=$rc; fi
done
echo "== corpus (tests/corpus)"
"$bin" corpus --out "$out/corpus"
rc=$?
if [ "$rc" -ne 0 ]; then status=$rc; fi
echo
echo "reports: $(realpath -m "$out")/reference_solutions/report.html and $(realpath -m "$out")/labs/report.html"
echo "corpus:  $(realpath -m "$out")/corpus/corpus.json, one report per case in $(realpath -m "$out")/corpus/<lab>/reports/"
exit $status
