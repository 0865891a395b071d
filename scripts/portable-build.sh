#!/usr/bin/env bash
# Builds the portable `shaderlab`: grader-only (no window; `serve` kept), one file that runs on any
# x86-64 Linux with glibc 2.31 or later and Mesa (Debian 11 to 13, Ubuntu 20.04 to 24.04, WSL2).
# It builds on Debian 11, because a program linked against the oldest glibc it supports runs on
# every newer one:
#   - Debian 11's GCC 10, CMake 3.18, glad 1 and static libraries (.a): libpng, zlib, libarchive
#     and what it needs, xxhash, draco, stb; libstdc++ and libgcc linked in (cmake/Portable.cmake);
#   - the header-only packages Debian 11 lacks or has too old (nlohmann-json3-dev, libcli11-dev,
#     libvalijson-dev) from Debian 12, architecture `all` only, unpacked beside the build;
#   - cpp-httplib's single header from Debian 12's source package (Debian ships no header-only
#     httplib: its binary package is a compiled library, and Debian 11 has none);
#   - Mesa is not linked: shaderlab opens libOSMesa or libEGL when it renders.
# Then it checks what the binary asks of the system (glibc's libraries only, no symbol newer than
# GLIBC_2.31) and strips it into OUT/shaderlab. The proof on other systems: portable-check.sh.
#
# Usage: sudo bash scripts/portable-build.sh OUT [--chroot DIR]
#          in a Debian 11 chroot (debootstrap; scripts/chroot-lib.sh) holding this working tree
#          --chroot DIR  the chroot: made there on first use and kept for the next build
#                        (incremental, with ccache); default: a fresh one, removed afterwards
#        bash scripts/portable-build.sh --here OUT
#          on this system, which must be Debian 11, as root (what the chroot runs; the
#          Dockerfile's `portable` stage too)
# Exit 0 built, 1 the build or a check failed, 2 bad arguments, 77 skipped (not root, no archive).
set -uo pipefail
cd "$(dirname "$0")/.."
checkout=$(pwd)

out=""
root=""
here=0
while (($#)); do
  case "$1" in
    --chroot) root=${2:-}; shift ;;
    --here) here=1 ;;
    -*) echo "portable-build: unknown option $1" >&2; exit 2 ;;
    *) [ -z "$out" ] || { echo "portable-build: one OUT folder only" >&2; exit 2; }; out=$1 ;;
  esac
  shift
done
[ -n "$out" ] || { echo "usage: sudo bash scripts/portable-build.sh OUT [--chroot DIR] | --here OUT" >&2; exit 2; }
mkdir -p "$out" && out=$(cd "$out" && pwd) || { echo "portable-build: cannot make $out" >&2; exit 2; }
say() { echo "portable-build: $*"; }
now() { date +%s; }
minutes() { awk -v s="$1" 'BEGIN { printf "%d min %02d s", s / 60, s % 60 }'; }

