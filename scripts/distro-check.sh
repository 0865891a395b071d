#!/usr/bin/env bash
# Tries the README's two commands as a newcomer would, on a fresh minimal Debian: makes a chroot of
# SUITE (debootstrap --variant=minbase), clones this checkout into it, runs the README's first
# command (set up, build, grade the bundled submissions) and its second (set up, build, the whole
# suite), and says what passed, with times. Needs root, debootstrap (installed when missing) and
# Debian's archive (the mirror this machine's apt uses). No container engine needed: this is the
# same road the Dockerfile takes, one level down.
#
# Usage: sudo bash scripts/distro-check.sh SUITE [--keep] [--only N]
#   SUITE      bookworm (Debian 12) or trixie (Debian 13), or any suite debootstrap knows
#   --keep     leave the chroot (under $DISTRO_CHECK_DIR, default /var/tmp) for a look afterwards
#   --only N   run only the README's command N (1 or 2)
# Exit 0 when every command run passed, 1 when one failed, 2 when the check could not run (77 when
# it was skipped: not root, the archive cannot be reached, debootstrap failed; the reason is printed).
set -uo pipefail
cd "$(dirname "$0")/.."
checkout=$(pwd)

suite=${1:-}
shift || true
keep=0
only=""
while (($#)); do
  case "$1" in
    --keep) keep=1 ;;
    --only) only=${2:-}; shift ;;
    *) echo "distro-check: unknown option $1" >&2; exit 2 ;;
  esac
  shift
done
[ -n "$suite" ] || { echo "usage: sudo bash scripts/distro-check.sh SUITE [--keep] [--only N]" >&2; exit 2; }

say() { echo "distro-check $suite: $*"; }
. scripts/chroot-lib.sh
chroot_prepare

base=${DISTRO_CHECK_DIR:-/var/tmp}
root=$(mktemp -d "$base/shaderlab-$suite.XXXXXX")
cleanup() {
  chroot_unmount_all
  if ((keep)); then say "chroot kept in $root"; else rm -rf --one-file-system "$root"; fi
}
trap cleanup EXIT
trap 'exit 130' INT TERM

now() { date +%s; }
minutes() { chroot_minutes "$1"; }

t0=$(now)
say "debootstrap --variant=minbase into $root (log: $root.log)"
chroot_make "$suite" "$root" || exit 77
chroot_mount "$root"
git clone -q "$checkout" "$root/root/shaderlab" || { say "cannot clone $checkout"; exit 2; }
say "fresh $suite ready in $(minutes $(($(now) - t0)))"

# The README's two commands: the first two lines of its first ```sh block.
mapfile -t commands < <(awk '/^```sh/ {block++; next} /^```/ {if (block == 1) exit} block == 1' README.md | head -n 2)
((${#commands[@]} == 2)) || { say "README.md does not start with two commands"; exit 2; }

status=0
results=()
for n in 1 2; do
  [ -z "$only" ] || [ "$only" = "$n" ] || continue
  cmd=${commands[n - 1]}
  say "command $n: $cmd"
  t=$(now)
  # 40 minutes at most a command: a hang ends as a failure, not as a CI run that never finishes.
  chroot_run --timeout 2400 "$root" "cd /root/shaderlab && $cmd" >"$root.command$n.log" 2>&1
  rc=$?
  took=$(minutes $(($(now) - t)))
  summary=$(grep -E "tests passed|score|worst correct|verdicts" "$root.command$n.log" | tail -n 3 | tr '\n' ';')
  if ((rc == 0)); then
    results+=("command $n passed in $took ($summary)")
  else
    results+=("command $n FAILED (exit $rc) after $took; log: $root.command$n.log")
    tail -n 40 "$root.command$n.log"
    status=1
  fi
done
say "Mesa: $(chroot "$root" dpkg-query -W -f='${Version}' libgl1-mesa-dri 2>/dev/null), GCC: $(chroot "$root" gcc -dumpfullversion 2>/dev/null)"
for r in "${results[@]}"; do say "$r"; done
say "total $(minutes $(($(now) - t0)))"
exit $status
