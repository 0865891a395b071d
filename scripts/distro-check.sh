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
if [ "$(id -u)" -ne 0 ]; then
  say "skipped: needs root (debootstrap and chroot)"
  exit 77
fi

# The mirror this machine's apt uses (deb822 .sources first, then sources.list).
mirror=$(sed -n 's/^URIs:[[:space:]]*//p' /etc/apt/sources.list.d/*.sources 2>/dev/null | grep -v security | head -n1)
[ -n "$mirror" ] || mirror=$(awk '$1 == "deb" && $0 !~ /security/ {print $2; exit}' /etc/apt/sources.list 2>/dev/null)
[ -n "$mirror" ] || { say "skipped: no Debian mirror found in this machine's apt sources"; exit 77; }
if ! timeout 20 bash -c "exec 3<>/dev/tcp/$(echo "$mirror" | sed -E 's#^[a-z]+://([^/:]+).*#\1#')/80" 2>/dev/null; then
  say "skipped: Debian's archive cannot be reached from here"
  exit 77
fi
if ! command -v debootstrap >/dev/null; then
  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq debootstrap >/dev/null ||
    { say "could not install debootstrap"; exit 2; }
fi

base=${DISTRO_CHECK_DIR:-/var/tmp}
root=$(mktemp -d "$base/shaderlab-$suite.XXXXXX")
log=$root.log
mounted=()
cleanup() {
  for ((i = ${#mounted[@]} - 1; i >= 0; i--)); do umount -l "${mounted[i]}" 2>/dev/null; done
  if ((keep)); then say "chroot kept in $root"; else rm -rf --one-file-system "$root"; fi
}
trap cleanup EXIT
trap 'exit 130' INT TERM

now() { date +%s; }
minutes() { awk -v s="$1" 'BEGIN { printf "%d min %02d s", s / 60, s % 60 }'; }

t0=$(now)
say "debootstrap --variant=minbase into $root (log: $log)"
if ! debootstrap --variant=minbase "$suite" "$root" "$mirror" >"$log" 2>&1; then
  say "skipped: debootstrap failed (the archive, the network or this machine); the end of its log:"
  tail -n 20 "$log"
  exit 77
fi
for m in proc sys dev dev/pts; do
  mkdir -p "$root/$m"
  case $m in
    proc) mount -t proc proc "$root/proc" ;;
    sys) mount -t sysfs sys "$root/sys" ;;
    *) mount --bind "/$m" "$root/$m" ;;
  esac && mounted+=("$root/$m")
done
mkdir -p "$root/dev/shm" && mount -t tmpfs shm "$root/dev/shm" && mounted+=("$root/dev/shm")
cp /etc/resolv.conf "$root/etc/resolv.conf" 2>/dev/null
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
  timeout --kill-after=30 2400 chroot "$root" /usr/bin/env -i HOME=/root PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
    LANG=C.UTF-8 bash -c "cd /root/shaderlab && $cmd" >"$root.command$n.log" 2>&1
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
