#!/usr/bin/env bash
# The proof of a portable `shaderlab` (scripts/portable-build.sh) on systems it was not built on.
# For each SUITE, a fresh minimal Debian chroot (debootstrap --variant=minbase: no compiler, no
# -dev package, no Mesa) laid out as Gradescope's autograder image:
#   1. the Gradescope bundle (`BINARY gradescope-bundle`, LAB) unpacked into /autograder/source, and
#      its setup.sh run: it installs Mesa's run-time packages and nothing else;
#   2. `grade reference_solutions` on every lab, as Gradescope grades (the reference drawn on this
#      Mesa too): full marks; and `--no-reference`, against the goldens drawn by another Mesa,
#      with scripts/cross-mesa.py's figures for the record (not a failure: docs/grading.md);
#   3. run_autograder on two uploads (LAB's reference files, its starter files) as Gradescope
#      runs it: /autograder/submission in, /autograder/results/results.json out, with the points;
#   4. `serve` answers its page on the loopback.
# Needs root, debootstrap and Debian's archive, as distro-check.sh (scripts/chroot-lib.sh).
#
# Usage: sudo bash scripts/portable-check.sh BINARY [SUITE...] [--lab LAB] [--keep]
#   BINARY   the portable shaderlab (portable-build.sh OUT: OUT/shaderlab)
#   SUITE    bullseye, bookworm, trixie (default: all three)
#   --lab    the lab of the Gradescope assignment (default 01-phong)
#   --keep   leave the chroots (under $PORTABLE_CHECK_DIR, default /var/tmp) for a look afterwards
# Exit 0 when every check passed on every suite, 1 when one failed, 2 bad arguments, 77 skipped.
set -uo pipefail
cd "$(dirname "$0")/.."
checkout=$(pwd)

binary=""
suites=()
lab=01-phong
keep=0
while (($#)); do
  case "$1" in
    --lab) lab=${2:-}; shift ;;
    --keep) keep=1 ;;
    -*) echo "portable-check: unknown option $1" >&2; exit 2 ;;
    *) if [ -z "$binary" ]; then binary=$1; else suites+=("$1"); fi ;;
  esac
  shift
done
[ -n "$binary" ] && [ -x "$binary" ] ||
  { echo "usage: sudo bash scripts/portable-check.sh BINARY [SUITE...] [--lab LAB] [--keep]" >&2; exit 2; }
