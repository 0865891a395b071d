#!/usr/bin/env bash
# The house format (.clang-format) over our own C++: every file as clang-format would write it.
# The files are formatted with clang-format 14 (Debian 12); another major version lays some
# constructs out differently (Debian 13's 19 does), so there the check is skipped, saying so
# (exit 77), instead of failing on code nobody changed. Usage: bash scripts/format-check.sh [clang-format]
set -uo pipefail
cd "$(dirname "$0")/.."
tool=${1:-clang-format}
house_major=14
version=$("$tool" --version 2>/dev/null) || { echo "format-check: $tool is not installed; skipped"; exit 77; }
major=$(echo "$version" | sed -nE 's/.*version ([0-9]+)\..*/\1/p')
if [ "$major" != "$house_major" ]; then
  echo "format-check: $tool is version ${major:-unknown}; the house format is checked with clang-format $house_major (Debian 12); skipped"
  exit 77
fi
mapfile -t files < <(git ls-files -- 'framework/*.cpp' 'framework/*.h' 'grader/*.cpp' 'grader/*.h' 'tests/*.cpp' \
  'tests/*.h' 'bench/*.cpp' 2>/dev/null)
((${#files[@]})) || mapfile -t files < <(find framework grader tests bench \( -name '*.cpp' -o -name '*.h' \))
"$tool" --dry-run -Werror "${files[@]}" && echo "format-check: ${#files[@]} files in the house format (clang-format $major)"
