#!/usr/bin/env bash
# The main job on the bundled material: grades the reference solutions, the starter code and
# every known submission under tests/submissions/, then prints where each report is.
# Usage: bash scripts/grade-bundled.sh [output folder, default out/bundled]
set -uo pipefail
cd "$(dirname "$0")/.."
out=${1:-out/bundled}
bin=build/framework/shaderlab
[ -x "$bin" ] || { echo "grade-bundled: $bin not built; run scripts/setup.sh first" >&2; exit 2; }

submissions=(reference_solutions labs)
for d in tests/submissions/*/; do submissions+=("${d%/}"); done

status=0
for s in "${submissions[@]}"; do
  name=$(basename "$s")
  echo "== $s"
  # Exit 1 means "graded, and not everything passed": expected for the known mistakes.
  "$bin" grade "$s" --out "$out/$name" --timeout 10 --format gradescope --format junit | sed 's/^/   /'
  rc=${PIPESTATUS[0]}
  if [ "$rc" -ge 2 ]; then status=$rc; fi
done
echo
echo "reports: $(realpath -m "$out")/<submission>/report.html (and report.json, results.json, report.junit.xml)"
exit $status
