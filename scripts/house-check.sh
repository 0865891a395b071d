#!/usr/bin/env bash
# The house's size rules (docs/architecture.md, "Sizes"): no C++ source file over 1,000 lines and no
# function over 150, in our own code (framework/, grader/, tests/, bench/). Function extents come
# from universal-ctags (end: field); without it only the files are checked, and it says so.
# Exit 0 when every rule holds, 1 naming each file or function over its limit.
# Usage: bash scripts/house-check.sh [max file lines] [max function lines]
set -euo pipefail
cd "$(dirname "$0")/.."
max_file=${1:-1000}
max_function=${2:-150}
mapfile -t files < <(git ls-files -- 'framework/*.cpp' 'framework/*.h' 'grader/*.cpp' 'grader/*.h' \
  'tests/*.cpp' 'tests/*.h' 'bench/*.cpp' 2>/dev/null || find framework grader tests bench -name '*.cpp' -o -name '*.h')
status=0
for f in "${files[@]}"; do
  [ -f "$f" ] || continue
  n=$(wc -l <"$f")
  if ((n > max_file)); then
    echo "house-check: $f has $n lines (at most $max_file)"
    status=1
  fi
done
if ctags --version 2>/dev/null | grep -q "Universal Ctags"; then
  # One line per function: "<end> <start> <name> <file>".
  while read -r end start name file; do
    len=$((end - start + 1))
    if ((len > max_function)); then
      echo "house-check: $file:$start $name is $len lines (at most $max_function)"
      status=1
    fi
  done < <(ctags --languages=C++ --kinds-C++=f --fields=+ne -x --_xformat='%{end} %{line} %N %F' \
             "${files[@]}" 2>/dev/null | awk '$1 != "-"')
else
  echo "house-check: universal-ctags is not installed; function lengths not checked"
fi
if ((status == 0)); then
  echo "house-check: ${#files[@]} files, none over $max_file lines, no function over $max_function"
fi
exit $status