# ---- on Debian 11 itself ---------------------------------------------------------------------
build_here() {
  local t0 mirror
  t0=$(now)
  case $(cat /etc/debian_version 2>/dev/null) in
    11.*) ;;
    *) say "--here builds on Debian 11 only (this is $(cat /etc/debian_version 2>/dev/null || echo 'not Debian')): the binary would need this system's newer glibc"; exit 2 ;;
  esac
  [ "$(id -u)" -eq 0 ] || { say "--here installs packages: run it as root"; exit 2; }
  mirror=$(awk '$1 == "deb" && $0 !~ /security/ {print $2; exit}' /etc/apt/sources.list 2>/dev/null)
  [ -n "$mirror" ] || mirror=http://deb.debian.org/debian
  export DEBIAN_FRONTEND=noninteractive

  # Debian 11's tools and static libraries. libarchive.a needs the archives of what it was built
  # with (pkg-config --static libarchive); python3-pkg-resources: glad 1 imports it but does not
  # depend on it.
  local packages=(
    build-essential cmake pkg-config ccache binutils xz-utils ca-certificates
    python3-glad python3-pkg-resources libegl-dev
    libglm-dev libstb-dev libpng-dev zlib1g-dev libdraco-dev libtinygltf-dev libxxhash-dev
    libarchive-dev nettle-dev libacl1-dev liblzma-dev libzstd-dev liblz4-dev libbz2-dev libxml2-dev libicu-dev
  )
  say "installing Debian 11's compiler and libraries"
  { apt-get update -qq && apt-get install -y -qq --no-install-recommends "${packages[@]}" >/dev/null; } ||
    { say "apt-get install failed"; exit 1; }

  # Debian 12's header-only packages and cpp-httplib's source, through a second apt configuration
  # (its own lists and cache) so that the system's own apt stays Debian 11's.
  say "unpacking Debian 12's header-only packages into /opt/shaderlab-deps"
  local a=/opt/bookworm-apt deps=/opt/shaderlab-deps
  mkdir -p $a/lists/partial $a/cache/archives/partial $deps/usr/include/cpp-httplib-header-only
  printf 'deb %s bookworm main\ndeb-src %s bookworm main\n' "$mirror" "$mirror" >$a/sources.list
  apt_bookworm() {
    apt-get -qq -o Dir::Etc::SourceList=$a/sources.list -o Dir::Etc::SourceParts=/nonexistent \
      -o Dir::State::Lists=$a/lists -o Dir::Cache=$a/cache -o APT::Sandbox::User=root "$@"
  }
  (
    set -euo pipefail
    cd $a
    rm -f ./*.deb ./*.dsc ./*.tar.*
    apt_bookworm update
    apt_bookworm download nlohmann-json3-dev libcli11-dev libvalijson-dev
    for deb in ./*.deb; do
      arch=$(dpkg-deb -f "$deb" Architecture)
      [ "$arch" = all ] || { echo "$deb is built for $arch, not architecture-independent" >&2; exit 1; }
      dpkg-deb -x "$deb" $deps
      echo "  $(dpkg-deb -f "$deb" Package) $(dpkg-deb -f "$deb" Version) (all)"
    done
    apt_bookworm source --download-only cpp-httplib >/dev/null
    orig=$(ls ./cpp-httplib_*.orig.tar.*)
    header=$(tar -tf "$orig" | grep '/httplib.h$' | awk -F/ '{print NF, $0}' | sort -n | head -n1 | cut -d' ' -f2)
    tar -xf "$orig" -O "$header" >$deps/usr/include/cpp-httplib-header-only/httplib.h
    version=$(grep -m1 -o 'CPPHTTPLIB_VERSION "[0-9.]*"' $deps/usr/include/cpp-httplib-header-only/httplib.h | tr -d '"' | awk '{print $2}')
    echo "  cpp-httplib $version (its single httplib.h, from the source ${orig#./})"
  ) || { say "could not take Debian 12's header-only packages"; exit 1; }

  local t_build build=${SHADERLAB_PORTABLE_BUILD_DIR:-/var/tmp/shaderlab-portable-build}
  t_build=$(now)
  say "building (grader-only, SHADERLAB_PORTABLE) in $build with $(nproc) jobs"
  export CCACHE_DIR=${CCACHE_DIR:-/root/.ccache} CCACHE_MAXSIZE=${CCACHE_MAXSIZE:-5G}
  rm -f "$build/framework/shaderlab"  # a failed build must not leave the last one to be checked
  cmake -S "$checkout" -B "$build" -DSHADERLAB_PORTABLE=ON -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_PREFIX_PATH=$deps/usr -DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache >/dev/null &&
    cmake --build "$build" -j"$(nproc)" --target shaderlab | grep -Ev '^\[ *[0-9]+%\]'
  [ -x "$build/framework/shaderlab" ] || { say "the build failed"; exit 1; }
  local t_built
  t_built=$(now)

  # What the binary asks of the system it runs on.
  local bin=$build/framework/shaderlab status=0 needed newest lib
  needed=$(objdump -p "$bin" | awk '$1 == "NEEDED" {print $2}' | sort | tr '\n' ' ')
  for lib in $needed; do
    case $lib in
      libc.so.6 | libm.so.6 | libdl.so.2 | libpthread.so.0 | librt.so.1 | ld-linux-x86-64.so.2) ;;
      *) say "FAILED: needs $lib, which is not glibc's"; status=1 ;;
    esac
  done
  newest=$(objdump -T "$bin" | grep -o 'GLIBC_[0-9.]*' | sort -u -V | tail -n1)
  if [ "$(printf '%s\nGLIBC_2.31\n' "$newest" | sort -V | tail -n1)" != GLIBC_2.31 ]; then
    say "FAILED: needs $newest, newer than GLIBC_2.31"
    status=1
  fi
  if objdump -T "$bin" | grep -qE 'GLIBCXX_|CXXABI_|GCC_[0-9]'; then
    say "FAILED: links libstdc++ or libgcc_s dynamically"
    status=1
  fi
  strip -o "$out/shaderlab" "$bin" && chmod 755 "$out/shaderlab" || { say "cannot write $out/shaderlab"; exit 1; }
  say "wrote $out/shaderlab: $(stat -c %s "$out/shaderlab" | awk '{printf "%.1f MiB", $1 / 1048576}') stripped"
  say "needs (NEEDED): $needed"
  say "newest glibc symbol: $newest (of $(objdump -T "$bin" | grep -c 'GLIBC_') symbols from glibc)"
  say "built with GCC $(gcc -dumpfullversion), glibc $(ldd --version | head -n1 | grep -o '[0-9.]*$') (Debian $(cat /etc/debian_version))"
  say "packages $(minutes $((t_build - t0))), build $(minutes $((t_built - t_build)))"
  exit $status
}
((here)) && build_here

# ---- from any Linux, in a Debian 11 chroot ---------------------------------------------------
. scripts/chroot-lib.sh
chroot_prepare
fresh=0
if [ -z "$root" ]; then
  root=$(mktemp -d /var/tmp/shaderlab-portable.XXXXXX)
  fresh=1
fi
cleanup() {
  chroot_unmount_all
  if ((fresh)); then rm -rf --one-file-system "$root" "$root.log"; fi
}
trap cleanup EXIT
trap 'exit 130' INT TERM
t0=$(now)
if [ ! -x "$root/usr/bin/apt-get" ]; then
  mkdir -p "$root"
  say "debootstrap --variant=minbase bullseye into $root"
  chroot_make bullseye "$root" || exit 77
  say "fresh Debian 11 in $(minutes $(($(now) - t0)))"
fi
chroot_mount "$root"

# The sources as they are in this working tree (tracked files and new ones git does not ignore),
# with their times kept, so that a kept chroot rebuilds only what changed.
rm -rf "$root/root/shaderlab" "$root/root/out"
mkdir -p "$root/root/shaderlab"
git ls-files -z -co --exclude-standard | tar --null -T - -cf - | tar -xf - -C "$root/root/shaderlab" ||
  { say "cannot copy the sources"; exit 2; }
chroot_run "$root" "bash /root/shaderlab/scripts/portable-build.sh --here /root/out"
rc=$?
if [ -f "$root/root/out/shaderlab" ]; then
  cp "$root/root/out/shaderlab" "$out/shaderlab" && say "copied to $out/shaderlab"
fi
say "total $(minutes $(($(now) - t0)))"
exit $rc
