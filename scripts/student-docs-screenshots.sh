#!/usr/bin/env bash
# Takes the screenshots of docs/students.md: a student's course (labs without the reference
# solutions, as students get it) in a scratch folder, `shaderlab view` on an Xvfb display of its
# own, the window saved at each step of the walk-through into docs/images/; then the same course
# in the browser workbench (`shaderlab serve`, headless Chromium: scripts/serve-screenshots.py), at
# 1400, 1024 and 390 px wide and in the light theme.
# Usage: bash scripts/student-docs-screenshots.sh   (after building; needs Xvfb, chromium and
# python3-websocket, which scripts/setup.sh installs)
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$(pwd)
sl="$repo/build/framework/shaderlab"
images="$repo/docs/images"
course=${COURSE:-/tmp/shaderlab-course}
command -v Xvfb >/dev/null || { echo "Xvfb is not installed (scripts/setup.sh installs it)" >&2; exit 2; }
[ -x "$sl" ] || { echo "build shaderlab first (scripts/setup.sh)" >&2; exit 2; }

rm -rf "$course" && mkdir -p "$course/labs" "$images"
cp -r labs/01-phong labs/02-toon labs/06-bloom labs/scenes labs/shared labs/README.md "$course/labs/"

# A display of our own: Xvfb picks a free number and writes it to fd 3.
exec 3< <(echo "pid $BASHPID"; exec Xvfb -displayfd 1 -screen 0 1280x800x24 -nolisten tcp 2>/dev/null)
read -r _ xvfb_pid <&3
read -r display_number <&3
export DISPLAY=":$display_number"
trap 'kill "$xvfb_pid" 2>/dev/null || true' EXIT

cd "$course"
"$sl" start 01-phong >/dev/null
# 1. The starter code beside the reference, split.
"$sl" view 01-phong --scene torus --mode split --frames 3 --screenshot-window "$images/view-starter-split.png" >/dev/null
# 2. A nearly right solution (Blinn's half vector instead of Phong's mirror direction): the diff.
cp "$repo/tests/corpus/01-phong/blinn-phong/phong.frag" work/01-phong/phong.frag
cp "$repo/reference_solutions/01-phong/phong.vert" work/01-phong/phong.vert
"$sl" view 01-phong --scene torus_grazing --mode diff --frames 3 --screenshot-window "$images/view-diff.png" >/dev/null
# 3. A typo saved while the window runs: the error, and the last good picture.
log=$(mktemp)
"$sl" view 01-phong --scene torus_grazing --exit-after-reloads 1 --screenshot-window "$images/view-compile-error.png" \
  >"$log" 2>&1 &
view_pid=$!
until grep -q "rendered in" "$log"; do sleep 0.1; done
sleep 0.5
sed -i 's/vec3 n = normalize(v_world_normal);/vec3 n = normalize(v_world_normal)/' work/01-phong/phong.frag
wait "$view_pid"
rm -f "$log"
# 4. The finished lab.
cp "$repo/reference_solutions/01-phong/phong.frag" work/01-phong/phong.frag
"$sl" view 01-phong --scene torus_grazing --frames 3 --screenshot-window "$images/view-pass.png" >/dev/null
# 4b. The vertex data instead of the picture: the torus's texture coordinates as a checker.
"$sl" view 01-phong --scene torus --debug uv-checker --frames 3 --screenshot-window "$images/view-debug.png" >/dev/null
# 4c. The grade in the window: a known mistake of 02-toon, every goal and the hint.
"$sl" start 02-toon >/dev/null
cp "$repo"/reference_solutions/02-toon/* work/02-toon/
cp "$repo"/tests/corpus/02-toon/ramp-lambert-coordinate/* work/02-toon/
"$sl" view 02-toon --scene teapot --frames 3 --screenshot-window "$images/view-grade.png" >/dev/null
# 5. A multi-pass lab: the bright pass of 06-bloom's starter beside its golden image.
"$sl" start 06-bloom >/dev/null
"$sl" view 06-bloom --scene teapot_white --image bright.color --mode split --frames 3 \
  --screenshot-window "$images/view-passes.png" >/dev/null
echo "screenshots written to $images"
# 6. The browser workbench on a fresh copy of the starter code.
"$sl" start 01-phong --force >/dev/null
/usr/bin/python3 "$repo/scripts/serve-screenshots.py" "$sl" "$course" "$repo" "$images"
