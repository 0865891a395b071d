# Fresh Debian chroots without a container engine, for the scripts that try shaderlab on a
# distribution other than this machine's (distro-check.sh, portable-build.sh, portable-check.sh).
# Sourced, not run: the caller defines say() (one line to the terminal) and calls
#   chroot_prepare            root, Debian's archive reachable, debootstrap installed (exit 77 if not)
#   chroot_make SUITE DIR     debootstrap --variant=minbase SUITE into DIR (its log in DIR.log)
#   chroot_mount DIR          /proc, /sys, /dev, /dev/pts and a /dev/shm the way a build needs them
#   chroot_run [--timeout S] DIR COMMAND
#                             COMMAND (bash -c) inside DIR with a clean environment, as root
#   chroot_unmount_all        what chroot_mount mounted, the last first (call it from an EXIT trap)
# CHROOT_MIRROR holds the mirror after chroot_prepare: the one this machine's apt uses.

CHROOT_MOUNTED=()
CHROOT_MIRROR=""

chroot_prepare() {
  if [ "$(id -u)" -ne 0 ]; then
    say "skipped: needs root (debootstrap and chroot)"
    exit 77
  fi
  # The mirror this machine's apt uses (deb822 .sources first, then sources.list).
  CHROOT_MIRROR=$(sed -n 's/^URIs:[[:space:]]*//p' /etc/apt/sources.list.d/*.sources 2>/dev/null | grep -v security | head -n1)
  [ -n "$CHROOT_MIRROR" ] || CHROOT_MIRROR=$(awk '$1 == "deb" && $0 !~ /security/ {print $2; exit}' /etc/apt/sources.list 2>/dev/null)
  [ -n "$CHROOT_MIRROR" ] || { say "skipped: no Debian mirror found in this machine's apt sources"; exit 77; }
  local host
  host=$(echo "$CHROOT_MIRROR" | sed -E 's#^[a-z]+://([^/:]+).*#\1#')
  if ! timeout 20 bash -c "exec 3<>/dev/tcp/$host/80" 2>/dev/null; then
    say "skipped: Debian's archive cannot be reached from here"
    exit 77
  fi
  if ! command -v debootstrap >/dev/null; then
    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq debootstrap >/dev/null ||
      { say "could not install debootstrap"; exit 2; }
  fi
}

# chroot_make SUITE DIR: a minimal Debian (what `debootstrap --variant=minbase` installs: no
# compiler, no Mesa). Returns 1, with the end of the log printed, when debootstrap fails.
chroot_make() {
  local suite=$1 dir=$2
  if ! debootstrap --variant=minbase "$suite" "$dir" "$CHROOT_MIRROR" >"$dir.log" 2>&1; then
    say "debootstrap $suite failed (the archive, the network or this machine); the end of $dir.log:"
    tail -n 20 "$dir.log"
    return 1
  fi
  cp /etc/resolv.conf "$dir/etc/resolv.conf" 2>/dev/null
  return 0
}

chroot_mount() {
  local dir=$1 m
  for m in proc sys dev dev/pts; do
    mountpoint -q "$dir/$m" && continue
    mkdir -p "$dir/$m"
    case $m in
      proc) mount -t proc proc "$dir/proc" ;;
      sys) mount -t sysfs sys "$dir/sys" ;;
      *) mount --bind "/$m" "$dir/$m" ;;
    esac && CHROOT_MOUNTED+=("$dir/$m")
  done
  # Mesa and the grader's render children share memory through /dev/shm: a chroot's own, not the host's.
  mkdir -p "$dir/dev/shm"
  mountpoint -q "$dir/dev/shm" || { mount -t tmpfs shm "$dir/dev/shm" && CHROOT_MOUNTED+=("$dir/dev/shm"); }
}

chroot_unmount_all() {
  local i
  for ((i = ${#CHROOT_MOUNTED[@]} - 1; i >= 0; i--)); do umount -l "${CHROOT_MOUNTED[i]}" 2>/dev/null; done
  CHROOT_MOUNTED=()
}

chroot_run() {
  local limit=()
  if [ "$1" = "--timeout" ]; then
    # A hang ends as a failure, not as a run that never finishes.
    limit=(timeout --kill-after=30 "$2")
    shift 2
  fi
  local dir=$1
  shift
  "${limit[@]}" chroot "$dir" /usr/bin/env -i HOME=/root PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
    LANG=C.UTF-8 DEBIAN_FRONTEND=noninteractive bash -c "$*"
}

# chroot_minutes SECONDS: "3 min 07 s".
chroot_minutes() { awk -v s="$1" 'BEGIN { printf "%d min %02d s", s / 60, s % 60 }'; }