binary=$(realpath "$binary")
((${#suites[@]})) || suites=(bullseye bookworm trixie)

suite=""
say() { echo "portable-check${suite:+ $suite}: $*"; }
. scripts/chroot-lib.sh
chroot_prepare

work=$(mktemp -d "${PORTABLE_CHECK_DIR:-/var/tmp}/shaderlab-portable-check.XXXXXX")
roots=()
cleanup() {
  chroot_unmount_all
  if ((keep)); then say "kept: $work"; else rm -rf --one-file-system "$work"; fi
}
trap cleanup EXIT
trap 'exit 130' INT TERM
now() { date +%s; }

# The bundle, made by the binary under test from this checkout's labs.
"$binary" gradescope-bundle --out "$work/autograder.zip" --labs "$checkout/labs" --lab "$lab" >/dev/null ||
  { say "gradescope-bundle failed"; exit 1; }
say "bundle: $(stat -c %s "$work/autograder.zip" | awk '{printf "%.1f MiB", $1 / 1048576}') ($work/autograder.zip)"

unzip_into() {  # unzip_into ZIP DIR: Python's zipfile, as minbase has no unzip
  python3 - "$1" "$2" <<'EOF'
import os, sys, zipfile
with zipfile.ZipFile(sys.argv[1]) as z:
    for info in z.infolist():
        path = z.extract(info, sys.argv[2])
        mode = info.external_attr >> 16
        if mode:
            os.chmod(path, mode & 0o777)
EOF
}

status=0
results=()
for suite in "${suites[@]}"; do
  t0=$(now)
  root=$work/$suite
  mkdir -p "$root"
  say "debootstrap --variant=minbase $suite"
  chroot_make "$suite" "$root" || { results+=("$suite: skipped (debootstrap failed)"); status=1; continue; }
  chroot_mount "$root"
  fail() { say "FAILED: $*"; results+=("$suite: FAILED: $*"); status=1; }

  # 1. Gradescope's layout, and the bundle's setup.sh: Mesa's run-time packages only.
  mkdir -p "$root/autograder/submission" "$root/autograder/results"
  unzip_into "$work/autograder.zip" "$root/autograder/source"
  cp "$root/autograder/source/run_autograder" "$root/autograder/run_autograder"
  before=$(chroot_run "$root" "dpkg-query -W -f='\${Package}\n' | sort")
  t=$(now)
  if ! chroot_run --timeout 900 "$root" "cd /autograder/source && bash ./setup.sh" >"$root.setup.log" 2>&1; then
    fail "setup.sh (log: $root.setup.log)"
    tail -n 20 "$root.setup.log"
    continue
  fi
  added=$(comm -13 <(echo "$before") <(chroot_run "$root" "dpkg-query -W -f='\${Package}\n' | sort") | wc -l)
  devs=$(chroot_run "$root" "dpkg-query -W -f='\${Package}\n' | grep -E -- '-dev\$|^(gcc|g\+\+|cpp|make|cmake|binutils)(-[0-9]+)?\$' | tr '\n' ' '")
  [ -z "$devs" ] || fail "setup.sh installed build tools or -dev packages: $devs"
  mesa=$(chroot_run "$root" "dpkg-query -W -f='\${Version}' libgl1-mesa-dri")
  renderer=$(grep -m1 -i 'renderer' "$root.setup.log" | sed 's/^ *//')
  say "setup.sh: $(chroot_minutes $(($(now) - t))), $added packages added (Mesa $mesa), no compiler; $renderer"
  # EGL too: what renders where Mesa has no OSMesa (25.1 and later).
  egl=$(chroot_run "$root" "/autograder/source/bin/shaderlab info --backend egl" 2>&1 | grep -m1 '^version' | sed 's/  */ /g')
  if [ -n "$egl" ]; then say "EGL: $egl"; else fail "info --backend egl gave no context"; fi

  # 2. The reference solutions of every lab: graded as Gradescope grades (the reference drawn here
  #    too), and against the goldens drawn by another Mesa (figures, for the record).
  mkdir -p "$root/root/course"
  cp -a "$checkout/labs" "$checkout/reference_solutions" "$root/root/course/"
  for how in reference goldens; do
    t=$(now)
    flag=""
    [ $how = goldens ] && flag=--no-reference
    chroot_run --timeout 1800 "$root" "cd /root/course && /autograder/source/bin/shaderlab grade reference_solutions $flag --out /root/ref-$how" \
      >"$root.grade-$how.log" 2>&1
    rc=$?
    score=$(grep -m1 -o 'score [0-9.]* */ *[0-9.]*' "$root.grade-$how.log" || tail -n1 "$root.grade-$how.log")
    say "grade reference_solutions against the $how: exit $rc, $score, $(chroot_minutes $(($(now) - t)))"
    if [ $how = reference ] && ((rc != 0)); then fail "grade reference_solutions: exit $rc ($score; log: $root.grade-$how.log)"; fi
  done
  [ -f "$root/root/ref-goldens/report.json" ] && python3 scripts/cross-mesa.py "$root/root/ref-goldens/report.json" >"$root.cross-mesa.md" &&
    say "cross-Mesa figures (against the goldens): $root.cross-mesa.md" && grep -E '^\| [0-9]' "$root.cross-mesa.md" | grep -v '| 10 / 10 |' | sed 's/^/    not full marks: /'

  # 3. run_autograder on the lab's reference and starter files, uploaded flat as students do.
  for upload in reference_solutions labs; do
    rm -rf "$root/autograder/submission" "$root/autograder/results"
    mkdir -p "$root/autograder/submission" "$root/autograder/results"
    find "$checkout/$upload/$lab" -maxdepth 1 -type f \( -name '*.vert' -o -name '*.frag' -o -name '*.glsl' -o -name '*.comp' \) \
      -exec cp {} "$root/autograder/submission/" \;
    chroot_run --timeout 600 "$root" "bash /autograder/run_autograder" >"$root.run-$upload.log" 2>&1
    rc=$?
    points=$(python3 -c 'import json,sys; r=json.load(open(sys.argv[1])); print("%g / %g in %d tests" % (r["score"], sum(t.get("max_score", 0) for t in r["tests"]), len(r["tests"])))' \
      "$root/autograder/results/results.json" 2>/dev/null)
    if ((rc != 0)) || [ -z "$points" ]; then fail "run_autograder on $upload/$lab (exit $rc, log: $root.run-$upload.log)"; fi
    if grep -q '/tmp/\|/autograder/' "$root/autograder/results/results.json" 2>/dev/null; then
      fail "results.json of $upload/$lab names a folder of the grader"
    fi
    say "run_autograder, $upload/$lab uploaded: results.json $points"
  done

  # 4. serve: the workbench's page on the loopback.
  page=$(chroot_run --timeout 120 "$root" "cd /root/course && { /autograder/source/bin/shaderlab serve $lab --submission reference_solutions --port 8431 >/root/serve.log 2>&1 & pid=\$!; }
    for i in \$(seq 50); do
      if exec 3<>/dev/tcp/127.0.0.1/8431 2>/dev/null; then
        printf 'GET / HTTP/1.0\r\nHost: 127.0.0.1\r\n\r\n' >&3; head -n1 <&3; break
      fi
      sleep 0.2
    done
    kill \$pid" 2>/dev/null | tr -d '\r')
  case $page in *" 200 "*) say "serve: GET / answered $page" ;; *) fail "serve did not answer its page ($page)" ;; esac

  results+=("$suite (Mesa $mesa): $(chroot_minutes $(($(now) - t0)))")
  chroot_unmount_all
done
suite=""
for r in "${results[@]}"; do say "$r"; done
exit $status
